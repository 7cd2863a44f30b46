// A large grid merged window by window: whole slabs of its first axis at a
// time, each as a spec of its own whose point i is point offset + i of the
// whole grid (row-major order). A point's results depend only on its
// parameters (its random streams are keyed by them, point_key; its bins by
// histogram_parameters), so a window's points have the same bits as in the
// whole grid. run_journaled (a run, a shard, a resume) and merge_shards
// hold only one window's accumulators in full; the finished points of the
// earlier windows keep only what the outputs read.
#pragma once
#include <cstddef>
#include <map>
#include <vector>

#include "stickslip/io/journal.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::run::detail {

struct grid_window {
  sweep_spec spec;
  std::size_t offset = 0;  // the whole grid's index of the window's point 0
};

// Whether `spec` may be merged in windows of about `window_points` points:
// a grid of more points than that (window_points = 0: never), and nothing
// that depends on the whole grid (a sensitivity design; a survival grid
// still to be resolved from the data).
[[nodiscard]] bool splits_into_windows(const sweep_spec& spec, std::size_t window_points);

// The windows of `spec`, at least one slab each; the whole grid as one
// window unless splits_into_windows.
[[nodiscard]] std::vector<grid_window> windows_of(const sweep_spec& spec,
                                                  std::size_t window_points);

// Moves the journaled prefixes and units of the window's points out of
// `prefixes` and `units` (keyed by the whole grid's points) into `merger`
// (made for w.spec), renumbered to the window. They are read back and
// decoded here, one window at a time.
void restore_window(const grid_window& w, std::map<std::size_t, io::journaled_prefix>& prefixes,
                    std::map<work_unit, io::journaled_unit>& units, ordered_merger& merger);

// Appends a window's results (make_result_set of its merger) to `all`, the
// whole grid's; with `release` (a window of a larger grid), as slab_of: each
// point's index on the whole grid, and only what the outputs read
// (release_unselected). Without it the window is the whole grid.
void append_window(result_set& all, result_set part, std::size_t offset, bool release);

// A window's results (make_result_set of its merger) as a slab of the
// whole grid (`spec`), for run_plan::stream: the whole grid's spec, each
// point's index on the whole grid, unselected histograms released.
[[nodiscard]] result_set slab_of(const sweep_spec& spec, result_set part, std::size_t offset);

}  // namespace stickslip::run::detail
