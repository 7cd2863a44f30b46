#include "stickslip/uncertainty/sensitivity_design.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "stickslip/engines/point_engine.hpp"
#include "stickslip/error.hpp"
#include "stickslip/uncertainty/sobol.hpp"
#include "stickslip/uncertainty/uncertain_block.hpp"
#include "stickslip/uncertainty/uncertain_draws.hpp"

namespace stickslip {

std::string sensitivity_statistic_names() {
  std::string out;
  for (const auto& q : quantities())
    if (q.sampled == sampling::per_realization)
      out += (out.empty() ? "" : ", ") + std::string(q.summary_name);
  return out;
}

const quantity_info& sensitivity_quantity(const sweep_spec& s) {
  const quantity_info* q = find_mean_statistic(s.sensitivity_statistic);
  if (!q || q->sampled != sampling::per_realization)
    throw invalid_value("--statistic", s.sensitivity_statistic,
                        "a statistic with one value for every realization: " +
                            sensitivity_statistic_names());
  return *q;
}

void set_sensitivity_design(sweep_spec& s, const sensitivity_choice& c) {
  s.sensitivity_statistic = c.statistic;
  (void)sensitivity_quantity(s);  // before anything runs: an empty name is no study
  s.block_size = c.block_size.value_or(default_design_block);
  if (c.target_halfwidth) {
    if (c.samples)
      throw invalid_value("--samples", std::to_string(*c.samples),
                          "not with --target-halfwidth: the stop rule chooses the rows; cap "
                          "them with --max-samples");
    const double h = *c.target_halfwidth;
    // Above 1/2 an interval could be wider than [0, 1], the range of an
    // index, and still meet it (a review: a met target beside the warning
    // that the intervals say nothing).
    if (!(h > 0.0 && h <= 0.5)) throw invalid_parameter("--target-halfwidth", h, "0 < H <= 0.5");
    s.target_halfwidth = h;
    s.realizations = c.max_samples.value_or(default_design_max_rows);
    s.min_realizations = c.min_samples.value_or(default_design_min_rows);
    if (s.min_realizations < 2 || s.min_realizations > s.realizations)
      throw invalid_value(
          "--min-samples",
          std::to_string(s.min_realizations) + (c.min_samples ? "" : " (the default)"),
          "2 .. --max-samples (" + std::to_string(s.realizations) + ")" +
              (c.min_samples ? "" : ": give --min-samples too"));
  } else {
    if (c.max_samples || c.min_samples)
      throw invalid_value(c.max_samples ? "--max-samples" : "--min-samples",
                          std::to_string(c.max_samples ? *c.max_samples : *c.min_samples),
                          "only with --target-halfwidth H");
    s.realizations = c.samples.value_or(default_design_rows);
    if (s.realizations < 2)
      throw invalid_value("--samples", std::to_string(s.realizations),
                          ">= 2 (variances need two rows)");
  }
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
  // A design row's statistic is taken over the whole window (the rates
  // divide by t_a), so a burn-in would mix windows.
  if (s.burn_in != 0.0)
    throw invalid_parameter("burn_in", s.burn_in,
                            "0 in a sensitivity study (its statistics are over [0, t_a])");
  const std::uint64_t cap = max_realizations / runs_per_row(s);
  if (s.realizations > cap)
    throw invalid_parameter("--samples", static_cast<double>(s.realizations),
                            "2 .. " + std::to_string(cap) +
                                " (each row runs d + 3 realizations, and realization indices "
                                "must stay below 2^40)");
}

block_result simulate_block_sensitivity(const sweep_spec& s, const work_unit& u) {
  detail::count_engine_run(point_engine::sensitivity);
  const quantity_info& q = sensitivity_quantity(s);
  const std::size_t d = s.uncertain.size();
  const auto key = uncertain_stream_key(s, s.base);
  block_result out;
  // Shaped like the merger's point (ordered_merger), so that += applies.
  out.stats = point_statistics(histogram_parameters(s, u.point), s.histograms, s.family_statistics);
  select_statistics(out.stats, s);
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

bool study_target_met(const sweep_spec& s, const sobol_estimates& e) {
  if (!(s.target_halfwidth > 0.0)) return false;
  // A statistic constant over every row so far has indices 0 / 0: NaN, whose
  // half-width no number of rows brings under the target. The stop rule
  // stops at the minimum, where the warning of undefined indices says why
  // (it ran to the maximum, 10^6 rows by default, for nothing).
  return e.constant_statistic || e.max_half_width() <= s.target_halfwidth;  // false for NaN
}

std::string study_warning(const sweep_spec& s, const sobol_estimates& e) {
  const auto note = sensitivity_warning(e, sensitivity_quantity(s).summary_name);
  if (!(s.target_halfwidth > 0.0) || study_target_met(s, e)) return note;
  // Both when both apply: a small share is the usual reason a target is
  // missed, and its note alone did not say the run stopped at the cap.
  const double widest = e.max_half_width();
  const std::string unmet = fmt::format(
      "the target 95 % half-width {} was not reached within --max-samples {} rows{}",
      s.target_halfwidth, e.rows,
      std::isfinite(widest) ? fmt::format(": the largest is {:.3g}; raise --max-samples", widest)
                            : std::string(" (some intervals are undefined)"));
  return note.empty() ? unmet : note + "; " + unmet;
}

bool meets_sensitivity_target(const sweep_spec& s, const point_statistics& p) {
  if (!is_sensitivity(s) || !(s.target_halfwidth > 0.0)) return false;
  if (p.sensitivity.rows() < s.min_realizations) return false;
  return study_target_met(s, sobol_indices(p.sensitivity));
}

}  // namespace stickslip
