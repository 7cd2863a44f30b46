#include "stickslip/run/result_memory.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "stickslip/error.hpp"
#include "stickslip/run/runner.hpp"
#include "stickslip/statistics_schema.hpp"

namespace stickslip::run {

double estimated_result_bytes(const sweep_spec& spec, unsigned threads) noexcept {
  const double points = static_cast<double>(point_count(spec));
  const double blocks = static_cast<double>(blocks_per_point(spec));
  const double trace = std::min(blocks, 64.0) + 32.0 * std::max(0.0, std::log2(blocks / 64.0)) + 1;
  const double bins = static_cast<double>(spec.histograms.bins);
  // The observe times (accumulators/time_statistics.hpp): about 3 KB per
  // time and point (moments, level counts and two quantile sketches of a
  // few hundred bins: measured 146 MB on the 320-point paper grid at 101
  // times, 1.0 GB at 1001, against 42 MB without).
  const double observed = 3072.0 * static_cast<double>(spec.observe_times.size());
  const double statistics = 1024.0 + 4.0 * 8.0 * bins +
                            8.0 * bins * bins * static_cast<double>(joint_histograms().size()) +
                            observed;
  const double records = spec.keep_records ? 96.0 * static_cast<double>(spec.realizations) : 0.0;
  const double in_flight = std::min(static_cast<double>(resolve_threads(threads)) *
                                        static_cast<double>(units_per_batch(spec)),
                                    static_cast<double>(unit_count(spec)));
  return 2.0 * points * (statistics + 40.0 * trace + records) + in_flight * statistics;
}

void check_result_memory(const sweep_spec& spec, unsigned threads) {
  const double bytes = estimated_result_bytes(spec, threads);
  const double ram = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) *
                     static_cast<double>(::sysconf(_SC_PAGE_SIZE));
  if (ram > 0 && bytes > 0.8 * ram)
    throw error(exit_code::invalid_input,
                fmt::format("invalid grid size: the results would need about {:.3g} GiB (estimated "
                            "memory; allowed: <= 80% of this machine's {:.3g} GiB): "
                            "use fewer grid points, bins{}",
                            bytes / (1u << 30), ram / (1u << 30),
                            spec.observe_times.empty() ? "" : " or observe times"));
}

}  // namespace stickslip::run
