#include "stickslip/precision/peak_sweep.hpp"

#include <fmt/format.h>

#include "stickslip/error.hpp"

namespace stickslip::precision {

const quantity_info& peak_statistic(const std::string& key, const std::string& name) {
  std::string names;
  for (const auto& q : quantities()) {
    if (!per_realization(q.sampled)) continue;
    if (name == q.summary_name || name == q.name || name == q.symbol) return q;
    names += fmt::format("{}{}", names.empty() ? "" : ", ", q.summary_name);
  }
  throw invalid_value(key, name, "one of the per-realization statistics: " + names);
}

peak_result find_peak_by_sweeps(const sweep_peak_request& q) {
  if (!q.statistic) throw invalid_value("statistic", "(none)", "a per-realization statistic");
  validate(q.options);
  // Both ends of the range must be valid models (and within the work bound).
  for (double x : {q.options.lo, q.options.hi}) {
    auto check = q.spec;
    check.axes.clear();
    set_parameter(check.base, q.over, x);
    validate(check);
  }
  const auto& moments = q.statistic->moments;
  const auto sweep_at = [&](const std::vector<double>& xs, std::uint64_t n, std::uint64_t seed,
                            bool crn) {
    sweep_spec s = q.spec;
    s.axes = {axis{q.over, xs}};
    s.realizations = n;
    s.seed = seed;
    s.common_random_numbers = crn;
    s.target_statistic.clear();
    // The finder reads one mean per point; the family's statistics would
    // cost ~15 % (docs/performance.md) and are not among its statistics
    // unless asked for.
    if (q.statistic - quantities().data() < static_cast<std::ptrdiff_t>(paper_quantity_count))
      s.family_statistics = false;
    // Nor the pooled statistics, histograms and duration lists (about 15 %
    // less CPU; the means are the same bits).
    s.means_only = per_realization(q.statistic->sampled);
    validate(s);
    return q.run ? q.run(s) : run_sweep(s, q.threads);
  };
  if (q.common_random_numbers) {
    // Each stage: `groups` sweeps with common random numbers across the
    // points, seeds hashed from (seed, stage, group).
    common_peak_options co;
    co.base = q.options;
    const group_evaluator eval = [&](const std::vector<double>& xs, std::uint64_t n,
                                     std::size_t groups, std::uint64_t stage) {
      std::vector<std::vector<double>> means(groups);
      for (std::size_t g = 0; g < groups; ++g) {
        const auto result = sweep_at(xs, n, stage_seed(stage_seed(q.spec.seed, stage), g), true);
        for (const auto& p : result.points) means[g].push_back((p.stats.*moments).mean());
      }
      return means;
    };
    return find_peak_common(eval, co);
  }
  // One sweep per stage, every point its own streams.
  const evaluator eval = [&](const std::vector<double>& xs, std::uint64_t n, std::uint64_t stage) {
    const auto result = sweep_at(xs, n, stage_seed(q.spec.seed, stage), false);
    std::vector<evaluation> out;
    for (std::size_t i = 0; i < xs.size(); ++i) {
      const auto& m = result.points[i].stats.*moments;
      out.push_back({xs[i], m.mean(), m.std_error()});
    }
    return out;
  };
  return find_peak(eval, q.options);
}

}  // namespace stickslip::precision
