// A spec's identity: which of its fields decide the results, the fingerprint
// the journal stamps, and the first field in which two specs differ.
#include "stickslip/serialize.hpp"

#include <bit>
#include <fmt/format.h>

#include "fnv1a.hpp"
#include "stickslip/fast_math.hpp"
#include "stickslip/version.hpp"

namespace stickslip {

namespace {
// The spec with the fields that cannot change results reset: the engine.
sweep_spec results_relevant(sweep_spec s) {
  s.engine = sweep_engine{};
  return s;
}
}  // namespace

bool same_results(const sweep_spec& a, const sweep_spec& b) {
  return serialize(results_relevant(a)) == serialize(results_relevant(b));
}

std::uint64_t fingerprint(const sweep_spec& s) {
  // The build is part of the identity: another version, revision or SIMD
  // target may round differently, and its units must not be mixed in.
  const std::string build = std::string(stickslip::version) + '|' + stickslip::git_revision +
                            '|' + detail::fm::target_name();
  return detail::fnv1a_of(build + serialize(results_relevant(s)));
}

std::string first_difference(const sweep_spec& a, const sweep_spec& b) {
  auto num = [](double x) { return fmt::format("{}", x); };
  for (const char* name : recorded_parameter_names) {
    const double x = parameter_value(a.base, name), y = parameter_value(b.base, name);
    if (std::bit_cast<std::uint64_t>(x) != std::bit_cast<std::uint64_t>(y))
      return fmt::format("parameter {}: {} vs {}", name, num(x), num(y));
  }
  if (a.base.levels() != b.base.levels()) return "belt levels";
  if (a.base.generator() != b.base.generator()) return "belt rates or generator";
  if (!(a.initial == b.initial)) return "initial-condition law (x0, xdot0 ranges or belt start)";
  if (a.axes.size() != b.axes.size())
    return fmt::format("number of grid axes: {} vs {}", a.axes.size(), b.axes.size());
  for (std::size_t i = 0; i < a.axes.size(); ++i) {
    if (a.axes[i].name != b.axes[i].name)
      return fmt::format("grid axis #{}: {} vs {}", i + 1, a.axes[i].name, b.axes[i].name);
    if (a.axes[i].values.size() != b.axes[i].values.size())
      return fmt::format("grid axis {}: {} values vs {}", a.axes[i].name,
                         a.axes[i].values.size(), b.axes[i].values.size());
    for (std::size_t k = 0; k < a.axes[i].values.size(); ++k)
      if (std::bit_cast<std::uint64_t>(a.axes[i].values[k]) !=
          std::bit_cast<std::uint64_t>(b.axes[i].values[k]))
        return fmt::format("grid axis {} value #{}: {} vs {}", a.axes[i].name, k + 1,
                           num(a.axes[i].values[k]), num(b.axes[i].values[k]));
  }
  // A sensitivity study's realizations are its design's rows (a new user
  // read "realizations: 256 vs 512" after giving --samples), set by
  // --samples or by a stop rule: each side in its own flags (a review).
  const bool study = !a.sensitivity_statistic.empty() && !b.sensitivity_statistic.empty();
  if (study && (a.realizations != b.realizations || a.target_halfwidth != b.target_halfwidth ||
                (a.target_halfwidth > 0.0 && a.min_realizations != b.min_realizations))) {
    const auto rows = [](const sweep_spec& s) {
      return s.target_halfwidth > 0.0
                 ? fmt::format("a target half-width {} in {} to {} rows (--target-halfwidth, "
                               "--min-samples, --max-samples)",
                               s.target_halfwidth, s.min_realizations, s.realizations)
                 : fmt::format("{} rows (--samples)", s.realizations);
    };
    return fmt::format("design: {} vs {}", rows(a), rows(b));
  }
  if (a.realizations != b.realizations)
    return fmt::format("realizations: {} vs {}", a.realizations, b.realizations);
  if (a.seed != b.seed) return fmt::format("seed: {} vs {}", a.seed, b.seed);
  if (a.block_size != b.block_size)
    return fmt::format("block size: {} vs {}", a.block_size, b.block_size);
  if (!(a.histograms == b.histograms)) return "histogram bins or ranges";
  if (a.max_events != b.max_events)
    return fmt::format("max events: {} vs {}", a.max_events, b.max_events);
  if (a.keep_records != b.keep_records)
    return fmt::format("keep records: {} vs {}", a.keep_records, b.keep_records);
  if (a.common_random_numbers != b.common_random_numbers)
    return fmt::format("common random numbers: {} vs {}", a.common_random_numbers,
                       b.common_random_numbers);
  if (a.target_statistic != b.target_statistic || a.target_halfwidth != b.target_halfwidth ||
      a.min_realizations != b.min_realizations)
    return fmt::format("target CI: {}:{} (min {}) vs {}:{} (min {})", a.target_statistic,
                       a.target_halfwidth, a.min_realizations, b.target_statistic,
                       b.target_halfwidth, b.min_realizations);
  // The selection first: the engine settings below follow from it.
  if (!(a.statistics == b.statistics))
    return fmt::format("statistics: {} vs {}", to_string(a.statistics), to_string(b.statistics));
  if (a.family_statistics != b.family_statistics)
    return fmt::format("family statistics: {} vs {}", a.family_statistics, b.family_statistics);
  if (a.means_only != b.means_only)
    return fmt::format("means only: {} vs {}", a.means_only, b.means_only);
  auto laws = [](const sweep_spec& s) {
    std::string t;
    for (const auto& u : s.uncertain)
      t += (t.empty() ? "" : ", ") + u.symbol + " ~ " + to_string(u.law);
    return t.empty() ? std::string("none") : t;
  };
  if (a.uncertain != b.uncertain)
    return fmt::format("uncertain parameters: {} vs {}", laws(a), laws(b));
  if (a.sensitivity_statistic != b.sensitivity_statistic)
    return fmt::format("sensitivity statistic: '{}' vs '{}'", a.sensitivity_statistic,
                       b.sensitivity_statistic);
  if (a.statistics.survival && !(a.survival == b.survival))
    return fmt::format("survival grid: {} bins on [0, {}] s and [0, {}] s vs {} bins on [0, {}] s "
                       "and [0, {}] s",
                       a.survival.bins, a.survival.stick_duration_max,
                       a.survival.slip_duration_max, b.survival.bins,
                       b.survival.stick_duration_max, b.survival.slip_duration_max);
  if (a.burn_in != b.burn_in) return fmt::format("burn-in: {} s vs {} s", a.burn_in, b.burn_in);
  if (a.observe_times != b.observe_times)
    return fmt::format("observe times: {} vs {}", a.observe_times.size(), b.observe_times.size());
  if (!same_results(a, b)) return "bit patterns of some value";
  return {};
}

}  // namespace stickslip
