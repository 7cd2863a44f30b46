// The model family (derivations: docs/model.md, "The model family"):
//
//   m x'' + c x' + k x = f(t)
//   slip:  f = mu_k m g sgn(v - x')
//   stick: x' = v, held while |k x + c v| <= mu_s m g
//
// on a belt whose velocity v(t) is a continuous-time Markov chain on n >= 2
// distinct levels v_1..v_n (any sign, zero allowed) with generator Q
// (q_ij >= 0 for i != j, rows sum to 0). The paper's model is the special case
// mu_s = mu_k = mu, c = 0, levels (+V, -V), both rates lambda (model_of() of the
// paper's parameters, parameters.hpp).
//
// A value type: validate() once at the edge, then the engines trust it.
#pragma once
#include <cmath>
#include <cstddef>
#include <vector>

namespace stickslip {

// Magnitudes the closed form handles without overflow in its squares.
inline constexpr double min_magnitude = 1e-60, max_magnitude = 1e60;

// The belt: a continuous-time Markov chain on `levels` with generator
// `generator` (n x n, row-major: generator[i * n + j] = q_ij).
struct markov_belt {
  std::vector<double> levels;     // v_1..v_n [m/s], distinct
  std::vector<double> generator;  // Q, row-major; q_ii = -sum_{j != i} q_ij

  [[nodiscard]] std::size_t level_count() const noexcept { return levels.size(); }
  [[nodiscard]] double rate(std::size_t i, std::size_t j) const noexcept {
    return generator[i * levels.size() + j];
  }
  // q_i = -q_ii: the rate of leaving level i (its holding time is Exp(q_i)).
  [[nodiscard]] double leaving_rate(std::size_t i) const noexcept { return -rate(i, i); }
  friend bool operator==(const markov_belt&, const markov_belt&) = default;
};

// A two-level belt: rate_from_first = rate of leaving v1 (to v2), and back.
[[nodiscard]] markov_belt two_level_belt(double v1, double v2, double rate_from_first,
                                         double rate_from_second);

// The stationary law pi of the chain (pi Q = 0, sum pi = 1), by Gaussian
// elimination with partial pivoting on Q^T with one row replaced by the
// normalisation. Precondition: validate(belt) passed (irreducibility is not
// checked; a reducible chain gives one of its stationary laws).
[[nodiscard]] std::vector<double> stationary_law(const markov_belt& belt);
// d pi / d q_ij (i != j; q_ii = -q_i moves with it): the solution of
// dpi Q = -pi_i (e_j - e_i)^T with sum dpi = 0. Same precondition.
[[nodiscard]] std::vector<double> stationary_law_derivative(const markov_belt& belt, std::size_t i,
                                                            std::size_t j);

struct oscillator_model {
  double mass = 1.0;               // m     [kg]
  double stiffness = 4.0;          // k     [N/m]
  double damping = 0.0;            // c     [N s/m], viscous, >= 0
  double gravity = 9.81;           // g     [m/s^2]
  double static_friction = 5.0;    // mu_s  [-], >= mu_k
  double kinetic_friction = 5.0;   // mu_k  [-], > 0
  markov_belt belt = two_level_belt(1.0, -1.0, 1.0, 1.0);
  double window = 50.0;            // t_a   [s]

  // a_s = mu_s m g / k: with c = 0 the stick band is |x| <= a_s; in general
  // it is |x + c v / k| <= a_s.
  [[nodiscard]] double static_band_half_width() const noexcept {
    return static_friction * mass * gravity / stiffness;
  }
  // a_k = mu_k m g / k: the slip equilibrium is x = sigma a_k.
  [[nodiscard]] double kinetic_offset() const noexcept {
    return kinetic_friction * mass * gravity / stiffness;
  }
  // omega_0 = sqrt(k/m), gamma = c / (2 m) (decay rate), zeta = gamma / omega_0.
  [[nodiscard]] double natural_frequency() const noexcept { return std::sqrt(stiffness / mass); }
  [[nodiscard]] double decay_rate() const noexcept { return damping / (2.0 * mass); }
  [[nodiscard]] double damping_ratio() const noexcept {
    return decay_rate() / natural_frequency();
  }
  friend bool operator==(const oscillator_model&, const oscillator_model&) = default;
};

// Throws stickslip::error (exit code 2) naming the first invalid parameter,
// its value and the allowed range: m, k, g, t_a finite and > 0; c finite and
// >= 0; mu_k finite and > 0; mu_s finite and >= mu_k; the belt as below; the
// derived scales within [min_magnitude, max_magnitude] like the paper model;
// every moving belt level |v| >= omega_0 a_s / max_band_to_belt_ratio;
// with damping, sqrt(k/m) t_a <= 1e6 and gamma t_a <= max_decay_periods.
void validate(const oscillator_model& model);
// The largest omega_0 a_s / |v|: radians of the oscillation while a moving
// belt level crosses the static band. Beyond it a slip can be shorter than
// the resolution of t (|v| / (omega_0^2 a_s) below ulp(t)) and would have no
// length. The paper's studies sit near 10, a creep study at 1e-6 m/s with
// the paper's k and mu near 1e7; fuzz_model_family found such slips (and a
// missed damped return) only near 1e52.
inline constexpr double max_band_to_belt_ratio = 1e12;
// The largest gamma t_a = c t_a / (2 m) of a damped model: the slip's fastest
// relaxation time stays above 1e-12 t_a, which t resolves anywhere in the
// window.
inline constexpr double max_decay_periods = 1e12;
// n >= 2 levels, finite and pairwise distinct; Q is n x n, off-diagonal
// rates finite and >= 0, every level left at a finite rate > 0, and each row
// sums to 0 within a relative 1e-12 of its largest entry.
void validate(const markov_belt& belt);

// Initial state of one realization of the family: x0, x'0 and the index of
// the starting belt level.
struct model_initial_state {
  double position = 0.0;
  double velocity = 0.0;
  std::size_t level = 0;
};

// Throws stickslip::error: x0 and x'0 finite with |value| <= 1e60, and the
// level an index of one of the belt's levels.
void validate(const model_initial_state& state, const markov_belt& belt);

}  // namespace stickslip
