#include "stickslip/run/merge.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <map>
#include <set>
#include <optional>

#include "stickslip/error.hpp"
#include "stickslip/io/streamed_outputs.hpp"
#include "stickslip/run/shard.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"
#include "grid_windows.hpp"

namespace stickslip::run {
namespace {

// The configuration of the first input whose journal header is readable.
sweep_spec configuration_of(const std::vector<std::string>& dirs, const io::journal_report& report) {
  for (const auto& d : dirs) {
    if (!io::journal_exists(d))
      throw invalid_value("merge input", d,
                          "an output directory of `stickslip sweep --shard` holding a journal (" +
                              io::journal_path(d) + ")");
  }
  for (const auto& d : dirs) {
    const auto j = io::read_journal(d, nullptr, report);
    if (j.spec) return *j.spec;
  }
  throw error(exit_code::io_failure, "merge: no input journal has a readable header");
}

struct combined {
  std::map<work_unit, io::journaled_unit> units;
  std::map<std::size_t, io::journaled_prefix> prefixes;  // the longest per point
  std::optional<io::run_metadata> metadata;
  std::set<std::string> runs;  // the journals' run ids
  double elapsed = 0;
  std::uint64_t duplicates = 0;
};

combined combine(const sweep_spec& spec, const std::vector<std::string>& dirs,
                 const io::journal_report& report) {
  combined all;
  io::journal_readback journal;  // for units and prefixes present twice
  for (const auto& d : dirs) {
    auto j = io::read_journal(d, &spec, report);  // throws resume_mismatch on another config
    if (!all.metadata && j.metadata) all.metadata = j.metadata;
    all.elapsed += j.elapsed_seconds;
    all.runs.insert(j.runs.begin(), j.runs.end());
    for (auto& [point, p] : j.prefixes) {  // from a whole run's journal in the inputs
      auto [it, fresh] = all.prefixes.emplace(point, p);
      if (fresh || it->second.blocks > p.blocks) continue;
      if (it->second.blocks < p.blocks) {
        it->second = std::move(p);
      } else if (journal.bytes(it->second.place) != journal.bytes(p.place)) {
        throw error(exit_code::io_failure,
                    fmt::format("merge: the merged first {} blocks of point {} differ between "
                                "two journals (one of them is from another program version or "
                                "damaged); '{}'",
                                p.blocks, point, d));
      }
    }
    for (auto& [u, r] : j.units) {
      auto [it, fresh] = all.units.try_emplace(u, r);
      if (fresh) continue;
      if (journal.bytes(it->second.place) != journal.bytes(r.place))
        throw error(exit_code::io_failure,
                    fmt::format("merge: point {} block {} differs between two journals (one "
                                "of them is from another program version or damaged); '{}'",
                                u.point, u.block, d));
      ++all.duplicates;
    }
  }
  return all;
}

// The n of the shards that wrote the journals (shard::of_run), or 0 when
// they are not all shards of one n.
std::uint64_t shard_count(const std::set<std::string>& runs) {
  std::uint64_t n = 0;
  for (const auto& run : runs) {
    const auto s = shard::of_run(run);
    if (!s || (n != 0 && n != s->count)) return 0;
    n = s->count;
  }
  return n;
}

// Units a prefix covers are dropped first; every other unit must be there.
void check_coverage(const sweep_spec& spec, combined& all) {
  std::erase_if(all.units, [&](const auto& kv) {
    const auto it = all.prefixes.find(kv.first.point);
    return it != all.prefixes.end() && kv.first.block < it->second.blocks;
  });
  const auto total = unit_count(spec);
  const auto covered = [&](const work_unit& u) {
    const auto it = all.prefixes.find(u.point);
    return (it != all.prefixes.end() && u.block < it->second.blocks) || all.units.count(u) > 0;
  };
  const std::uint64_t n = shard_count(all.runs);  // 0: not known
  std::uint64_t missing = 0;
  std::vector<std::string> first;
  std::set<std::uint64_t> shards;  // of the missing units, when n is known
  for (std::uint64_t i = 0; i < total; ++i) {
    if (covered(unit_at(spec, i))) continue;
    if (++missing <= 5) first.push_back(std::to_string(i));
    if (n) shards.insert(i % n);  // the shard that owns unit i (shard::owns)
  }
  if (missing == 0) return;
  std::vector<std::string> names;
  for (const auto i : shards) names.push_back(fmt::format("{}/{}", i, n));
  const std::string whose =
      names.empty() ? ""
                    : fmt::format("; they are shard{} {}'s", names.size() == 1 ? "" : "s",
                                  fmt::join(names, ", "));
  throw error(exit_code::invalid_input,
              fmt::format("merge: {} of {} work units are missing (unit indices {}{}{}); run the "
                          "missing shards (`stickslip {} ... --shard i/n --resume -o DIR`) "
                          "and merge again",
                          missing, total, fmt::join(first, ", "), missing > first.size() ? ", ..." : "",
                          whose, is_sensitivity(spec) ? "sensitivity" : "sweep"));
}

}  // namespace

merged_shards merge_shards(const std::vector<std::string>& dirs, const io::journal_report& report,
                           std::size_t window_points, const slab_stream& stream) {
  const sweep_spec spec = configuration_of(dirs, report);
  validate(spec);
  combined all = combine(spec, dirs, report);
  check_coverage(spec, all);
  // Window by window, as run_journaled (grid_windows.hpp): one window's
  // accumulators at a time, and the journaled units leave the maps as
  // their window is merged.
  const bool windowed = detail::splits_into_windows(spec, window_points);
  const bool streamed = windowed && stream && io::streams_outputs(spec);
  if (streamed) window_points = streamed_window_points(spec, window_points);
  merged_shards out{result_set{}, *all.metadata, all.duplicates};
  out.results.spec = spec;
  if (!streamed) out.results.points.reserve(point_count(spec));
  if (spec.keep_records) out.results.records.reserve(point_count(spec));
  for (const auto& w : detail::windows_of(spec, window_points)) {
    ordered_merger merger(w.spec);
    detail::restore_window(w, all.prefixes, all.units, merger);
    if (!merger.complete()) throw error(exit_code::internal, "merge: merger incomplete");
    if (streamed)
      stream(detail::slab_of(spec, make_result_set(w.spec, std::move(merger)), w.offset),
             out.metadata);
    else
      detail::append_window(out.results, make_result_set(w.spec, std::move(merger)), w.offset,
                            windowed);
  }
  out.results.elapsed_seconds = all.elapsed;
  return out;
}

}  // namespace stickslip::run
