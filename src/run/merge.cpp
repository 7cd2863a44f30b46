#include "stickslip/run/merge.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <map>
#include <optional>

#include "stickslip/error.hpp"
#include "stickslip/serialize.hpp"

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
  std::map<work_unit, block_result> units;
  std::optional<io::run_metadata> metadata;
  double elapsed = 0;
  std::uint64_t duplicates = 0;
};

combined combine(const sweep_spec& spec, const std::vector<std::string>& dirs,
                 const io::journal_report& report) {
  combined all;
  for (const auto& d : dirs) {
    auto j = io::read_journal(d, &spec, report);  // throws resume_mismatch on another config
    if (!all.metadata && j.metadata) all.metadata = j.metadata;
    all.elapsed += j.elapsed_seconds;
    for (auto& [u, r] : j.units) {
      auto [it, fresh] = all.units.emplace(u, std::move(r));
      if (fresh) continue;
      if (serialize(u, it->second) != serialize(u, r))
        throw error(exit_code::io_failure,
                    fmt::format("merge: point {} block {} differs between two journals (one "
                                "of them is from another program version or damaged); '{}'",
                                u.point, u.block, d));
      ++all.duplicates;
    }
  }
  return all;
}

void check_coverage(const sweep_spec& spec, const combined& all) {
  const auto total = unit_count(spec);
  if (all.units.size() == total) return;
  std::vector<std::string> first;
  for (std::uint64_t i = 0; i < total && first.size() < 5; ++i)
    if (!all.units.count(unit_at(spec, i))) first.push_back(std::to_string(i));
  throw error(exit_code::invalid_input,
              fmt::format("merge: {} of {} work units are missing (unit indices {}{}); run the "
                          "missing shards (`stickslip sweep ... --shard i/n --resume -o DIR`) "
                          "and merge again",
                          total - all.units.size(), total, fmt::join(first, ", "),
                          total - all.units.size() > first.size() ? ", ..." : ""));
}

}  // namespace

merged_shards merge_shards(const std::vector<std::string>& dirs, const io::journal_report& report) {
  const sweep_spec spec = configuration_of(dirs, report);
  validate(spec);
  combined all = combine(spec, dirs, report);
  check_coverage(spec, all);
  ordered_merger merger(spec);
  for (auto& [u, r] : all.units) merger.add(u, std::move(r));
  if (!merger.complete()) throw error(exit_code::internal, "merge: merger incomplete");
  merged_shards out{make_result_set(spec, std::move(merger)), *all.metadata, all.duplicates};
  out.results.elapsed_seconds = all.elapsed;
  return out;
}

}  // namespace stickslip::run
