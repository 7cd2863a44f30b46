#include "stickslip/precision/batch_means.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "stickslip/error.hpp"

namespace stickslip::precision {

std::vector<double> mean_curve(const std::vector<std::vector<double>>& rows) {
  std::vector<double> m(rows.front().size(), 0.0);
  for (const auto& row : rows)
    for (std::size_t i = 0; i < m.size(); ++i) m[i] += row[i] / static_cast<double>(rows.size());
  return m;
}

polynomial_fit fit_groups(const std::vector<double>& xs,
                          const std::vector<std::vector<double>>& rows, std::size_t degree,
                          double center, double scale) {
  const std::size_t k = degree + 1;
  std::vector<std::vector<double>> coefs;
  for (const auto& row : rows) {
    std::vector<evaluation> pts;
    for (std::size_t i = 0; i < xs.size(); ++i) pts.push_back({xs[i], row[i], 1.0});
    coefs.push_back(fit_polynomial(pts, degree, center, scale).coef);
  }
  auto f = average_of_groups(coefs, center, scale);
  f.dof = xs.size() - k;
  return f;
}

polynomial_fit average_of_groups(const std::vector<std::vector<double>>& coefs, double center,
                                 double scale) {
  const std::size_t g = coefs.size(), k = coefs.front().size();
  polynomial_fit f;
  f.center = center;
  f.scale = scale;
  f.coef.assign(k, 0.0);
  for (const auto& c : coefs)
    for (std::size_t j = 0; j < k; ++j) f.coef[j] += c[j] / static_cast<double>(g);
  f.covariance.assign(k, std::vector<double>(k, 0.0));
  const double norm = static_cast<double>(g) * static_cast<double>(g - 1);
  for (const auto& c : coefs)
    for (std::size_t a = 0; a < k; ++a)
      for (std::size_t b = 0; b < k; ++b)
        f.covariance[a][b] += (c[a] - f.coef[a]) * (c[b] - f.coef[b]) / norm;
  return f;
}

void record_stage_estimate(peak_result& r, peak_stage& progress, double max_halfwidth,
                           double window_lo, double window_hi, std::size_t points) noexcept {
  r.max_lo = r.max - max_halfwidth;
  r.max_hi = r.max + max_halfwidth;
  r.window_lo = window_lo;
  r.window_hi = window_hi;
  r.points_in_fit = points;
  progress.estimate = true;
  progress.argmax = r.argmax;
  progress.sampling_halfwidth = r.sampling_halfwidth;
  progress.model_bias = r.model_bias;
}

std::uint64_t grown_realizations(std::uint64_t n, double want) noexcept {
  const auto dn = static_cast<double>(n);
  return std::isfinite(want) ? static_cast<std::uint64_t>(std::clamp(want, dn, 8.0 * dn)) : 8 * n;
}

std::size_t interior_scan_maximum(const std::vector<double>& xs, const std::vector<double>& means,
                                  const peak_options& o) {
  const auto best =
      static_cast<std::size_t>(std::max_element(means.begin(), means.end()) - means.begin());
  if (best == 0 || best + 1 == means.size())
    throw error(exit_code::invalid_input,
                fmt::format("the largest mean of the first scan is at {} = the {} end of the "
                            "range [{}, {}]; the maximizer may lie outside: widen the range",
                            xs[best], best == 0 ? "lower" : "upper", o.lo, o.hi));
  return best;
}

std::size_t groups_to_add(std::size_t have, double ratio, std::size_t min_groups_to_stop) noexcept {
  const double h = static_cast<double>(have);
  auto add = static_cast<std::size_t>(
      std::clamp(std::ceil(h * (ratio * ratio - 1.0)), std::ceil(0.5 * h), 3.0 * h));
  if (have + add < min_groups_to_stop) add = min_groups_to_stop - have;
  return add;
}

}  // namespace stickslip::precision
