#include "stickslip/model/oscillator_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "stickslip/error.hpp"

namespace stickslip {
namespace {

void require_positive(const char* name, double value) {
  if (!std::isfinite(value) || !(value > 0.0))
    throw invalid_parameter(name, value, "a finite number > 0");
}

void require_scale(const char* name, double value) {
  if (!(value >= min_magnitude && value <= max_magnitude))
    throw invalid_parameter(name, value, "a derived scale within [1e-60, 1e60]");
}

std::string level_name(std::size_t i) { return "belt level v" + std::to_string(i + 1); }
std::string rate_name(std::size_t i, std::size_t j) {
  return "belt rate q" + std::to_string(i + 1) + "," + std::to_string(j + 1);
}

}  // namespace

markov_belt two_level_belt(double v1, double v2, double rate_from_first,
                           double rate_from_second) {
  return markov_belt{{v1, v2},
                     {-rate_from_first, rate_from_first, rate_from_second, -rate_from_second}};
}

void validate(const markov_belt& belt) {
  const std::size_t n = belt.levels.size();
  if (n < 2)
    throw invalid_parameter("belt levels (count)", static_cast<double>(n), "at least 2 levels");
  for (std::size_t i = 0; i < n; ++i) {
    const double v = belt.levels[i];
    if (!std::isfinite(v) || std::abs(v) > max_magnitude)
      throw invalid_parameter(level_name(i), v, "a finite number with |value| <= 1e60");
    for (std::size_t j = 0; j < i; ++j)
      if (belt.levels[j] == v)
        throw invalid_parameter(level_name(i), v,
                                "distinct from every other level (equals " + level_name(j) + ")");
  }
  if (belt.generator.size() != n * n)
    throw invalid_parameter("belt generator (entries)", static_cast<double>(belt.generator.size()),
                            "exactly n x n = " + std::to_string(n * n) + " rates");
  for (std::size_t i = 0; i < n; ++i) {
    double off_sum = 0.0, largest = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i) continue;
      const double q = belt.rate(i, j);
      if (!std::isfinite(q) || q < 0.0 || q > max_magnitude)
        throw invalid_parameter(rate_name(i, j), q, "a finite rate >= 0 and <= 1e60");
      off_sum += q;
      largest = std::max(largest, q);
    }
    if (!(off_sum > 0.0))
      throw invalid_parameter("belt rate of leaving " + level_name(i), off_sum,
                              "a finite rate > 0 (every level must be left)");
    const double diagonal = belt.rate(i, i);
    if (!std::isfinite(diagonal))
      throw invalid_parameter(rate_name(i, i), diagonal, "finite (minus the row's other rates)");
    const double row_sum = off_sum + diagonal;
    if (std::abs(row_sum) > 1e-12 * std::max(largest, std::abs(diagonal)))
      throw invalid_parameter("belt generator row " + std::to_string(i + 1) + " sum", row_sum,
                              "0 (q" + std::to_string(i + 1) + "," + std::to_string(i + 1) +
                                  " = -sum of the other rates in its row)");
  }
}

void validate(const oscillator_model& m) {
  require_positive("m", m.mass);
  require_positive("k", m.stiffness);
  require_positive("g", m.gravity);
  require_positive("ta", m.window);
  if (!std::isfinite(m.damping) || m.damping < 0.0)
    throw invalid_parameter("c (damping)", m.damping, "a finite number >= 0");
  require_positive("mu_k (kinetic friction)", m.kinetic_friction);
  if (!std::isfinite(m.static_friction) || m.static_friction < m.kinetic_friction)
    throw invalid_parameter("mu_s (static friction)", m.static_friction,
                            ">= mu_k = " + std::to_string(m.kinetic_friction) +
                                " (mu_k > mu_s is not allowed)");
  for (double v : {m.mass, m.stiffness, m.gravity, m.window, m.kinetic_friction})
    require_scale("model parameter", v);
  validate(m.belt);
  require_scale("a_k = mu_k m g / k", m.kinetic_offset());
  require_scale("a_s = mu_s m g / k", m.static_band_half_width());
  require_scale("omega_0 = sqrt(k/m)", m.natural_frequency());
  const double band_speed = m.natural_frequency() * m.static_band_half_width();
  for (std::size_t i = 0; i < m.belt.levels.size(); ++i) {
    const double v = m.belt.levels[i];
    if (v == 0.0 || band_speed <= max_band_to_belt_ratio * std::abs(v)) continue;
    throw invalid_parameter(
        fmt::format("belt level v{} (V for the paper's belt)", i + 1), v,
        fmt::format("0 or |value| >= omega_0 a_s / 1e12 = {:.6g} m/s (omega_0 = sqrt(k/m) = "
                    "{:.6g}, a_s = mu_s m g / k = {:.6g}): a slower belt makes slips shorter "
                    "than the resolution of t",
                    band_speed / max_band_to_belt_ratio, m.natural_frequency(),
                    m.static_band_half_width()));
  }
  if (m.damping > 0.0) {
    require_scale("c", m.damping);
    require_scale("gamma = c / (2 m)", m.decay_rate());
    // The damped engine isolates a slip's return to x' = v half-period by
    // half-period (damped_slip.hpp), at most about omega_0 t_a / pi of them
    // over the window: more than 1e6 radians would take that many steps (a
    // fuzzer found k ~ 1e49, m = 50: a hang). Users' models are far below
    // (k = 80, m = 1, t_a = 1e4: 9e4 rad).
    if (m.natural_frequency() * m.window > 1e6)
      throw invalid_parameter(
          "k (stiffness)", m.stiffness,
          fmt::format("with damping c > 0, sqrt(k/m) t_a <= 1e6, i.e. k <= {:.6g} for m = {:.6g} "
                      "and t_a = {:.6g} (the damped engine visits every half-period of a slip)",
                      1e12 * m.mass / (m.window * m.window), m.mass, m.window));
    // An over-damped slip relaxes on the time scale 1 / (2 gamma): beyond
    // gamma t_a = 1e12 its return to x' = v can fall below the resolution of
    // t (fuzz_model_family found c = 9.7e15, m = 0.078, t_a = 0.52: a return
    // 1.5e-16 s after the start, which the certified search could not
    // isolate in a 0.26-s bracket). Users' models are far below (c / m =
    // 1e3, t_a = 1e4: 5e6).
    if (m.decay_rate() * m.window > max_decay_periods)
      throw invalid_parameter(
          "c (damping)", m.damping,
          fmt::format("gamma t_a = c t_a / (2 m) <= 1e12, i.e. c <= {:.6g} for m = {:.6g} and "
                      "t_a = {:.6g} (faster relaxation falls below the resolution of t)",
                      2.0 * m.mass * max_decay_periods / m.window, m.mass, m.window));
  }
}

