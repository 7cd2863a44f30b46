// The lane engine behind simulate_block (sweep_engine::fast,
// src/core/engines/fast_lanes.cpp): several realizations per thread in lock step,
// their transcendentals evaluated as SIMD vectors of the target chosen at
// run time. It runs the physics of `simulate` (integrator.hpp), with the same
// operations in the same order and the same kernels (fast_math.hpp),
// and gives every observer the same episodes (every field) and, when the
// observer takes them, the same events as `simulate` does; it refuses at
// compile time an observer of segments (observer.hpp: observes_segments).
// Statistics come from realization_observer and point_statistics::add in
// realization order, exactly as in the reference engine, so every statistic
// is bit-identical to it (tests/unit/test_fast_path*.cpp).
#pragma once
#include <cstdint>
#include <vector>

#include "stickslip/episode.hpp"
#include "stickslip/integrator.hpp"

namespace stickslip {
struct model_parameters;
struct sweep_spec;
struct work_unit;
struct block_result;
}  // namespace stickslip

namespace stickslip::detail {

// Whether the lane engine runs a point: the paper's model, or a family model
// with c = 0 on a two-level belt (any levels, 0 included, any rates, mu_s >=
// mu_k): the same episodes, events and statistics as simulate_model
// (tests/unit/test_fast_path_family.cpp). Only engine_for
// (engines/engine_choice.hpp; defined beside it in engine_choice.cpp)
// chooses with it.
[[nodiscard]] bool runs_in_lanes(const model_parameters& p);

// simulate_block with the lane engine. Pure: depends only on (spec, unit).
// Precondition: runs_in_lanes of the point (else throws stickslip::error).
[[nodiscard]] block_result simulate_block_lanes(const sweep_spec& s, const work_unit& u);
// The same for `count` consecutive blocks of one point at once (what
// run_units uses): lanes move on to the next block's realizations instead of
// idling at a block's tail. Element i is exactly
// simulate_block_lanes(s, {point, first_block + i}).
[[nodiscard]] std::vector<block_result> simulate_blocks_lanes(const sweep_spec& s,
                                                              std::size_t point,
                                                              std::uint64_t first_block,
                                                              std::uint64_t count);

// Everything an observer of episodes and events receives from one
// realization, and the event counts the engine returns.
struct realization_trace {
  std::vector<episode> episodes;
  std::vector<event> events;
  event_counts counts;
};
// Realizations [first, last) of one point through the lane engine, each
// recorded by an observer of episodes and events (for the tests that hold
// the lane engine to `simulate`, field by field). Element i is realization
// first + i. Over max_events, throws the reference's error.
[[nodiscard]] std::vector<realization_trace> trace_realizations_lanes(const sweep_spec& s,
                                                                     std::size_t point,
                                                                     std::uint64_t first,
                                                                     std::uint64_t last);

// How many times the lane engine has handed its units to the reference
// engine because a realization exceeded max_events (process-wide; tests use
// it to check that the lane engine does not give up where the reference
// succeeds, which the rerun would otherwise hide).
[[nodiscard]] std::uint64_t lane_reference_reruns() noexcept;

}  // namespace stickslip::detail
