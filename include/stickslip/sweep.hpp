// A parametric sweep: a grid of plain parameter values, split into work units
// of (grid point, block of realizations). Every unit is a pure function of the
// spec, and block statistics are merged per point in block order, so the
// result is bit-identical for any number of threads, ranks or shards.
#pragma once
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "stickslip/belt_switches.hpp"
#include "stickslip/initial_conditions.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/statistics.hpp"
#include "stickslip/statistics_groups.hpp"
#include "stickslip/statistics_schema.hpp"
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
//              order (src/core/fast_lanes.cpp; docs/performance.md); the default;
//   reference  `simulate_model` one realization at a time, for every model
//              (the paper's is its undamped two-level case, the same bits as
//              `simulate`), markov_level_switches + realization_observer +
//              point_statistics::add: the plain path, kept as the oracle.
// engine_for (engines/point_engine.hpp) turns this and a point's model into
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
  // bits either way, everything else is empty.
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
  // The survival group's grid, shared by all points (statistics.hpp); used
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

// Sets the automatic (0) ends of s.survival: the largest d_max
// (max_stick_duration) and the largest t_a over the grid's points (with laws,
// at the quantiles histogram_parameters widens the ranges to). Nothing
// without the survival group.
void resolve_survival_grid(sweep_spec& s);

// Sizes the accumulators of the selected groups of `s` in fresh statistics
// of one of its points (every place that makes a point's statistics calls
// it, so blocks, merged prefixes and the merger agree on the shape).
void select_statistics(point_statistics& stats, const sweep_spec& s);

// The key of the random streams of point p: point_key(p), or
// common_stream_key with common random numbers.
[[nodiscard]] inline std::uint64_t stream_key(const sweep_spec& s,
                                              const model_parameters& p) noexcept {
  return s.common_random_numbers ? common_stream_key : point_key(p);
}

// Throws stickslip::error naming the first problem (unknown or repeated axis,
// empty axis, a value given twice on one axis, invalid point, zero
// realizations, absurd size).
void validate(const sweep_spec& s);

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

// Simulate the realizations of one unit on the engine engine_for gives its
// point (engines/point_engine.hpp). Pure: depends only on (spec, unit), and
// the engines give bit-identical results where more than one runs.
[[nodiscard]] block_result simulate_block(const sweep_spec& s, const work_unit& u);
// The reference engine, whatever s.engine says: simulate_model
// (model/model_engine.hpp) one realization at a time, for every model (the
// paper's included: the same bits as simulate). Where the lane engine runs
// too, both give the same bits. Precondition: the point has no laws.
[[nodiscard]] block_result simulate_block_reference(const sweep_spec& s, const work_unit& u);
// simulate_block of each unit, in order. Runs of consecutive blocks of one
// point go to the lane engine together, so its lanes move on to the next
// block instead of idling at a block's tail (~20 % with blocks of 50); the
// results are exactly simulate_block's.
[[nodiscard]] std::vector<block_result> simulate_units(const sweep_spec& s,
                                                       const std::vector<work_unit>& units);
// How many consecutive units a scheduler should hand out together for
// simulate_units to gain from: 20 with the lane engine (fast), else 1.
[[nodiscard]] std::uint64_t units_per_batch(const sweep_spec& s) noexcept;


// Simulate one realization of one grid point of the paper's model with
// simulate() (the family: model/model_realization.hpp).
template <class Observer>
event_counts simulate_realization(const sweep_spec& s, const model_parameters& p,
                                  std::uint64_t realization, Observer& obs);

// Whether the convergence trace gets a point after merging block b (1-based)
// of `total`: every block up to 64, then 32 points per doubling, and the last.
// The trace therefore grows like log N (about 350 points for N = 10^6 in
// blocks of 50), keeping memory flat in N.
[[nodiscard]] bool records_convergence_after(std::uint64_t b, std::uint64_t total) noexcept;

// The precision target's quantity (sweep_spec::target_statistic), or nullptr
// when there is none. Throws stickslip::error for a name that is not a
// per-realization quantity of the schema.
[[nodiscard]] const quantity_info* target_quantity(const sweep_spec& s);
// Whether a point with these merged statistics has met the precision target
// (false without one).
[[nodiscard]] bool meets_target(const sweep_spec& s, const point_statistics& p);

// The statistics of a point's first `blocks` blocks merged in block order,
// convergence trace included: what ordered_merger holds for the point then.
// The journal keeps finished work in this form (io/journal.hpp), so that its
// size and a resume's memory do not grow with the realizations; restoring it
// continues the merge with the same bits as merging the blocks one by one.
struct merged_prefix {
  std::size_t point = 0;
  std::uint64_t blocks = 0;
  point_statistics stats;
};

