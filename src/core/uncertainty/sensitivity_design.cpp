#include "stickslip/uncertainty/sensitivity_design.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/uncertainty/sobol.hpp"
#include "stickslip/uncertainty/uncertain_block.hpp"
#include "stickslip/uncertainty/uncertain_draws.hpp"

namespace stickslip {

const quantity_info& sensitivity_quantity(const sweep_spec& s) {
  const quantity_info* q = find_mean_statistic(s.sensitivity_statistic);
  if (!q || q->sampled != sampling::per_realization)
    throw invalid_value("--statistic", s.sensitivity_statistic,
                        "a statistic with one value for every realization: " +
                            mean_statistic_names() +
                            " (first_stick_duration has none for a realization without a stick)");
  return *q;
}

void validate_sensitivity(const sweep_spec& s) {
  if (!is_sensitivity(s)) return;
  (void)sensitivity_quantity(s);
  if (s.uncertain.empty())
    throw error(exit_code::invalid_input, 
        "sensitivity: no uncertain input: give at least one model parameter as a law, e.g. "
        "--mu 'uniform(2,7)'");
  if (!s.axes.empty())
    throw invalid_value("--" + s.axes.front().name, "a grid",
                        "a value or a law in a sensitivity study (it has no grid axes)");
  if (s.keep_records)
    throw error(exit_code::invalid_input, "sensitivity: --records is not available for a sensitivity study");
  if (!s.target_statistic.empty())
    throw error(exit_code::invalid_input, 
        "sensitivity: --target-ci does not apply; use --target-halfwidth H for the indices");
  const std::uint64_t cap = max_realizations / runs_per_row(s);
  if (s.realizations > cap)
    throw invalid_parameter("--samples", static_cast<double>(s.realizations),
                            "1 .. " + std::to_string(cap) +
                                " (each row runs d + 3 realizations, and realization indices "
                                "must stay below 2^40)");
}

block_result simulate_block_sensitivity(const sweep_spec& s, const work_unit& u) {
  const quantity_info& q = sensitivity_quantity(s);
  const std::size_t d = s.uncertain.size();
  const auto key = uncertain_stream_key(s, s.base);
  block_result out;
  // Shaped like the merger's point (ordered_merger), so that += applies.
  out.stats = point_statistics(point_parameters(s, u.point), s.histograms, s.family_statistics);
  out.stats.sensitivity = sobol_moments(d);
  const std::uint64_t first = u.block * s.block_size;
  const std::uint64_t last = std::min(s.realizations, first + s.block_size);
  const std::uint64_t runs = runs_per_row(s);
  std::vector<double> theta(d), y_e(d);
  // One realization of the statistic at parameters `theta`, with the
  // intrinsic randomness of realization index `r`.
  auto y = [&](std::uint64_t r) {
    const model_parameters p = with_values(s.base, s.uncertain, theta);
    const auto run = simulate_uncertain_realization(s, p, key, r);
    out.stats.events += run.record.events;
    return q.value(run.record, p.window);
  };
  for (std::uint64_t j = first; j < last; ++j) {
    const auto a = draw_values(s.uncertain, s.seed, key, j, 0);
    const auto b = draw_values(s.uncertain, s.seed, key, j, d);
    const std::uint64_t r0 = j * runs;
    theta = a;
    const double y_a = y(r0), y_a2 = y(r0 + 1);
    theta = b;
    const double y_b = y(r0 + 2);
    for (std::size_t i = 0; i < d; ++i) {
      theta = a;
      theta[i] = b[i];
      y_e[i] = y(r0 + 3 + i);
    }
    out.stats.sensitivity.add(y_a, y_a2, y_b, y_e);
    ++out.stats.realizations;  // rows: the spec's realizations (check_block_shape)
  }
  return out;
}

bool meets_sensitivity_target(const sweep_spec& s, const point_statistics& p) {
  if (!is_sensitivity(s) || !(s.target_halfwidth > 0.0)) return false;
  if (p.sensitivity.rows() < s.min_realizations) return false;
  const double h = sobol_indices(p.sensitivity).max_half_width();
  return h <= s.target_halfwidth;  // false for NaN
}

}  // namespace stickslip
