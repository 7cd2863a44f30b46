// Weighted least-squares polynomial fits of noisy point estimates, and the
// maximizer of the fitted polynomial with its delta-method standard error.
// Used by the peak finder (peak_finder.hpp); no I/O.
#pragma once
#include <cstddef>
#include <vector>

namespace stickslip::precision {

// One noisy evaluation of a mean: a point, the estimated mean there and its
// standard error (the sweep's mean and std_error of the statistic).
struct evaluation {
  double x = 0.0;
  double mean = 0.0;
  double std_error = 0.0;
};

// p(t) = sum_j coef[j] t^j with t = (x - center) / scale, fitted by weighted
// least squares (weights 1 / std_error^2).
struct polynomial_fit {
  double center = 0.0;
  double scale = 1.0;
  std::vector<double> coef;                     // degree + 1 values
  std::vector<std::vector<double>> covariance;  // of coef
  double chi2 = 0.0;                            // weighted residual sum of squares
  std::size_t dof = 0;                          // points - (degree + 1)
  [[nodiscard]] double value(double t) const noexcept;
  [[nodiscard]] double derivative(double t) const noexcept;
  [[nodiscard]] double second_derivative(double t) const noexcept;
  // Standard error of value(t) (from the covariance; t treated as fixed).
  [[nodiscard]] double value_std_error(double t) const noexcept;
};

// Throws stickslip::error when there are fewer than degree + 1 points, a
// standard error is not > 0, or the normal equations are singular.
[[nodiscard]] polynomial_fit fit_polynomial(const std::vector<evaluation>& points,
                                            std::size_t degree, double center, double scale);

// The interior maximizer of a fitted polynomial on t in [t_lo, t_hi]: the
// highest point of a dense scan refined by Newton steps on p'(t) = 0.
struct fitted_maximum {
  bool interior = false;  // false: the maximum is at an end, or p'' >= 0 there
  double t = 0.0;         // in the fit's t units
  double t_std_error = 0.0;  // delta method: dt*/dcoef_j = -j t^(j-1) / p''(t*)
};
[[nodiscard]] fitted_maximum maximize(const polynomial_fit& f, double t_lo, double t_hi);

// P(chi2_dof > x), for the goodness-of-fit test of a local model.
[[nodiscard]] double chi2_upper_tail(double x, std::size_t dof) noexcept;

}  // namespace stickslip::precision
