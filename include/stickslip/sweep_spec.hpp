// The spec of a parametric sweep: a grid of plain parameter values, split
// into work units of (grid point, block of realizations); the parameters of
// each point and the units of the grid. What runs the units and merges their
// results is in sweep.hpp; the laws of uncertain parameters and the
// sensitivity design (uncertainty/) build on this header, and sweep.hpp on
// them.
#pragma once
#include <compare>
#include <cstdint>
#include <string>
#include <vector>

#include "stickslip/initial_conditions.hpp"
#include "stickslip/integrator.hpp"  // default_max_events
#include "stickslip/parameters.hpp"
#include "stickslip/random_stream.hpp"
#include "stickslip/statistics.hpp"
#include "stickslip/statistics_groups.hpp"
#include "stickslip/uncertainty/parameter_law.hpp"

namespace stickslip {

struct axis {
  std::string name;            // a parameter symbol (parameters.hpp): m k g mu V lambda ta
                               // c mu_s mu_k, belt levels v1..vN, two-level rates r1 r2
  std::vector<double> values;  // in the order given
  friend bool operator==(const axis&, const axis&) = default;
};

// Which engine simulates a work unit. Both run the same exact physics and
// give bit-identical episodes, events and statistics for a given seed
// (tests/unit/test_fast_path*.cpp):
//   fast       the lane engine: 32 realizations per thread advanced together as
//              AVX-512 vectors (16 as AVX2 vectors, 8 on SSE4, 4 on SCALAR), one
//              event per lane per round, the SIMD target chosen at run time,
//              finished realizations added to the statistics in realization
//              order (src/core/engines/fast_lanes.cpp; docs/performance.md); the default;
//   reference  `simulate_model` one realization at a time, for every model
//              (the paper's is its undamped two-level case, the same bits as
//              `simulate`), markov_level_switches + realization_observer +
//              point_statistics::add: the plain path, kept as the oracle.
// engine_for (engines/engine_choice.hpp) turns this and a point's model into
// the engine that runs it.
enum class sweep_engine : unsigned char { fast, reference };
inline constexpr const char* to_string(sweep_engine e) noexcept {
  return e == sweep_engine::fast ? "fast" : "reference";
}

// The limits validate() enforces, in one place (flags, TOML and messages use
// these): realization indices must fit the 40-bit counter field of the random
// streams; a unit's block and the histograms must stay small enough to hold.
inline constexpr std::uint64_t max_realizations = std::uint64_t{1} << 40;
inline constexpr std::uint64_t max_block_size = std::uint64_t{1} << 24;
inline constexpr std::uint64_t max_histogram_bins = 100'000;
inline constexpr std::int64_t max_event_bound = std::int64_t{1} << 53;
inline constexpr std::size_t max_observe_times = 100'000;

struct sweep_spec {
  model_parameters base;           // values of the parameters not swept
  initial_condition_law initial;
  std::vector<axis> axes;          // first axis outermost (slowest)
  std::uint64_t realizations = 2000;
  std::uint64_t seed = 1;
  std::uint64_t block_size = 50;   // realizations per work unit
  histogram_spec histograms;
  std::int64_t max_events = default_max_events;
  bool keep_records = false;       // raw per-realization records (memory grows with N)
  sweep_engine engine = sweep_engine::fast;  // does not change results, only speed
  // Common random numbers (docs/precision.md): every point draws its streams
  // with common_stream_key instead of point_key, so realization r of every
  // point has the same x0, x'0, belt start and unit exponentials. Points are
  // then correlated (differences between them have low variance); each point
  // alone is exactly what it is without the flag, in distribution.
  bool common_random_numbers = false;
  // Adaptive sampling (--target-ci STAT:HALFWIDTH), off when target_statistic
  // is empty: each point stops after the first block, in block order, at
  // which at least min_realizations are merged and the 95 % half-width of
  // the mean of target_statistic (a per-realization quantity of the schema,
  // find_mean_statistic: R, sticks_per_time, ...) is <=
  // target_halfwidth; `realizations` is then the cap per point. The rule
  // sees only the ordered merge, so results do not depend on threads,
  // ranks or resume; later blocks computed ahead are dropped.
  std::string target_statistic;
  double target_halfwidth = 0.0;
  std::uint64_t min_realizations = 1000;
  // The family statistics (stick-onset position X, the joint (D, X)
  // histogram, belt level fractions P_j, friction and damping power). On for
  // every sweep; the paper study (paper_study.cpp) turns them off: they add
  // about 15 % to its time (docs/performance.md), and it does not report them.
  // Off, their accumulators stay empty (NaN means, zero counts); the other
  // statistics are the same bits either way.
  bool family_statistics = true;
  // Only the means of the per-realization statistics (R, S_T/t_a, S_L/t_a,
  // D_1, the powers): no pooled per-stick or per-slip statistics, no
  // histograms, and the lane engine keeps no list of durations. What the
  // peak finder reads (precision/peak_sweep.cpp); those means are the same
  // bits either way, everything else is empty. R's causal score is then kept
  // only with statistics.derivatives selected (keeps_causal_score).
  bool means_only = false;
  // Uncertain parameters (uncertainty/parameter_law.hpp): each realization
  // of every grid point draws its own values of these from its own substream
  // (uncertainty/uncertain_draws.hpp), so a point's statistics are over the
  // mixture. Empty: every parameter is a value or an axis.
  std::vector<uncertain_parameter> uncertain;
  // A sensitivity study (uncertainty/sensitivity.hpp) when not empty: the
  // name of the per-realization statistic whose Sobol' indices over
  // `uncertain` are estimated. There is then one point (no axes), and
  // `realizations` counts the design's sample rows (each row runs
  // 3 + uncertain.size() realizations); the point's statistics hold the
  // design's moments (point_statistics::sensitivity). With
  // target_halfwidth > 0 and target_statistic empty, the study stops at the
  // first block after which every index and share has a 95 % half-width
  // <= target_halfwidth (and at least min_realizations rows are merged).
  std::string sensitivity_statistic;
  // The optional groups of statistics (statistics_groups.hpp; `default` is
  // always on): part of the results' identity, like every field above.
  statistics_selection statistics;
  // The survival group's grid, shared by all points (point_accumulators.hpp); used
  // only with statistics.survival. Its automatic (0) ends are resolved by
  // resolve_survival_grid before a run (validate() requires them).
  survival_spec survival;
  // The burn-in T (burn_in.hpp, `sweep --burn-in`): every statistic counts
  // only [T, t_a]; 0 <= T < t_a at every point, 0 = none (the whole window,
  // the same bits and journal as without the field).
  double burn_in = 0.0;
  // The observe times t_j (`sweep --observe-times`; accumulators/
  // time_statistics.hpp, state_sampler.hpp): ascending, 0 <= t_j <= t_a at
  // every point; empty = none. Every point then also keeps the ensemble's
  // state at each t_j (point_statistics::observed).
  std::vector<double> observe_times;
  friend bool operator==(const sweep_spec&, const sweep_spec&) = default;
};

// Sets what the engines compute from the selection of statistics
// (statistics_groups.hpp): family_statistics when the selection needs them,
// means_only when it asks only for means of per-realization quantities.
// The CLI and Python call it before a run; a spec built in code keeps the
// flags it sets.
void apply_statistics_selection(sweep_spec& s);

// Sizes the accumulators of the selected groups of `s` in fresh statistics
// of one of its points (every place that makes a point's statistics calls
// it, so blocks, merged prefixes and the merger agree on the shape).
void select_statistics(point_statistics& stats, const sweep_spec& s);

// Whether the statistics of `s` keep R's causal score (point_statistics::
// keeps_causal_score): with the family statistics, or with means only when
// the derivatives are selected (the peak finder's score method,
// precision/peak_sweep.cpp). A `sweep --statistics R` reads no derivative.
[[nodiscard]] bool keeps_causal_score(const sweep_spec& s) noexcept;

// The fresh statistics of a block at parameters `p` (the point's, or its
// histogram_parameters with drawn parameters): the flags of `s`, sized by
// select_statistics. Every engine's block starts from them.
[[nodiscard]] point_statistics block_statistics(const sweep_spec& s, const model_parameters& p);

// The key of the random streams of point p: point_key(p), or
// common_stream_key with common random numbers.
[[nodiscard]] inline std::uint64_t stream_key(const sweep_spec& s,
                                              const model_parameters& p) noexcept {
  return s.common_random_numbers ? common_stream_key : point_key(p);
}

[[nodiscard]] std::size_t point_count(const sweep_spec& s) noexcept;
[[nodiscard]] std::vector<std::size_t> point_index(const sweep_spec& s, std::size_t point);
[[nodiscard]] model_parameters point_parameters(const sweep_spec& s, std::size_t point);
// The parameters a point's histogram ranges come from (point_statistics):
// point_parameters, except that at a point with laws each uncertain
// parameter sits at its law's 0.001 or 0.999 quantile, whichever widens the
// ranges (a larger friction, mass, gravity, damping or window; a smaller
// stiffness, belt speed or rate), so that the mixture's durations and onset
// positions fall inside the bins (the median model's ranges cut ~12 % off).
[[nodiscard]] model_parameters histogram_parameters(const sweep_spec& s, std::size_t point);
[[nodiscard]] std::uint64_t blocks_per_point(const sweep_spec& s) noexcept;

struct work_unit {
  std::size_t point = 0;
  std::uint64_t block = 0;
  friend auto operator<=>(const work_unit&, const work_unit&) = default;
};
[[nodiscard]] std::uint64_t unit_count(const sweep_spec& s) noexcept;
[[nodiscard]] work_unit unit_at(const sweep_spec& s, std::uint64_t i) noexcept;

struct block_result {
  point_statistics stats;
  std::vector<realization_record> records;  // filled when spec.keep_records
};

}  // namespace stickslip
