// The fast engine behind simulate_block (sweep_engine::fast).
//
// It runs the same exact integrator (`simulate`, same formulas, same order of
// floating-point operations) as the reference engine, so every statistic is
// bit-identical to the reference path for a given seed. What differs is
// everything around the integrator:
//   - belt switch times come in batches (batched_poisson_switches: the same
//     values as poisson_switches);
//   - the statistics are the reference's: realization_observer, then
//     point_statistics::add in realization order.
#pragma once
#include <cstdint>
#include <vector>

#include "stickslip/episode.hpp"
#include "stickslip/observer.hpp"
#include "stickslip/statistics.hpp"

namespace stickslip {
struct sweep_spec;
struct work_unit;
struct block_result;
}  // namespace stickslip

namespace stickslip::detail {

// simulate_block with the previous, one-realization-at-a-time fast engine
// (kept for tests and comparisons). Pure: depends only on (spec, unit).
[[nodiscard]] block_result simulate_block_fast(const sweep_spec& s, const work_unit& u);

// Which implementation sweep_engine::fast runs. All give bit-identical
// results (tests/unit/test_fast_path*.cpp), so this only changes speed; it is
// process-wide and meant for benchmarks (bench_study --engine lanes).
// Default: lanes, ~10-15 % less CPU per event than one_at_a_time on the
// 2-core development machine (docs/performance.md).
enum class fast_variant : unsigned char { one_at_a_time, lanes };
void set_fast_variant(fast_variant v) noexcept;
[[nodiscard]] fast_variant get_fast_variant() noexcept;

// simulate_block with the lane engine (src/core/fast_lanes.cpp), what
// sweep_engine::fast runs: several realizations per thread in lock step, with
// their transcendentals evaluated as SIMD vectors. Bit-identical to both
// engines above. Pure: depends only on (spec, unit).
[[nodiscard]] block_result simulate_block_lanes(const sweep_spec& s, const work_unit& u);
// The same for `count` consecutive blocks of one point at once (what
// run_units uses with the lanes variant): lanes move on to the next block's
// realizations instead of idling at a block's tail. Element i is exactly
// simulate_block_lanes(s, {point, first_block + i}).
[[nodiscard]] std::vector<block_result> simulate_blocks_lanes(const sweep_spec& s,
                                                              std::size_t point,
                                                              std::uint64_t first_block,
                                                              std::uint64_t count);

// How many times the lane engine has handed its units to the reference
// engine because a realization exceeded max_events (process-wide; tests use
// it to check that the lane engine does not give up where the reference
// succeeds, which the rerun would otherwise hide).
[[nodiscard]] std::uint64_t lane_reference_reruns() noexcept;

}  // namespace stickslip::detail
