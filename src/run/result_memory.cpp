#include "stickslip/run/result_memory.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>

#include "stickslip/error.hpp"
#include "stickslip/run/runner.hpp"
#include "stickslip/statistics_groups.hpp"
#include "stickslip/statistics_schema.hpp"

namespace stickslip::run {
namespace {

// The heap of one point's statistics: its histograms of `densities`
// quantities and `joints` joint histograms (of (bins + 2)^2 cells, plus the
// two binnings each carries), the observe times, the convergence trace and
// ~256 bytes of small vectors (level fractions, the trace's and the grid
// index's blocks), with malloc's 16 bytes per block.
double statistics_heap(const sweep_spec& spec, double densities, double joints, double trace) {
  const double bins = static_cast<double>(spec.histograms.bins);
  const double histogram = 8.0 * bins + 16.0;
  // The observe times (accumulators/time_statistics.hpp): about 3 KB per
  // time and point (moments, level counts and two quantile sketches of a
  // few hundred bins: measured 146 MB on the 320-point paper grid at 101
  // times, 1.0 GB at 1001, against 42 MB without).
  const double observed = 3072.0 * static_cast<double>(spec.observe_times.size());
  return densities * histogram + joints * (8.0 * (bins + 2) * (bins + 2) + 16.0 + 2 * histogram) +
         observed + 40.0 * trace + 256.0;
}

// Per point: the trace entries and the binned quantities, all and selected.
struct point_shape {
  double trace = 0, all_densities = 0, kept_densities = 0, all_joints = 0, kept_joints = 0;
};

point_shape shape_of(const sweep_spec& spec) {
  point_shape s;
  const double blocks = static_cast<double>(blocks_per_point(spec));
  s.trace = std::min(blocks, 64.0) + 32.0 * std::max(0.0, std::log2(blocks / 64.0)) + 1;
  for (const auto& q : quantities()) {
    if (!q.density) continue;
    s.all_densities += 1;
    if (selects(spec.statistics, q)) s.kept_densities += 1;
  }
  // Joint histograms only with the family statistics (point_statistics).
  s.all_joints = spec.family_statistics && !spec.means_only
                     ? static_cast<double>(joint_histograms().size())
                     : 0.0;
  s.kept_joints = selects_joint_histograms(spec.statistics) && !spec.means_only ? s.all_joints : 0.0;
  return s;
}

// While merged, every accumulator (point_statistics allocates them all but
// the joint histograms without the family statistics).
double merging_point_bytes(const sweep_spec& spec) {
  const auto s = shape_of(spec);
  return static_cast<double>(sizeof(point_statistics)) +
         statistics_heap(spec, s.all_densities, s.all_joints, s.trace);
}

}  // namespace

std::size_t streamed_window_points(const sweep_spec& spec, std::size_t window_points) {
  if (window_points == 0 || spec.axes.empty()) return window_points;
  const std::size_t slab = point_count(spec) / spec.axes.front().values.size();
  const double budget = 64.0 * (1u << 20);
  const auto fit = static_cast<std::size_t>(budget / merging_point_bytes(spec));
  const std::size_t rows = std::max(window_points / slab, std::min(fit / slab, streamed_window_rows));
  return std::bit_floor(std::max<std::size_t>(1, rows)) * slab;
}

double estimated_result_bytes(const sweep_spec& spec, unsigned threads,
                              std::size_t window_points, bool keeps_results) noexcept {
  const double points = static_cast<double>(point_count(spec));
  const auto shape = shape_of(spec);
  // Once finished, what the outputs read (release_unselected).
  const double merging = merging_point_bytes(spec);
  const double finished = static_cast<double>(sizeof(point_result)) +
                          statistics_heap(spec, shape.kept_densities, shape.kept_joints, shape.trace);
  const double records =
      spec.keep_records && keeps_results ? 96.0 * static_cast<double>(spec.realizations) : 0.0;
  const double window = window_points == 0 ? points : std::min(points, static_cast<double>(window_points));
  const double in_flight = std::min(static_cast<double>(resolve_threads(threads)) *
                                        static_cast<double>(units_per_batch(spec)),
                                    static_cast<double>(unit_count(spec)));
  // Without windows the merger's statistics become the result set's
  // (moved): one copy of each point at a time.
  const double finished_points = keeps_results ? points * finished : 0.0;
  const double held = window_points == 0 ? points * (merging + sizeof(model_parameters) + 64.0)
                                         : window * merging + finished_points;
  return held + points * records + in_flight * merging;
}

void check_result_memory(const sweep_spec& spec, unsigned threads, std::size_t window_points,
                         bool keeps_results) {
  const double bytes = estimated_result_bytes(spec, threads, window_points, keeps_results);
  const double ram = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) *
                     static_cast<double>(::sysconf(_SC_PAGE_SIZE));
  if (ram > 0 && bytes > 0.8 * ram) {
    // What shrinks it: the joint histograms (bins^2 cells) exist only with
    // the family statistics.
    std::string levers = "fewer grid points";
    if (!spec.observe_times.empty()) levers += ", fewer observe times";
    levers += spec.family_statistics && !spec.means_only
                  ? ", fewer bins, or a --statistics without family, derivatives and all"
                  : " or fewer bins";
    throw error(exit_code::invalid_input,
                fmt::format("invalid grid size: the results would need about {:.3g} GiB (estimated "
                            "memory; allowed: <= 80% of this machine's {:.3g} GiB): use {}",
                            bytes / (1u << 30), ram / (1u << 30), levers));
  }
}

void release_unselected(point_statistics& stats, const sweep_spec& spec) {
  if (!selects_joint_histograms(spec.statistics) || spec.means_only)
    for (const auto& j : joint_histograms()) stats.*j.counts = histogram2d{};
  for (const auto& q : quantities())
    if (q.density && !selects(spec.statistics, q)) stats.*q.density = histogram{};
}

}  // namespace stickslip::run