// Accepts block results in any order; merges each point's blocks in block
// order and records a convergence point after the blocks that
// records_convergence_after() selects. With a precision target a point
// stops at the first block after which meets_target(); later blocks of it
// are dropped.
class ordered_merger {
 public:
  explicit ordered_merger(const sweep_spec& s);
  void add(const work_unit& u, block_result r);
  // Continues from a journaled prefix. Precondition: nothing merged for the
  // point yet, and no raw records kept (spec.keep_records is false).
  void restore(merged_prefix p);
  // The point's blocks merged so far (in order, from block 0), and their
  // statistics; the blocks waiting for an earlier one.
  [[nodiscard]] std::uint64_t merged_blocks(std::size_t point) const noexcept {
    return next_block_[point];
  }
  [[nodiscard]] const point_statistics& merged(std::size_t point) const noexcept {
    return points_[point];
  }
  [[nodiscard]] const std::map<work_unit, block_result>& waiting() const noexcept {
    return pending_;
  }
  // Count units without keeping them (a --shard run only journals its units;
  // holding them until the missing blocks of other shards arrive would grow
  // memory with the shard's size).
  void discard_results() noexcept { discard_ = true; }
  [[nodiscard]] bool complete() const noexcept;
  // Whether a point needs no more blocks: all merged, or (--target-ci) its
  // stop rule met. Safe to call from any thread without the caller's lock
  // (schedulers skip the units of finished points).
  [[nodiscard]] bool point_finished(std::size_t point) const noexcept {
    return finished_[point].load(std::memory_order_relaxed) != 0;
  }
  // Units merged, plus the units a stopped point no longer needs.
  [[nodiscard]] std::uint64_t merged_units() const noexcept { return merged_; }
  [[nodiscard]] std::vector<point_statistics>& points() noexcept { return points_; }
  [[nodiscard]] std::vector<std::vector<realization_record>>& records() noexcept { return records_; }

 private:
  const sweep_spec* spec_;
  std::vector<point_statistics> points_;
  std::vector<std::vector<realization_record>> records_;
  std::vector<std::uint64_t> next_block_;
  std::vector<std::atomic<unsigned char>> finished_;
  std::map<work_unit, block_result> pending_;
  std::uint64_t merged_ = 0;
  bool discard_ = false;
};

struct point_result {
  model_parameters parameters;
  std::vector<std::size_t> index;  // position on each axis
  point_statistics stats;
};

struct result_set {
  sweep_spec spec;
  std::vector<point_result> points;
  std::vector<std::vector<realization_record>> records;  // per point, when kept
  double elapsed_seconds = 0.0;
  unsigned threads = 1;  // worker threads (per rank)
  unsigned ranks = 1;    // MPI ranks the sweep ran on (1 without MPI)
};

[[nodiscard]] result_set make_result_set(const sweep_spec& s, ordered_merger&& m);

// Points in order of decreasing expected work (stable for ties): the cost of
// a realization is about linear in its events (expected_events), which at
// fixed t_a vary ~300x across the paper's lambda range. Schedulers (the
// thread pool, the MPI master) start the costliest points first; the ordered
// merge keeps results independent of this order.
[[nodiscard]] std::vector<std::size_t> points_by_cost(const sweep_spec& s);

// The expected number of events of one realization at p: a cost model for
// progress estimates (the ETA), not physics to rely on. A realization costs
// about linearly in its events. Per belt switch (lambda t_a of them):
//   the switch itself;
//   a stick onset if the mass reaches the new belt velocity before the next
//   switch: friction needs about tau = 2V/(mu g) to undo the relative
//   velocity 2V, so p_onset ~ 1/(1 + lambda tau);
//   a stick break if that stick then lasts the longest stick d_max = 2a/V
//   before the next switch, p_break = p_onset exp(-lambda d_max), plus about
//   half as many slip reversals;
// and ~2 events to start a realization. Fitted against the event counts of
// a 12 lambda x 4 mu x 2 k sweep, it is within about 25 % at every point
// (test_eta_cost_model.cpp), where lambda t_a alone is off by up to 3x.
[[nodiscard]] double expected_events(const model_parameters& p);

// Expected work of a unit: its realizations times expected_events.
[[nodiscard]] double expected_unit_cost(const sweep_spec& s, const work_unit& u);

struct sweep_hooks {
  // Called from one thread at a time, after each unit is merged.
  std::function<void(std::uint64_t units_done, std::uint64_t units_total)> progress;
  // Called (serialized) with every unit computed by this process, before merging.
  std::function<void(const work_unit&, const block_result&)> unit_done;
  // Units to run: default all. Used by --shard, --resume and to stop (a
  // signal makes it false from then on). Asked when a unit is about to be
  // handed out, possibly more than once per unit and from several threads
  // (run_units: without a lock), so it must be thread-safe and cheap.
  std::function<bool(const work_unit&)> wanted;
};

// Run the units on `threads` threads (0 = all cores) into `merger`. Units are
// started in order of decreasing expected cost (points with more belt switches
// first, blocks in order within a point) so the cheap ones fill the tail;
// the merger still merges in block order, so results do not depend on it.
void run_units(const sweep_spec& s, unsigned threads, ordered_merger& merger,
               const sweep_hooks& hooks = {});

// Convenience: run everything and return the result set.
[[nodiscard]] result_set run_sweep(const sweep_spec& s, unsigned threads = 0,
                                   const sweep_hooks& hooks = {});

// ---- implementation of the templates ----
template <class Observer>
event_counts simulate_realization(const sweep_spec& s, const model_parameters& p,
                                  std::uint64_t realization, Observer& obs) {
  const auto key = stream_key(s, p);
  const auto ic = draw_initial_conditions(s.initial, s.seed, key, realization);
  poisson_switches sw(p.switch_rate, s.seed, key, realization);
  return simulate(p, ic, sw, obs, s.max_events);
}

}  // namespace stickslip
