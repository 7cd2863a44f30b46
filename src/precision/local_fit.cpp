#include "stickslip/precision/local_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "stickslip/error.hpp"

namespace stickslip::precision {

double polynomial_fit::value(double t) const noexcept {
  double v = 0.0;
  for (std::size_t j = coef.size(); j-- > 0;) v = v * t + coef[j];
  return v;
}

double polynomial_fit::derivative(double t) const noexcept {
  double v = 0.0;
  for (std::size_t j = coef.size(); j-- > 1;) v = v * t + static_cast<double>(j) * coef[j];
  return v;
}

double polynomial_fit::second_derivative(double t) const noexcept {
  double v = 0.0;
  for (std::size_t j = coef.size(); j-- > 2;)
    v = v * t + static_cast<double>(j * (j - 1)) * coef[j];
  return v;
}

double polynomial_fit::value_std_error(double t) const noexcept {
  const std::size_t k = coef.size();
  std::vector<double> g(k);
  double tj = 1.0;
  for (std::size_t j = 0; j < k; ++j, tj *= t) g[j] = tj;
  double var = 0.0;
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = 0; j < k; ++j) var += g[i] * covariance[i][j] * g[j];
  return std::sqrt(std::max(var, 0.0));
}

namespace {

// Inverse of a small symmetric positive definite matrix by Gauss-Jordan
// elimination with partial pivoting.
std::vector<std::vector<double>> inverse(std::vector<std::vector<double>> a) {
  const std::size_t n = a.size();
  std::vector<std::vector<double>> inv(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i) inv[i][i] = 1.0;
  for (std::size_t col = 0; col < n; ++col) {
    std::size_t piv = col;
    for (std::size_t r = col + 1; r < n; ++r)
      if (std::abs(a[r][col]) > std::abs(a[piv][col])) piv = r;
    if (!(std::abs(a[piv][col]) > 1e-300))
      throw error(exit_code::invalid_input, "local fit: the points do not determine the polynomial");
    std::swap(a[piv], a[col]);
    std::swap(inv[piv], inv[col]);
    const double d = a[col][col];
    for (std::size_t j = 0; j < n; ++j) {
      a[col][j] /= d;
      inv[col][j] /= d;
    }
    for (std::size_t r = 0; r < n; ++r) {
      if (r == col) continue;
      const double f = a[r][col];
      if (f == 0.0) continue;
      for (std::size_t j = 0; j < n; ++j) {
        a[r][j] -= f * a[col][j];
        inv[r][j] -= f * inv[col][j];
      }
    }
  }
  return inv;
}

}  // namespace

polynomial_fit fit_polynomial(const std::vector<evaluation>& points, std::size_t degree,
                              double center, double scale) {
  const std::size_t k = degree + 1;
  if (points.size() < k)
    throw error(exit_code::invalid_input,
                "local fit: " + std::to_string(points.size()) + " points for a polynomial of degree " +
                    std::to_string(degree));
  if (!(scale > 0)) throw invalid_parameter("local fit scale", scale, "> 0");
  std::vector<std::vector<double>> normal(k, std::vector<double>(k, 0.0));
  std::vector<double> rhs(k, 0.0);
  for (const auto& p : points) {
    if (!(p.std_error > 0) || !std::isfinite(p.mean))
      throw invalid_parameter("local fit standard error", p.std_error, "> 0 with a finite mean");
    const double w = 1.0 / (p.std_error * p.std_error);
    const double t = (p.x - center) / scale;
    std::vector<double> row(k);
    double tj = 1.0;
    for (std::size_t j = 0; j < k; ++j, tj *= t) row[j] = tj;
    for (std::size_t i = 0; i < k; ++i) {
      rhs[i] += w * row[i] * p.mean;
      for (std::size_t j = 0; j < k; ++j) normal[i][j] += w * row[i] * row[j];
    }
  }
  polynomial_fit f;
  f.center = center;
  f.scale = scale;
  f.covariance = inverse(normal);
  f.coef.assign(k, 0.0);
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = 0; j < k; ++j) f.coef[i] += f.covariance[i][j] * rhs[j];
  for (const auto& p : points) {
    const double r = (p.mean - f.value((p.x - center) / scale)) / p.std_error;
    f.chi2 += r * r;
  }
  f.dof = points.size() - k;
  return f;
}

fitted_maximum maximize(const polynomial_fit& f, double t_lo, double t_hi) {
  fitted_maximum m;
  constexpr int steps = 400;
  double best_t = t_lo, best_v = f.value(t_lo);
  for (int i = 1; i <= steps; ++i) {
    const double t = t_lo + (t_hi - t_lo) * i / steps;
    if (const double v = f.value(t); v > best_v) {
      best_v = v;
      best_t = t;
    }
  }
  double t = best_t;
  for (int it = 0; it < 50; ++it) {
    const double d2 = f.second_derivative(t);
    if (!(d2 < 0)) break;
    const double next = std::clamp(t - f.derivative(t) / d2, t_lo, t_hi);
    if (std::abs(next - t) < 1e-15 * (1 + std::abs(t))) {
      t = next;
      break;
    }
    t = next;
  }
  const double d2 = f.second_derivative(t);
  m.t = t;
  m.interior = t > t_lo && t < t_hi && d2 < 0 && std::abs(f.derivative(t)) <= 1e-9 * std::abs(d2);
  if (!m.interior) return m;
  // t* solves p'(t*) = 0: dt*/dc_j = -(d p'/d c_j) / p''(t*) = -j t^(j-1) / p''(t*).
  const std::size_t k = f.coef.size();
  std::vector<double> g(k, 0.0);
  double tj = 1.0;  // t^(j-1)
  for (std::size_t j = 1; j < k; ++j, tj *= t) g[j] = -static_cast<double>(j) * tj / d2;
  double var = 0.0;
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = 0; j < k; ++j) var += g[i] * f.covariance[i][j] * g[j];
  m.t_std_error = std::sqrt(std::max(var, 0.0));
  return m;
}

double chi2_upper_tail(double x, std::size_t dof) noexcept {
  if (dof == 0) return 1.0;
  if (!(x > 0)) return 1.0;
  // Wilson-Hilferty: (X/k)^(1/3) is close to normal with mean 1 - 2/(9k)
  // and variance 2/(9k).
  const double k = static_cast<double>(dof);
  const double v = 2.0 / (9.0 * k);
  const double z = (std::cbrt(x / k) - (1.0 - v)) / std::sqrt(v);
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

}  // namespace stickslip::precision
