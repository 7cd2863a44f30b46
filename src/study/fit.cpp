// Locating the maximum of mean R in lambda: a weighted quadratic fit in
// u = ln(lambda / center) (precision::fit_polynomial) with delta-method errors
// and a parametric bootstrap.
// The math is written out in include/stickslip/study/fit.hpp.
#include <Random123/philox.h>
#include <Random123/uniform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>

#include "stickslip/study/fit.hpp"
#include "stickslip/accumulators/mean_variance.hpp"  // z95
#include "stickslip/error.hpp"
#include "stickslip/precision/local_fit.hpp"

namespace stickslip::study {

namespace {

using precision::evaluation;
using precision::polynomial_fit;

// g^T C g for a gradient g of the three coefficients and their covariance C.
double quadratic_form(const std::array<double, 3>& g, const polynomial_fit& f) {
  double s = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) s += g[r] * f.covariance[r][c] * g[c];
  return s;
}

// The fit in u with center 0 and scale 1, or nothing when the points do not
// determine it (fit_polynomial throws for a singular normal matrix or a
// mean that is not finite).
std::optional<polynomial_fit> fit_quadratic(const std::vector<evaluation>& points) {
  try {
    return precision::fit_polynomial(points, 2, 0.0, 1.0);
  } catch (const error&) {
    return std::nullopt;
  }
}

// Standard normal pairs by Box-Muller from Philox words (key {seed, tag},
// counter {draw, 0, 0, 0}): reproducible on every platform, unlike
// std::normal_distribution.
class normal_stream {
 public:
  normal_stream(std::uint64_t seed, std::uint64_t tag) : key_{{seed, tag}} {}
  double next() {
    if (have_) {
      have_ = false;
      return spare_;
    }
    const auto w = r123::Philox4x64{}(ctr_, key_);
    ++ctr_.v[0];
    const double u1 = r123::u01fixedpt<double>(w.v[0]);  // (0, 1): log is safe
    const double u2 = r123::u01fixedpt<double>(w.v[1]);
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
    have_ = true;
    return r * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  r123::Philox4x64::key_type key_;
  r123::Philox4x64::ctr_type ctr_{{0, 0, 0, 0}};
  double spare_ = 0;
  bool have_ = false;
};

double percentile(std::vector<double> v, double q) {
  // Linear interpolation between order statistics (type 7).
  std::sort(v.begin(), v.end());
  const double h = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const auto hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (h - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

}  // namespace

// Wilson-Hilferty cube-root normal approximation (within ~1 % for dof >= 3):
// q = dof (1 - 2/(9 dof) + z sqrt(2/(9 dof)))^3, z = 1.6449 for 95 %.
double chi2_95(std::size_t dof) {
  const double k = static_cast<double>(dof);
  const double c = 2.0 / (9.0 * k);
  return k * std::pow(1.0 - c + 1.6448536269514722 * std::sqrt(c), 3);
}

bool poor_fit(const peak_estimate& p) { return p.dof > 0 && p.chi2 > chi2_95(p.dof); }

peak_estimate fit_peak(const std::vector<double>& lambda, const std::vector<double>& mean,
                       const std::vector<double>& std_error, double center, std::uint64_t seed,
                       std::uint64_t stream_tag, std::size_t bootstrap) {
  peak_estimate e;
  e.center = center;
  const std::size_t n = lambda.size();
  if (n < 3 || mean.size() != n || std_error.size() != n || !(center > 0)) return e;
  // The evaluations in u; a zero standard error (all realizations equal)
  // would get infinite weight.
  std::vector<evaluation> points(n);
  for (std::size_t i = 0; i < n; ++i)
    points[i] = {std::log(lambda[i] / center), mean[i], std::max(std_error[i], 1e-12)};
  const auto fit = fit_quadratic(points);
  if (!fit) return e;
  const auto& b = fit->coef;
  e.b0 = b[0];
  e.b1 = b[1];
  e.b2 = b[2];
  e.dof = fit->dof;
  e.chi2 = fit->chi2;
  if (!(b[2] < 0.0)) return e;  // no maximum: curvature is not negative
  e.valid = true;
  const double us = -b[1] / (2.0 * b[2]);
  e.lambda_star = center * std::exp(us);
  e.R_star = b[0] - b[1] * b[1] / (4.0 * b[2]);
  const auto [u_lo, u_hi] = std::minmax_element(
      points.begin(), points.end(), [](const auto& a, const auto& c) { return a.x < c.x; });
  e.interior = us >= u_lo->x && us <= u_hi->x;
  // Delta method: gradients of u* and R* with respect to (b0, b1, b2);
  // d lambda* = lambda* d u*.
  const std::array<double, 3> gu{0.0, -1.0 / (2.0 * b[2]), b[1] / (2.0 * b[2] * b[2])};
  const std::array<double, 3> gr{1.0, -b[1] / (2.0 * b[2]), b[1] * b[1] / (4.0 * b[2] * b[2])};
  e.lambda_se_delta = e.lambda_star * std::sqrt(quadratic_form(gu, *fit));
  e.R_se_delta = std::sqrt(quadratic_form(gr, *fit));

  // Parametric bootstrap.
  normal_stream z(seed, stream_tag);
  std::vector<double> ls, rs;
  ls.reserve(bootstrap);
  rs.reserve(bootstrap);
  auto draw = points;
  for (std::size_t k = 0; k < bootstrap; ++k) {
    for (std::size_t i = 0; i < n; ++i) draw[i].mean = mean[i] + std_error[i] * z.next();
    const auto refit = fit_quadratic(draw);
    if (!refit || !(refit->coef[2] < 0.0)) {
      ++e.bootstrap_degenerate;
      continue;
    }
    const auto& bb = refit->coef;
    ls.push_back(center * std::exp(-bb[1] / (2.0 * bb[2])));
    rs.push_back(bb[0] - bb[1] * bb[1] / (4.0 * bb[2]));
  }
  e.bootstrap = ls.size();
  if (ls.size() >= 20) {
    e.lambda_lo = percentile(ls, 0.025);
    e.lambda_hi = percentile(ls, 0.975);
    e.R_lo = percentile(rs, 0.025);
    e.R_hi = percentile(rs, 0.975);
  } else {  // too few usable draws: fall back to the delta method
    e.lambda_lo = e.lambda_star - z95 * e.lambda_se_delta;
    e.lambda_hi = e.lambda_star + z95 * e.lambda_se_delta;
    e.R_lo = e.R_star - z95 * e.R_se_delta;
    e.R_hi = e.R_star + z95 * e.R_se_delta;
  }
  return e;
}

}  // namespace stickslip::study
