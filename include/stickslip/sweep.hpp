// A parametric sweep: a grid of plain parameter values, split into work units
// of (grid point, block of realizations). Every unit is a pure function of the
// spec, and block statistics are merged per point in block order, so the
// result is bit-identical for any number of threads, ranks or shards.
// The spec, its grid and its units are in sweep_spec.hpp; here the engines of
// a unit, the ordered merge, the cost model and the thread pool's run.
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
#include "stickslip/sweep_spec.hpp"

namespace stickslip {

// Sets the automatic (0) ends of s.survival: the largest d_max
// (max_stick_duration) and the largest t_a over the grid's points (with laws,
// at the quantiles histogram_parameters widens the ranges to). Nothing
// without the survival group.
void resolve_survival_grid(sweep_spec& s);

// Throws stickslip::error naming the first problem (unknown or repeated axis,
// empty axis, a value given twice on one axis, invalid point, zero
// realizations, absurd size).
void validate(const sweep_spec& s);

// Simulate the realizations of one unit on the engine engine_for gives its
// point (engines/engine_choice.hpp). Pure: depends only on (spec, unit), and
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

// With --target-ci: one line on the grid points whose mean's 95 % half-width
// is still above the target (their cap came first), how many, and the
// widest with its point, and how many had fewer than 2 values (no
// half-width); empty when every point met it or there is no target. The
// cap is "the cap of N realizations per point", one text for the CLI's
// warning, Python's and the outputs' record (results.nc's and
// summary.json's `warning`; a new user found the flag's name in one and
// not the other odd, and Python's "within realizations 400" odder).
// A sensitivity study's: study_warning (uncertainty/sensitivity_design.hpp).
// (A new user's unreachable target ended with exit 0 and no word.)
[[nodiscard]] std::string unmet_target_note(const result_set& rs);

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
