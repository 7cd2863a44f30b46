// One realization, replayed exactly as a sweep draws it, or with any of its
// random inputs fixed: what `stickslip simulate` and the Python
// stickslip.simulate() compute. By default realization r of the point with
// these parameters is drawn from the Philox streams keyed by
// (seed, point_key(params), r), so any sweep realization can be replayed
// alone; fixing x0, x'0 or the belt start keeps the other draws; given switch
// times replace the Poisson switches.
#pragma once
#include <cstdint>
#include <cstddef>
#include <optional>
#include <vector>

#include "stickslip/episode.hpp"
#include "stickslip/initial_conditions.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/parameters.hpp"
#include "stickslip/statistics.hpp"

namespace stickslip {

struct replay_request {
  model_parameters parameters;
  std::uint64_t seed = 1, realization = 0;
  initial_condition_law initial;                  // the sweep's law (paper default)
  std::int64_t max_events = default_max_events;
  std::optional<double> x0, xdot0;                // fix the initial state
  // +1 / -1 (first / second level of two), or a level number 1..n.
  std::optional<int> belt_start;
  std::optional<std::vector<double>> switch_times;  // replace the random switches
  // With switch_times: the level index (0-based) each switch goes to; without
  // it the belt alternates between two levels (more levels need it).
  std::optional<std::vector<std::size_t>> switch_levels;
  bool keep_events = true, keep_segments = true;
  // Replay realization r of a sweep run with common random numbers: the
  // streams of common_stream_key instead of point_key(parameters).
  bool common_random_numbers = false;
  // Count only [T, t_a] in the record (sweep_spec::burn_in, burn_in.hpp):
  // the record of realization r of a sweep run with --burn-in T. The
  // episodes, events and segments are the whole realization either way.
  double burn_in = 0.0;
};

struct realization_trace {
  // x0, x'0, and the belt start as recorded (recorded_belt_start: +1 / -1 on
  // two levels, the level number on more).
  initial_conditions initial;
  std::vector<episode> episodes;  // tile [0, t_a]
  std::vector<event> events;      // when kept
  std::vector<segment> segments;  // closed-form pieces, when kept (evaluate())
  realization_record record;      // S_T, S_L, R, D_1, event counts
};

// Throws stickslip::error for invalid parameters, initial state or switch
// times (naming the parameter, the value and the allowed range), and when the
// realization exceeds max_events. With given switch times the switch rate is
// not used and may also be 0. Every model runs on the reference engine,
// simulate_model (engines/point_engine.hpp): the paper's model with the
// bits of simulate(), hence of 0.1.0.
[[nodiscard]] realization_trace replay(const replay_request& r);

}  // namespace stickslip
