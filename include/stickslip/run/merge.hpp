// Combining the journals that shard runs (`sweep --shard i/n -o DIR`) left in
// their directories into the results of one run, bit-identical to an
// unsharded sweep. Checks: every journal was made with the same
// configuration, every unit is present, and a unit found in several journals
// is identical in each. The input journals are only read, never changed.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "stickslip/io/journal.hpp"
#include "stickslip/io/metadata.hpp"
#include "stickslip/run/result_memory.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::run {

struct merged_shards {
  result_set results;
  io::run_metadata metadata;     // the first journal's run
  std::uint64_t duplicates = 0;  // units found (identical) in more than one journal
};

// Throws invalid_input for a directory without a journal or missing units,
// resume_mismatch for journals of different configurations, io_failure for
// differing duplicates or unreadable headers. A grid of more than
// `window_points` points is merged window by window, as a run
// (run_plan::window_points): only one window's accumulators are held in
// full, and the finished points keep what the outputs read; 0: the whole
// grid at once. The results are the same bits either way. With `stream`, a
// grid merged window by window whose outputs can stream
// (io::streams_outputs) hands each window to it as a slab, with the first
// journal's metadata, as run_plan::stream (`merge` writes them with
// io::streamed_outputs), in windows of streamed_window_points; the
// results then hold no points.
using slab_stream = std::function<void(const result_set& slab, const io::run_metadata& meta)>;
[[nodiscard]] merged_shards merge_shards(const std::vector<std::string>& dirs,
                                         const io::journal_report& report = {},
                                         std::size_t window_points = default_window_points,
                                         const slab_stream& stream = {});

}  // namespace stickslip::run
