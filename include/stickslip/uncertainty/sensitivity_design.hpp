// A sensitivity study as a sweep (docs/uncertainty.md): a sweep_spec with
// sensitivity_statistic set and laws in `uncertain` has one point, and its
// "realizations" are the rows of a pick-freeze design (uncertainty/sobol.hpp).
// Running it through the sweep's run layer gives it the journal, resume,
// shards, MPI, progress and the ordered merge: bit-identical for any threads,
// ranks, shards or resume.
//
// Row j (0-based) of a design with d uncertain inputs:
//   theta_A = draw_values(laws, seed, key, j, 0),  theta_B = draw_values(laws, seed, key, j, d)
//   theta_E[i] = theta_A with input i from theta_B
// and d + 3 realizations, each with its own intrinsic randomness (initial
// conditions, belt) from realization index j (d + 3) + c of the point key:
//   c = 0: y_A,  c = 1: y_A2 (theta_A again),  c = 2: y_B,  c = 3 + i: y_E[i].
// y is the statistic's value for that one realization (quantity_info::value
// at the realization's own window).
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "stickslip/statistics_schema.hpp"
#include "stickslip/sweep_spec.hpp"
#include "stickslip/uncertainty/sobol.hpp"

namespace stickslip {

[[nodiscard]] inline bool is_sensitivity(const sweep_spec& s) noexcept {
  return !s.sensitivity_statistic.empty();
}
// Realizations one design row runs: d + 3.
[[nodiscard]] inline std::uint64_t runs_per_row(const sweep_spec& s) noexcept {
  return s.uncertain.size() + 3;
}

// What a user chooses about a study's sampling, flag by flag (the CLI's
// `sensitivity` and Python's stickslip.sensitivity() both go through
// set_sensitivity_design, so the rules and defaults live here once):
//   statistic         a per-realization statistic (default R)
//   samples           N design rows (default 4096), or
//   target_halfwidth  H, 0 < H <= 1: rows until every index and share has a
//                     95 % half-width <= H, at least min_samples (default
//                     1000) and at most max_samples (default 10^6);
//   block_size        rows per work unit (default 64).
struct sensitivity_choice {
  std::string statistic = "R";
  std::optional<std::uint64_t> samples, max_samples, min_samples, block_size;
  std::optional<double> target_halfwidth;
};
inline constexpr std::uint64_t default_design_rows = 4096;
inline constexpr std::uint64_t default_design_block = 64;
inline constexpr std::uint64_t default_design_max_rows = 1'000'000;
inline constexpr std::uint64_t default_design_min_rows = 1000;

// Makes `s` the design `c` describes. Throws invalid_value naming the flag
// (--statistic, --samples, --target-halfwidth, --max-samples,
// --min-samples) for a statistic without one value per realization, or a
// combination that means nothing (--samples with --target-halfwidth;
// --max-samples or --min-samples without it).
void set_sensitivity_design(sweep_spec& s, const sensitivity_choice& c);

// The statistics a study can take: the schema's per-realization ones
// ("R, sticks_per_time, ..."), joined by ", ".
[[nodiscard]] std::string sensitivity_statistic_names();

// The statistic of a sensitivity study: a quantity of the schema with one
// value per realization (R, sticks_per_time, ...). Throws invalid_input
// naming the statistic and the allowed ones.
[[nodiscard]] const quantity_info& sensitivity_quantity(const sweep_spec& s);

// Throws invalid_input for a sensitivity spec that is not one: no laws, grid
// axes, kept records, a precision target on a statistic, or more rows than
// the random streams' realization counter holds once multiplied by d + 3.
void validate_sensitivity(const sweep_spec& s);

// The rows of unit u: their sobol_moments in point_statistics::sensitivity,
// with `realizations` counting the rows (the spec's unit of work; each ran
// runs_per_row realizations) and `events` the events of every run.
[[nodiscard]] block_result simulate_block_sensitivity(const sweep_spec& s, const work_unit& u);

// Whether the merged design has met --target-halfwidth: at least
// min_realizations rows and every index and share's 95 % half-width <=
// target_halfwidth.
[[nodiscard]] bool meets_sensitivity_target(const sweep_spec& s, const point_statistics& p);

// What a study's outputs record as its "warning" (sensitivity.nc,
// summary.json; the CLI, merge and Python give it): sensitivity_warning of
// its estimates, else, with --target-halfwidth, that the target was not
// reached within --max-samples rows (the largest half-width, and what to
// raise); empty otherwise. (A new user's unreachable target ended with exit
// 0 and no word.)
[[nodiscard]] std::string study_warning(const sweep_spec& s, const sobol_estimates& e);
// Whether the study met its --target-halfwidth (false without one; true for
// a constant statistic, where the stop rule stops).
[[nodiscard]] bool study_target_met(const sweep_spec& s, const sobol_estimates& e);

}  // namespace stickslip
