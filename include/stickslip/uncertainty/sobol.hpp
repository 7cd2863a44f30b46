// Sobol' indices of a stochastic simulator by pick-freeze (docs/uncertainty.md).
//
// The output of one realization is Y = STAT(theta, omega): theta the
// uncertain parameters, omega the realization's own randomness (initial
// conditions, belt). g(theta) = E[Y | theta] is the mean response, and
//   Var Y = Var g(theta) + E Var(Y | theta)
// splits the spread into the parameters' share and the intrinsic share.
//
// One sample row j evaluates, each with its own independent omega:
//   y_A   at theta_A,   y_A2 at theta_A again (a replicate),
//   y_B   at theta_B,   y_E[i] at theta_A with input i taken from theta_B.
// Estimators (Saltelli 2010 first order, Jansen 1999 total; the intrinsic
// noise drops out of the products of independent draws):
//   V     = Var Y                                 (from y_A and y_B)
//   s2    = E Var(Y|theta) = mean((y_A - y_A2)^2) / 2
//   V_i   = mean(y_B (y_E[i] - y_A))  -> Var E[Y | theta_i]
//   VT_i  = mean((y_A - y_E[i])^2) / 2 - s2  -> E Var(g | theta_~i)
//   first order of g      S_i  = V_i / (V - s2)
//   total order of g      T_i  = VT_i / (V - s2)
//   first order in Y      S_i^Y = V_i / V
//   shares                (V - s2) / V and s2 / V
// None of these depends on how random numbers are coupled across rows.
// Each is a smooth function of the means of a row vector z_j; its 95 %
// interval is the delta method's (CLT) with the sample covariance of z.
// Estimates are never clipped: a negative one is reported with its interval.
//
// The accumulator holds the means and co-moments of z (dimension 5 + 2d):
// memory O(d^2), never O(rows); merging two is exact up to rounding and,
// done in a fixed order, gives the same bits for any threads or ranks.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace stickslip {

class sobol_moments {
 public:
  sobol_moments() = default;
  explicit sobol_moments(std::size_t inputs);
  // One row. Precondition: y_e.size() == inputs().
  void add(double y_a, double y_a2, double y_b, std::span<const double> y_e);
  // Chan-Golub-LeVeque merge. Precondition: same inputs().
  sobol_moments& operator+=(const sobol_moments& o);

  [[nodiscard]] std::size_t inputs() const noexcept { return inputs_; }
  [[nodiscard]] std::uint64_t rows() const noexcept { return rows_; }
  // The state, for serialization: the means of z and its co-moments
  // sum (z - mean)(z - mean)^T (upper triangle, row-major).
  [[nodiscard]] const std::vector<double>& means() const noexcept { return mean_; }
  [[nodiscard]] const std::vector<double>& comoments() const noexcept { return comoment_; }
  [[nodiscard]] static sobol_moments from_state(std::size_t inputs, std::uint64_t rows,
                                                std::vector<double> means,
                                                std::vector<double> comoments);
  friend bool operator==(const sobol_moments&, const sobol_moments&) = default;

 private:
  std::size_t inputs_ = 0;
  std::uint64_t rows_ = 0;
  std::vector<double> mean_, comoment_;
};

struct interval_estimate {
  double value = 0.0;
  double low = 0.0, high = 0.0;  // the 95 % interval
  [[nodiscard]] double half_width() const noexcept { return 0.5 * (high - low); }
  friend bool operator==(const interval_estimate&, const interval_estimate&) = default;
};

struct sobol_estimates {
  std::uint64_t rows = 0;
  double mean = 0.0;                 // E Y
  double variance = 0.0;             // Var Y
  double intrinsic_variance = 0.0;   // E Var(Y | theta)
  std::vector<interval_estimate> first_order;           // S_i of g
  std::vector<interval_estimate> total_order;           // T_i of g
  std::vector<interval_estimate> response_first_order;  // Var E[Y|theta_i] / Var Y
  interval_estimate parameter_share, intrinsic_share;
  // The largest half-width of every index and share (the stop rule of
  // --target-halfwidth).
  [[nodiscard]] double max_half_width() const noexcept;
};

// The estimates and their 95 % intervals. With fewer than 2 rows, or a zero
// variance, every value is NaN.
[[nodiscard]] sobol_estimates sobol_indices(const sobol_moments& m);

}  // namespace stickslip
