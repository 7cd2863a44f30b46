// `stickslip merge -o OUT DIR...`: combines the journals that shard runs
// (`stickslip sweep --shard i/n -o DIR`) left in their output directories
// into the outputs of one run, bit-identical to an unsharded sweep.
// Checks: every journal was made with the same configuration, every unit is
// present (coverage), and a unit found in several journals is identical in
// each. The input journals are only read, never changed. docs/scaling.md.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <csignal>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/journal.hpp"
#include "stickslip/io/output_files.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/serialize.hpp"

namespace stickslip::app {
[[noreturn]] void exit_after_failed_write(const error& e);  // cmd_sweep.cpp

namespace {

struct merge_options {
  std::vector<std::string> inputs;
  std::string out_dir;
  bool overwrite = false;
};

void print_problem(const std::string& p) { fmt::print(stderr, "stickslip: journal: {}\n", p); }

// The configuration of the first input whose journal header is readable.
sweep_spec configuration_of(const std::vector<std::string>& dirs) {
  for (const auto& d : dirs) {
    if (!io::journal_exists(d))
      throw invalid_value("merge input", d,
                          "an output directory of `stickslip sweep --shard` holding a journal (" +
                              io::journal_path(d) + ")");
  }
  for (const auto& d : dirs) {
    const auto j = io::read_journal(d, nullptr, print_problem);
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

combined combine(const sweep_spec& spec, const std::vector<std::string>& dirs) {
  combined all;
  for (const auto& d : dirs) {
    auto j = io::read_journal(d, &spec, print_problem);  // throws resume_mismatch on another config
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

void run_merge(const merge_options& o) {
  std::signal(SIGXFSZ, SIG_IGN);  // past `ulimit -f`: EFBIG, reported
  {
    std::error_code ec;
    const auto st = std::filesystem::status(o.out_dir, ec);
    if (std::filesystem::exists(st) && !std::filesystem::is_directory(st))
      throw invalid_value("-o (output directory)", o.out_dir, "a directory or a new path");
  }
  if (!o.overwrite)
    io::refuse_to_replace(io::existing_sweep_results(o.out_dir), "the results of an earlier run",
                          "add --overwrite to replace them, or choose another -o OUT");
  const sweep_spec spec = configuration_of(o.inputs);
  validate(spec);
  combined all = combine(spec, o.inputs);
  check_coverage(spec, all);
  if (all.duplicates)
    fmt::print(stderr, "stickslip: merge: {} units were in more than one journal (identical; "
                       "used once)\n", all.duplicates);
  ordered_merger merger(spec);
  for (auto& [u, r] : all.units) merger.add(u, std::move(r));
  if (!merger.complete()) throw error(exit_code::internal, "merge: merger incomplete");
  auto rs = make_result_set(spec, std::move(merger));
  rs.elapsed_seconds = all.elapsed;
  try {
    io::write_all(rs, *all.metadata, o.out_dir);
  } catch (const error& e) {
    if (e.code() == exit_code::io_failure) exit_after_failed_write(e);  // see cmd_sweep.cpp
    throw;
  }
  fmt::print(stderr, "merged {} units from {} journals ({} grid points) -> {}\n",
             unit_count(spec), o.inputs.size(), point_count(spec), o.out_dir);
}

}  // namespace

void add_merge_command(CLI::App& app, const invocation&) {
  auto opts = std::make_shared<merge_options>();
  auto* cmd = app.add_subcommand(
      "merge",
      "Combine the journals of `sweep --shard i/n` runs into the outputs of one sweep "
      "(results.nc, summary.json, summary.csv), bit-identical to an unsharded run.");
  cmd->add_option("dirs", opts->inputs, "output directories of the shard runs")
      ->type_name("DIR")
      ->required();
  cmd->add_option("-o,--output", opts->out_dir, "directory for the merged outputs")
      ->type_name("OUT")
      ->required();
  cmd->add_flag("--overwrite", opts->overwrite,
                "replace the results of an earlier run in OUT (default: refuse and say which)");
  cmd->callback([opts] { run_merge(*opts); });
}

}  // namespace stickslip::app
