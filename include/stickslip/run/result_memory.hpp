// The memory a sweep's results need, estimated before it runs, so that an
// absurd grid or bin count is refused with a clear error (exit 2) instead of
// ending in std::bad_alloc or the OOM killer. run_journaled calls it for
// every front end (sweep, reproduce, sensitivity, Python); `stickslip sweep`
// also calls it before it touches the output directory.
#pragma once
#include "stickslip/sweep.hpp"

namespace stickslip::run {

// The points of a grid merged with every accumulator at a time, by default
// (run_plan::window_points, merge_shards).
inline constexpr std::size_t default_window_points = 1024;

// The points of one window of a sweep whose outputs are streamed
// (run::streams_outputs): whole rows of the first axis, as many as
// `window_points` holds or, when more, up to streamed_window_rows while the
// window's accumulators stay within 64 MiB (estimated, as
// estimated_result_bytes); then rounded down to a power of two rows (at
// least one). results.nc's chunks end at a window's last row (a chunk's
// rows divide the window's), and chunks of a few rows deflate worse: the
// 100,000-point grid's file (400 x 250) was 154 MB with windows of 4 rows,
// 98 MB with 16, 89 MB written whole; with a prime number of rows (53 of
// 19 points) a large variable's chunks fell to one row.
inline constexpr std::size_t streamed_window_rows = 16;
[[nodiscard]] std::size_t streamed_window_points(const sweep_spec& spec, std::size_t window_points);

// Bytes held at once by a sweep run on `threads` threads (0 = all cores),
// merged `window_points` points at a time (run_plan::window_points; 0 = the
// whole grid at once): the points being merged hold every accumulator
// (sizeof(point_statistics), the histograms of every binned quantity, the
// joint (D, X) histograms of (bins + 2)^2 cells each, allocated for every
// point also when the family's statistics are off, the observe times and
// the convergence trace: every block up to 64, then 32 entries per
// doubling, records_convergence_after); the finished points (point_result)
// only what the outputs read (release_unselected); plus the raw records when
// kept, and one point's statistics per block in flight (a batch per thread,
// at most every unit). The writers add no copy (results.nc is written a
// chunk of at most 4 MiB at a time, the text files a buffer at a time).
// `keeps_results` false: a shard, which journals its units and keeps no
// finished point nor record (its merger still holds every accumulator of
// the points it merges: the window's, or the whole grid's).
[[nodiscard]] double estimated_result_bytes(const sweep_spec& spec, unsigned threads,
                                            std::size_t window_points = 0,
                                            bool keeps_results = true) noexcept;

// Throws invalid_input (exit 2) when estimated_result_bytes exceeds 80 % of
// this machine's RAM, naming both.
void check_result_memory(const sweep_spec& spec, unsigned threads, std::size_t window_points = 0,
                         bool keeps_results = true);

// Frees what no output of `spec` reads from a point's finished statistics:
// the joint histograms unless selected (point_statistics allocates their
// (bins + 2)^2 cells at every point, ~22 KB with 50 bins, also when the
// family statistics are off) and the histograms of unselected quantities.
// The writers read only selected statistics, so the outputs keep their bits.
// Not for statistics that are merged further or journaled.
void release_unselected(point_statistics& stats, const sweep_spec& spec);

}  // namespace stickslip::run
