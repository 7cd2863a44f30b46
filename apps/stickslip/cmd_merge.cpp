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
#include "run_wiring.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/journal.hpp"
#include "stickslip/run/merge.hpp"
#include "stickslip/io/output_files.hpp"
#include "stickslip/io/output_lock.hpp"
#include "stickslip/io/streamed_outputs.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"
#include "stickslip/uncertainty/sobol.hpp"

namespace stickslip::app {
namespace {

struct merge_options {
  std::vector<std::string> inputs;
  std::string out_dir;
  bool overwrite = false, json_histograms = false;
};

void print_problem(const std::string& p) { fmt::print(stderr, "stickslip: journal: {}\n", p); }

void run_merge(const merge_options& o, const invocation& inv) {
  std::signal(SIGXFSZ, SIG_IGN);  // past `ulimit -f`: EFBIG, reported
  {
    std::error_code ec;
    const auto st = std::filesystem::status(o.out_dir, ec);
    if (std::filesystem::exists(st) && !std::filesystem::is_directory(st))
      throw invalid_value("-o (output directory)", o.out_dir, "a directory or a new path");
  }
  // One writer of OUT until the outputs are written; a failed merge leaves
  // no OUT that it created.
  const bool existed = std::filesystem::exists(o.out_dir);
  const io::output_lock lock(o.out_dir, "stickslip merge");
  const io::output_options options{.json_joint_histograms = o.json_histograms};
  // A large grid's outputs are written window by window as it is merged
  // (io::streamed_outputs), as a sweep's: OUT holds them only once all are.
  std::optional<io::streamed_outputs> streamed;
  // The outputs say that this merge made them (its command line, its time),
  // of the configuration every journal holds; the shards' own command lines
  // (`sweep ... --shard i/n`) are not the run that wrote them.
  std::optional<io::run_metadata> this_merge;
  const auto metadata_of = [&](const io::run_metadata& shards) -> const io::run_metadata& {
    if (!this_merge) this_merge = io::make_metadata(inv.argc, inv.argv, shards.resolved_config);
    return *this_merge;
  };
  const auto stream = [&](const result_set& slab, const io::run_metadata& meta) {
    if (!streamed) {
      result_set header;  // threads and ranks as merge_shards' results
      header.spec = slab.spec;
      streamed.emplace(std::move(header), o.out_dir, options);
    }
    streamed->slab(slab, metadata_of(meta));
  };
  // A failed merge leaves nothing of its own: the stream's temporaries, and
  // OUT if this merge created it. An I/O failure then leaves through
  // exit_after_failed_write (as `sweep`: a throw past a failed HDF5 write
  // crashed at exit), which runs no destructor: clean up first.
  const auto clean_up = [&] {
    streamed.reset();
    std::error_code ec;
    if (!existed) std::filesystem::remove_all(o.out_dir, ec);
  };
  auto merged = [&] {
    try {
      if (!o.overwrite)
        io::refuse_to_replace(io::existing_sweep_results(o.out_dir), "the results of an earlier run",
                              "add --overwrite to replace them, or choose another -o OUT");
      return run::merge_shards(o.inputs, print_problem, run::default_window_points, stream);
    } catch (const error& e) {
      clean_up();
      if (e.code() == exit_code::io_failure) exit_after_failed_write(e);
      throw;
    }
  }();
  if (merged.duplicates)
    fmt::print(stderr, "stickslip: merge: {} units were in more than one journal (identical; "
                       "used once)\n", merged.duplicates);
  try {
    note_removed_outputs(
        streamed ? streamed->commit(merged.results.elapsed_seconds, metadata_of(merged.metadata))
                 : io::write_all(merged.results, metadata_of(merged.metadata), o.out_dir, options));
  } catch (const error& e) {
    clean_up();
    if (e.code() == exit_code::io_failure) exit_after_failed_write(e);
    throw;
  }
  const auto& spec = merged.results.spec;
  const auto units = unit_count(spec), points = point_count(spec);
  const auto journals = o.inputs.size();
  const bool study = is_sensitivity(spec);
  const auto est = study ? sobol_indices(merged.results.points.front().stats.sensitivity)
                         : sobol_estimates{};
  std::string what = fmt::format("{} grid point{}", points, points == 1 ? "" : "s");
  if (study)  // no figure for undefined indices: `plot` refuses them
    what = est.variance == 0.0
               ? std::string("a sensitivity study with undefined indices: no figure")
               : fmt::format("a sensitivity study; its figure: `stickslip plot {}`", o.out_dir);
  fmt::print(stderr, "merged {} unit{} from {} journal{} ({}) -> {}\n", units,
             units == 1 ? "" : "s", journals, journals == 1 ? "" : "s", what, o.out_dir);
  // A study's warning, as `sensitivity` gives it (the review: merged shards
  // said nothing of undefined or wide indices; summary.json had it), and a
  // sweep's unmet --target-ci, as `sweep` gives it.
  const auto w = study ? study_warning(spec, est) : unmet_target_note(merged.results);
  if (!w.empty()) fmt::print(stderr, "stickslip: warning: {}\n", w);
}

}  // namespace

void add_merge_command(CLI::App& app, const invocation& inv) {
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
  cmd->add_flag("--json-histograms", opts->json_histograms,
                "also write the joint (D, X) histograms into summary.json (default: results.nc only; they are most of its bytes)");
  cmd->callback([opts, inv] { run_merge(*opts, inv); });
}

}  // namespace stickslip::app
