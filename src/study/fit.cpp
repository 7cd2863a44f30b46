// Locating the maximum of mean R in lambda: a weighted quadratic fit in
// u = ln(lambda / center) with delta-method errors and a parametric bootstrap.
// The math is written out in include/stickslip/study/fit.hpp.
#include <Random123/philox.h>
#include <Random123/uniform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "stickslip/study/fit.hpp"
#include "stickslip/accumulators/mean_variance.hpp"  // z95

namespace stickslip::study {

namespace {

using mat3 = std::array<std::array<double, 3>, 3>;
using vec3 = std::array<double, 3>;

// Inverse of a symmetric positive definite 3x3 matrix by cofactors;
// returns false if it is singular.
bool invert(const mat3& a, mat3& inv) {
  const double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
  const double c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
  const double c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
  const double det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return false;
  inv[0][0] = c00 / det;
  inv[1][0] = c01 / det;
  inv[2][0] = c02 / det;
  inv[0][1] = (a[0][2] * a[2][1] - a[0][1] * a[2][2]) / det;
  inv[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) / det;
  inv[2][1] = (a[0][1] * a[2][0] - a[0][0] * a[2][1]) / det;
  inv[0][2] = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) / det;
  inv[1][2] = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) / det;
  inv[2][2] = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) / det;
  return true;
}

struct wls {
  mat3 cov{};  // (X^T W X)^-1: covariance of the coefficients
  bool ok = false;
};

// The normal matrix depends only on u and the weights, so it is inverted once
// and reused for every bootstrap draw: b = cov X^T W y.
wls prepare(const std::vector<double>& u, const std::vector<double>& w) {
  mat3 a{};
  for (std::size_t i = 0; i < u.size(); ++i) {
    const vec3 x{1.0, u[i], u[i] * u[i]};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) a[r][c] += w[i] * x[r] * x[c];
  }
  wls f;
  f.ok = invert(a, f.cov);
  return f;
}

vec3 solve(const wls& f, const std::vector<double>& u, const std::vector<double>& w,
           const std::vector<double>& y) {
  vec3 rhs{};
  for (std::size_t i = 0; i < u.size(); ++i) {
    rhs[0] += w[i] * y[i];
    rhs[1] += w[i] * y[i] * u[i];
    rhs[2] += w[i] * y[i] * u[i] * u[i];
  }
  vec3 b{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) b[r] += f.cov[r][c] * rhs[c];
  return b;
}

double quadratic_form(const vec3& g, const mat3& m) {
  double s = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) s += g[r] * m[r][c] * g[c];
  return s;
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
  std::vector<double> u(n), w(n);
  for (std::size_t i = 0; i < n; ++i) {
    u[i] = std::log(lambda[i] / center);
    // A zero standard error (all realizations equal) would get infinite weight.
    const double se = std::max(std_error[i], 1e-12);
    w[i] = 1.0 / (se * se);
  }
  const wls f = prepare(u, w);
  if (!f.ok) return e;
  const vec3 b = solve(f, u, w, mean);
  e.b0 = b[0];
  e.b1 = b[1];
  e.b2 = b[2];
  e.dof = n - 3;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = mean[i] - (b[0] + b[1] * u[i] + b[2] * u[i] * u[i]);
    e.chi2 += w[i] * r * r;
  }
  if (!(b[2] < 0.0)) return e;  // no maximum: curvature is not negative
  e.valid = true;
  const double us = -b[1] / (2.0 * b[2]);
  e.lambda_star = center * std::exp(us);
  e.R_star = b[0] - b[1] * b[1] / (4.0 * b[2]);
  e.interior = us >= *std::min_element(u.begin(), u.end()) &&
               us <= *std::max_element(u.begin(), u.end());
  // Delta method: gradients of u* and R* with respect to (b0, b1, b2);
  // d lambda* = lambda* d u*.
  const vec3 gu{0.0, -1.0 / (2.0 * b[2]), b[1] / (2.0 * b[2] * b[2])};
  const vec3 gr{1.0, -b[1] / (2.0 * b[2]), b[1] * b[1] / (4.0 * b[2] * b[2])};
  e.lambda_se_delta = e.lambda_star * std::sqrt(quadratic_form(gu, f.cov));
  e.R_se_delta = std::sqrt(quadratic_form(gr, f.cov));

  // Parametric bootstrap.
  normal_stream z(seed, stream_tag);
  std::vector<double> ls, rs, y(n);
  ls.reserve(bootstrap);
  rs.reserve(bootstrap);
  for (std::size_t k = 0; k < bootstrap; ++k) {
    for (std::size_t i = 0; i < n; ++i) y[i] = mean[i] + std_error[i] * z.next();
    const vec3 bb = solve(f, u, w, y);
    if (!(bb[2] < 0.0)) {
      ++e.bootstrap_degenerate;
      continue;
    }
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
