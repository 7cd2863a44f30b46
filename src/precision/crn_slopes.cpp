#include "stickslip/precision/crn_slopes.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace stickslip::precision {

namespace {

// The per-realization quantities the sweep filled (the family's only with
// family_statistics).
bool per_realization(const sweep_spec& s, std::size_t row) noexcept {
  const auto& q = quantities()[row];
  if (row >= paper_quantity_count && !s.family_statistics) return false;
  return q.sampled == sampling::per_realization && q.value != nullptr;
}

// The paired slope of q between points a and b (x_a != x_b).
crn_slope paired_slope(const result_set& rs, std::size_t axis, const quantity_info& q,
                       std::size_t a, std::size_t b, double xa, double xb) {
  crn_slope out{axis, &q, a, b, {}, 0};
  const auto& ra = rs.records[a];
  const auto& rb = rs.records[b];
  const double wa = rs.points[a].parameters.window, wb = rs.points[b].parameters.window;
  const std::size_t n = std::min(ra.size(), rb.size());
  out.pairs = n;
  if (n < 3) return out;
  mean_variance d;
  for (std::size_t r = 0; r < n; ++r) d.add(q.value(rb[r], wb) - q.value(ra[r], wa));
  const double h = xb - xa;
  out.slope = {d.mean() / h, d.std_error() / std::abs(h)};
  return out;
}

}  // namespace

bool has_crn_slopes(const result_set& rs) noexcept {
  if (!rs.spec.common_random_numbers || !rs.spec.keep_records) return false;
  if (rs.records.size() != rs.points.size()) return false;
  return std::any_of(rs.spec.axes.begin(), rs.spec.axes.end(),
                     [](const axis& a) { return a.values.size() >= 2; });
}

std::vector<std::vector<crn_slope>> crn_slopes(const result_set& rs) {
  std::vector<std::vector<crn_slope>> out;
  if (!has_crn_slopes(rs)) return out;
  const auto& axes = rs.spec.axes;
  out.resize(rs.points.size());
  // The stride of each axis in the point index (the last axis varies fastest).
  std::vector<std::size_t> stride(axes.size(), 1);
  for (std::size_t k = axes.size(); k-- > 1;) stride[k - 1] = stride[k] * axes[k].values.size();
  for (std::size_t point = 0; point < rs.points.size(); ++point) {
    const auto idx = point_index(rs.spec, point);
    for (std::size_t k = 0; k < axes.size(); ++k) {
      const auto& values = axes[k].values;
      if (values.size() < 2) continue;
      // The axis in increasing order; this point's neighbours in it.
      std::vector<std::size_t> order(values.size());
      std::iota(order.begin(), order.end(), 0);
      std::sort(order.begin(), order.end(),
                [&](std::size_t i, std::size_t j) { return values[i] < values[j]; });
      const auto at = static_cast<std::size_t>(
          std::find(order.begin(), order.end(), idx[k]) - order.begin());
      const std::size_t lo = order[at == 0 ? 0 : at - 1];
      const std::size_t hi = order[at + 1 == order.size() ? at : at + 1];
      const std::size_t base = point - idx[k] * stride[k];
      for (std::size_t row = 0; row < quantities().size(); ++row)
        if (per_realization(rs.spec, row))
          out[point].push_back(paired_slope(rs, k, quantities()[row], base + lo * stride[k],
                                            base + hi * stride[k], values[lo], values[hi]));
    }
  }
  return out;
}

}  // namespace stickslip::precision