namespace {

// Solves x A = b^T for the row vector x, with A = Q whose last column is
// replaced by (1, ..., 1): the system of pi Q = 0 (or its derivative) with
// the normalisation sum x = b[n-1] in place of the last equation. Gaussian
// elimination with partial pivoting on A^T.
std::vector<double> solve_with_normalisation(const markov_belt& belt, std::vector<double> b) {
  const std::size_t n = belt.levels.size();
  std::vector<double> a(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) a[i * n + j] = i + 1 == n ? 1.0 : belt.rate(j, i);
  for (std::size_t col = 0; col < n; ++col) {
    std::size_t pivot = col;
    for (std::size_t r = col + 1; r < n; ++r)
      if (std::abs(a[r * n + col]) > std::abs(a[pivot * n + col])) pivot = r;
    if (pivot != col) {
      for (std::size_t j = 0; j < n; ++j) std::swap(a[col * n + j], a[pivot * n + j]);
      std::swap(b[col], b[pivot]);
    }
    for (std::size_t r = col + 1; r < n; ++r) {
      const double f = a[r * n + col] / a[col * n + col];
      for (std::size_t j = col; j < n; ++j) a[r * n + j] -= f * a[col * n + j];
      b[r] -= f * b[col];
    }
  }
  std::vector<double> x(n);
  for (std::size_t i = n; i-- > 0;) {
    double s = b[i];
    for (std::size_t j = i + 1; j < n; ++j) s -= a[i * n + j] * x[j];
    x[i] = s / a[i * n + i];
  }
  return x;
}

}  // namespace

std::vector<double> stationary_law(const markov_belt& belt) {
  std::vector<double> b(belt.levels.size(), 0.0);
  b.back() = 1.0;
  return solve_with_normalisation(belt, std::move(b));
}

std::vector<double> stationary_law_derivative(const markov_belt& belt, std::size_t i,
                                              std::size_t j) {
  // d(pi Q) = dpi Q + pi dQ = 0 with dQ = e_i (e_j - e_i)^T, and sum dpi = 0.
  const std::vector<double> pi = stationary_law(belt);
  std::vector<double> b(belt.levels.size(), 0.0);
  b[j] -= pi[i];
  b[i] += pi[i];
  b.back() = 0.0;  // the normalisation's row: sum dpi = 0
  return solve_with_normalisation(belt, std::move(b));
}

void validate(const model_initial_state& state, const markov_belt& belt) {
  if (!std::isfinite(state.position) || std::abs(state.position) > max_magnitude)
    throw invalid_parameter("x0 (initial position)", state.position,
                            "a finite number with |value| <= 1e60");
  if (!std::isfinite(state.velocity) || std::abs(state.velocity) > max_magnitude)
    throw invalid_parameter("xdot0 (initial velocity)", state.velocity,
                            "a finite number with |value| <= 1e60");
  if (state.level >= belt.level_count())
    throw invalid_parameter("belt-start (level index)", static_cast<double>(state.level),
                            "an existing level index, 0.." + std::to_string(belt.level_count() - 1));
}

}  // namespace stickslip
