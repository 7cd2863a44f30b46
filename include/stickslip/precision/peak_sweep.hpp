// The peak finders evaluated with exact sweeps: what `stickslip peak` and
// Python's stickslip.peak() run (docs/precision.md). Each evaluation is a
// run_sweep over one axis, the parameter `over`, with seeds hashed from
// (spec.seed, stage[, group]), so the result is the same for any number of
// threads. No I/O.
#pragma once
#include <functional>
#include <string>

#include "stickslip/precision/common_peak_finder.hpp"
#include "stickslip/precision/peak_finder.hpp"
#include "stickslip/precision/score_peak_finder.hpp"
#include "stickslip/statistics_schema.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::precision {

// independent: find_peak; common: find_peak_common; score: find_peak_score
// (over lambda, statistic R, Poisson switching: the causal score derivative).
enum class peak_method { independent, common, score };

struct sweep_peak_request {
  sweep_spec spec;          // the model (base), seed and max_events; axes and realizations ignored
  std::string over;         // the parameter symbol to maximize over
  const quantity_info* statistic = nullptr;  // a per-realization statistic of the schema
  peak_options options;     // range, target, budget
  peak_method method = peak_method::common;
  unsigned threads = 0;     // per sweep, 0 = all cores
  // Runs one sweep; default (empty): run_sweep(spec, threads). `reproduce`
  // passes its runner, so that under mpirun the sweeps use every rank.
  std::function<result_set(const sweep_spec&)> run;
};

// The per-realization statistic named `name` (summary name, name or symbol);
// throws stickslip::error naming `key` and the allowed names otherwise.
[[nodiscard]] const quantity_info& peak_statistic(const std::string& key, const std::string& name);

// The method's name (independent, common, score) and back: "auto" is score
// where it applies to the request (score_applies), else common. Throws
// stickslip::error naming `key` for any other name.
[[nodiscard]] const char* to_string(peak_method m) noexcept;
[[nodiscard]] peak_method peak_method_named(const std::string& key, const std::string& name,
                                            const sweep_peak_request& q);

// Whether the score method applies: over lambda, statistic R, Poisson
// switching (the causal score is R's derivative over the switch rate).
[[nodiscard]] bool score_applies(const sweep_peak_request& q);

// Validates the request (both ends of the range valid models; for the score
// method: over lambda, statistic R and Poisson switching) and runs the
// finder. Throws stickslip::error like find_peak.
[[nodiscard]] peak_result find_peak_by_sweeps(const sweep_peak_request& q);

}  // namespace stickslip::precision
