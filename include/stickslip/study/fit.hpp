// The method of stickslip 0.1.0 for the maximum of mean R over lambda: a
// weighted quadratic in ln lambda with a parametric bootstrap. The study
// locates the maximum with `stickslip peak` (precision/peak_sweep.hpp:
// common random numbers, local cubic and quartic fits in a shrinking window,
// an interval that counts sampling error and local-model bias;
// docs/precision.md); it still runs this fit, on its own sweep, so that the
// report can show what changed and why.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace stickslip::study {

// Weighted least-squares fit of R = b0 + b1 u + b2 u^2, u = ln(lambda/center),
// weights 1/se_i^2, to the mean R of independent points
// (precision::fit_polynomial). With b2 < 0:
//   u* = -b1/(2 b2),  lambda* = center e^u*,  R* = b0 - b1^2/(4 b2).
// Delta-method standard errors come from cov(b) = (X^T W X)^-1; the 95 %
// intervals come from a parametric bootstrap: each point's mean is redrawn
// from N(mean_i, se_i^2) (independent, since each lambda has its own Philox
// key; normal by the CLT) and refitted, and the 2.5 and 97.5 percentiles of
// lambda* and R* are taken. Draws without a maximum (b2 >= 0) are counted
// and left out. The bootstrap streams are Philox with key {seed, tag}, so
// the intervals are reproducible.
struct peak_estimate {
  bool valid = false;         // b2 < 0 and enough points
  double center = 0;          // lambda the fit is expanded around
  double b0 = 0, b1 = 0, b2 = 0;
  double lambda_star = 0, lambda_lo = 0, lambda_hi = 0;  // bootstrap 95 %
  double R_star = 0, R_lo = 0, R_hi = 0;                 // bootstrap 95 %
  double lambda_se_delta = 0, R_se_delta = 0;            // delta method
  double chi2 = 0;            // weighted residual sum of squares
  std::size_t dof = 0;        // points - 3
  bool interior = false;      // lambda* inside the fitted lambda range
  std::size_t bootstrap = 0, bootstrap_degenerate = 0;
};

// The 95 % point of the chi^2 distribution with `dof` degrees of freedom.
[[nodiscard]] double chi2_95(std::size_t dof);
// A refinement fit whose chi^2 is above its 95 % point: the quadratic in
// ln lambda does not describe mean R over the window; the report flags it.
[[nodiscard]] bool poor_fit(const peak_estimate& p);

[[nodiscard]] peak_estimate fit_peak(const std::vector<double>& lambda,
                                     const std::vector<double>& mean,
                                     const std::vector<double>& std_error, double center,
                                     std::uint64_t seed, std::uint64_t stream_tag,
                                     std::size_t bootstrap = 2000);

}  // namespace stickslip::study
