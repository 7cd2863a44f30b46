// Comparison scenarios: one realization of the paper's model (initial
// conditions and belt switch times drawn from the core's Philox streams, so
// `stickslip simulate` replays the same realization), the exact episodes of
// our closed-form integrator, and the plain-text files the Octave script reads.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "stickslip/episode.hpp"
#include "stickslip/initial_conditions.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/parameters.hpp"

namespace stickslip::bench {

struct scenario {
  int id = 0;
  std::uint64_t seed = 1;
  std::uint64_t realization = 0;
  model_parameters params;       // params.window: the full window (paper: 50 s)
  initial_conditions initial;
  std::vector<double> switch_times;  // every belt switch Y_j < params.window
};

// Draw scenario `realization` of the grid point `params` exactly as
// sweep's simulate_realization does (same key, same substreams).
[[nodiscard]] scenario make_scenario(int id, const model_parameters& params, std::uint64_t seed,
                                     std::uint64_t realization);

// A stick interval [start, end]; `censored` when the window cut it off.
struct stick_interval {
  double start = 0.0, end = 0.0;
  bool censored = false;
};

// What one method computed for one scenario on one window.
struct method_run {
  std::vector<stick_interval> sticks;
  event_counts counts;            // belt switches, onsets, breaks, reversals
  std::uint64_t steps = 0;        // solver steps (0 for the exact method)
  std::uint64_t rhs_evaluations = 0;
};

// Our exact result on [0, window].
[[nodiscard]] method_run run_exact(const scenario& s, double window);

// Compare a method's sticks with the exact ones (both sorted by start).
// Two sticks match when their starts differ by less than `match_tolerance`.
struct stick_comparison {
  int matched = 0, spurious = 0, missed = 0;
  double max_boundary_error = 0.0;   // max |start - start*|, |end - end*| over matched sticks
  double max_spurious_duration = 0.0;
};
[[nodiscard]] stick_comparison compare_sticks(const std::vector<stick_interval>& exact,
                                              const std::vector<stick_interval>& method,
                                              double match_tolerance = 1e-3);

// Scenario file for Octave, one `key value...` per line:
//   id, lambda, m, k, g, mu, V, window, x0, xdot0, belt, switches <n> <t1> ... <tn>
void write_scenario_file(const std::string& path, const scenario& s, double window);
// Octave result file: `cpu <s>`, `wall <s>`, `steps <n>`, `counts <sw> <on> <br> <rev>`,
// then one `stick <start> <end> <censored>` per stick.
[[nodiscard]] method_run read_method_file(const std::string& path, double& cpu_seconds,
                                          double& wall_seconds);

}  // namespace stickslip::bench
