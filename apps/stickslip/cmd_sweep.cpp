// `stickslip sweep`: the paper's statistics over a parameter grid, on all
// cores, bit-identical for any thread count, written to DIR.
//
// This file only parses and prints:
//   (a) build_sweep_spec: TOML file (--config) + flags -> validated sweep_spec.
//       Nothing is touched on disk before this has succeeded.
//   (b) run::sweep_into (the run layer, stickslip/run/journaled_run.hpp): the
//       checkpoint journal DIR/.journal, --resume, --shard i/n, stop signals,
//       then the outputs (results.nc, summary.json, summary.csv, records.csv)
//       with the first run's metadata; under mpirun the units are spread over
//       the ranks (execution.hpp, backends/mpi). A progress bar on stderr
//       when it is a terminal.
// docs/scaling.md explains resume, shards and MPI.
#include <fmt/format.h>

#include <cmath>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include "commands.hpp"
#include "model_flags.hpp"
#include "execution.hpp"
#include "progress.hpp"
#include "run_wiring.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/io/journal.hpp"
#include "stickslip/io/metadata.hpp"
#include "stickslip/io/output_files.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/version.hpp"
#include "stickslip/run/journaled_run.hpp"
#include "stickslip/run/result_memory.hpp"

namespace stickslip::app {
namespace {

struct sweep_options {
  model_flags model;
  std::string config;
  std::string realizations, block_size, bins, threads = "0";
  bool records = false;
  std::string engine;
  std::string out_dir;
  bool resume = false, keep_journal = false, overwrite = false, json_histograms = false;
  std::string belt_start;
  CLI::Option* belt_start_opt = nullptr;
  std::string shard;                       // "i/n"
  std::string checkpoint_interval = "2";   // seconds between journal segments
  bool common_random_numbers = false;
  std::string target_ci, max_realizations, min_realizations;
  std::string statistics, survival_bins, burn_in, observe_times;
  CLI::Option *statistics_opt = nullptr, *survival_bins_opt = nullptr, *burn_in_opt = nullptr,
              *observe_times_opt = nullptr;
  CLI::Option *crn_opt = nullptr, *target_opt = nullptr, *max_real_opt = nullptr,
              *min_real_opt = nullptr;
  CLI::Option *config_opt = nullptr, *realizations_opt = nullptr, *block_size_opt = nullptr,
              *bins_opt = nullptr, *records_opt = nullptr, *engine_opt = nullptr;
};

// --common-random-numbers, --target-ci STAT:H [--max-realizations N]
// [--min-realizations N]. With a target, the cap per point is
// --max-realizations (default 10^6), not --realizations.
void apply_precision_flags(const sweep_options& o, sweep_spec& spec) {
  if (o.crn_opt->count() > 0) spec.common_random_numbers = o.common_random_numbers;
  if (o.target_opt->count() > 0) {
    if (o.realizations_opt->count() > 0)
      throw invalid_value("--realizations", o.realizations,
                          "not with --target-ci: the stop rule chooses the realizations per "
                          "point; cap them with --max-realizations");
    io::parse_target_ci("--target-ci", o.target_ci, spec);
    if (o.max_real_opt->count() == 0 && spec.realizations == sweep_spec{}.realizations)
      spec.realizations = 1'000'000;
  } else if (o.max_real_opt->count() > 0 || o.min_real_opt->count() > 0) {
    throw invalid_value(o.max_real_opt->count() > 0 ? "--max-realizations" : "--min-realizations",
                        o.max_real_opt->count() > 0 ? o.max_realizations : o.min_realizations,
                        "only with --target-ci STAT:HALFWIDTH");
  }
  if (o.max_real_opt->count() > 0)
    spec.realizations =
        io::parse_unsigned("--max-realizations", o.max_realizations, 1, max_realizations);
  if (o.min_real_opt->count() > 0)
    spec.min_realizations =
        io::parse_unsigned("--min-realizations", o.min_realizations, 2, max_realizations);
  // A cap below the minimum is named with where each came from (a new
  // user's --max-realizations 400 was refused as "min_realizations:
  // '1000'", a value they never gave: the default). validate() says the same
  // in the configuration's words for a target set there.
  if (o.target_opt->count() > 0 && spec.min_realizations > spec.realizations) {
    const bool min_flag = o.min_real_opt->count() > 0, max_flag = o.max_real_opt->count() > 0;
    const bool min_default = !min_flag && spec.min_realizations == sweep_spec{}.min_realizations;
    const std::string cap = max_flag ? fmt::format("--max-realizations ({})", spec.realizations)
                                     : fmt::format("the configuration's realizations ({})",
                                                   spec.realizations);
    const std::string advice = spec.realizations < 2 ? ": raise --max-realizations"
                               : min_flag            ? ""
                                                     : ": give --min-realizations too";
    throw invalid_value("--min-realizations",
                        std::to_string(spec.min_realizations) +
                            (min_flag ? "" : min_default ? " (the default)" : " (the configuration's)"),
                        "2 .. " + cap + advice);
  }
}

// --statistics LIST [--survival-bins N] [--burn-in T] [--observe-times GRID]
// (over the configuration's).
void apply_statistics_flags(const sweep_options& o, sweep_spec& spec) {
  if (o.burn_in_opt->count() > 0)
    spec.burn_in = io::parse_number("--burn-in", o.burn_in);  // 0 <= T < t_a: validate()
  // The axes' grid syntax; ascending and <= t_a: validate().
  if (o.observe_times_opt->count() > 0)
    spec.observe_times =
        io::parse_grid("--observe-times", o.observe_times, io::grid_domain::non_negative);
  if (o.statistics_opt->count() > 0)
    spec.statistics = parse_statistics_selection("--statistics", o.statistics);
  if (o.survival_bins_opt->count() == 0) return;
  if (!spec.statistics.survival)
    throw invalid_value("--survival-bins", o.survival_bins,
                        "only with the survival statistics (--statistics survival or all)");
  spec.survival.bins = static_cast<std::size_t>(
      io::parse_unsigned("--survival-bins", o.survival_bins, 1, max_histogram_bins));
}

// (a) The resolved, validated spec: defaults < --config file < --preset < flags.
sweep_spec build_sweep_spec(const CLI::App& cmd, const sweep_options& o) {
  sweep_spec spec = o.config_opt->count() > 0 ? io::read_sweep_toml_file(o.config) : sweep_spec{};
  if (!spec.sensitivity_statistic.empty() ||
      (spec.target_statistic.empty() && spec.target_halfwidth != 0.0))
    throw invalid_value("--config", o.config,
                        "a sweep's configuration: sensitivity_statistic and target_halfwidth "
                        "belong to a sensitivity study (`stickslip sensitivity`), not a sweep");
  apply_model_flags(cmd, o.model, spec, true);
  spec.seed = resolve_seed(o.model, spec.seed);
  spec.max_events = resolve_max_events(o.model, spec.max_events);
  if (o.realizations_opt->count() > 0)
    spec.realizations = io::parse_unsigned("--realizations", o.realizations, 1, max_realizations);
  if (o.block_size_opt->count() > 0)
    spec.block_size = io::parse_unsigned("--block-size", o.block_size, 1, max_block_size);
  if (o.bins_opt->count() > 0)
    spec.histograms.bins = static_cast<std::size_t>(io::parse_unsigned("--bins", o.bins, 1, max_histogram_bins));
  if (o.records_opt->count() > 0) spec.keep_records = o.records;
  if (o.belt_start_opt->count() > 0)
    spec.initial.belt_start =
        io::parse_belt_start("--belt-start", o.belt_start, spec.base.levels().size());
  if (o.engine_opt->count() > 0) spec.engine = io::parse_engine("--engine", o.engine);
  apply_precision_flags(o, spec);
  apply_statistics_flags(o, spec);
  apply_statistics_selection(spec);
  resolve_survival_grid(spec);
  validate(spec);
  return spec;
}

// The output directory must be a directory or not exist yet; it is created
// only by the writers, after the run.
void check_output_dir(const std::string& dir) {
  std::error_code ec;
  const auto st = std::filesystem::status(dir, ec);
  if (std::filesystem::exists(st) && !std::filesystem::is_directory(st))
    throw invalid_value("-o (output directory)", dir, "a directory or a path that does not exist");
}

// --resume found this configuration's finished outputs and no journal.
void report_already_complete(const run::run_plan& plan, const io::run_metadata& written_by) {
  fmt::print(stderr, "stickslip: {} already holds the complete results of this configuration "
                     "(written {}): nothing to do, they are left as they are\n",
             plan.dir, written_by.created_utc);
  // An unmet precision target, as the run said it and the outputs record it
  // (a --resume of such a run said only "nothing to do").
  if (const auto note = io::read_finished_warning(plan.dir); !note.empty())
    fmt::print(stderr, "stickslip: warning: {}\n", note);
  if (written_by.version != stickslip::version || written_by.git_revision != stickslip::git_revision)
    fmt::print(stderr, "stickslip: note: they were written by stickslip {} (git {}), this is {} "
                       "(git {}); add --overwrite to recompute them with this build\n",
               written_by.version, written_by.git_revision, stickslip::version,
               stickslip::git_revision);
}

void report(const sweep_spec& spec, const run::run_plan& plan, const run::run_outcome& out,
            const run::runner& r) {
  if (out.already_complete) return report_already_complete(plan, out.metadata);
  const std::string thread_text =
      fmt::format("{} thread{}", r.threads(), r.threads() == 1 ? "" : "s");
  const std::string where =
      r.ranks() > 1 ? fmt::format("{} ranks x {}", r.ranks(), thread_text) : thread_text;
  const std::string resumed =
      out.resumed_units ? fmt::format(", {} units from the journal", out.resumed_units) : "";
  if (plan.slice) {
    fmt::print(stderr, "shard {}/{}: {} units in {:.3g} s ({}{}) journaled in {}; combine the "
                       "shards with `stickslip merge`\n",
               plan.slice->index, plan.slice->count, out.computed_units, out.elapsed_this_run,
               where, resumed, io::journal_path(plan.dir));
    return;
  }
  std::uint64_t n = point_count(spec) * spec.realizations;
  if (out.results && !out.results->points.empty()) {  // with --target-ci, what the stop rule chose
    n = 0;
    for (const auto& p : out.results->points) n += p.stats.realizations;
  }
  const auto points = point_count(spec);
  fmt::print(stderr, "{} realization{} in {:.3g} s ({} grid point{}, {}{}) -> {}\n", n,
             n == 1 ? "" : "s", out.elapsed_this_run, points, points == 1 ? "" : "s", where,
             resumed, plan.dir);
  if (out.results)
    if (const auto note = unmet_target_note(*out.results); !note.empty())
      fmt::print(stderr, "stickslip: warning: {}\n", note);
}

// The command's results, kept until the process ends: it ends right after
// the command, and the system takes the memory back at once, where freeing
// it vector by vector took a 101-observe-time paper grid 30 ms on one core
// after its outputs were written (compilers do the same: clang's
// -disable-free). Reachable from here, so a leak checker reports nothing.
void keep_until_exit(run::run_outcome&& out) {
  static auto* const kept = new std::vector<run::run_outcome>();
  kept->push_back(std::move(out));
}

void run_sweep_command(const CLI::App& cmd, const sweep_options& o, const invocation& inv) {
  // Past `ulimit -f` a write must fail with EFBIG (reported), not kill us.
  std::signal(SIGXFSZ, SIG_IGN);
  // From here to the end (outputs written): a stop signal requests a stop (no
  // unit starts after it), on every rank until the workers ignore it.
  run::stop_token stop;
  run::stop_on_signals signals(stop);
  const auto threads =
      static_cast<unsigned>(io::parse_unsigned("--threads", o.threads, 0, 1u << 16));
  execution exec(threads);
  if (exec.is_worker()) return exec.serve();  // rank 0 reports everything

  const sweep_spec spec = build_sweep_spec(cmd, o);
  run::run_plan plan;
  plan.replace_advice =
      "add --overwrite to replace them, --resume to continue an interrupted sweep, or choose "
      "another -o DIR";
  plan.dir = o.out_dir;
  plan.slice = run::parse_shard(o.shard);
  plan.outputs.json_joint_histograms = o.json_histograms;
  plan.writer = plan.slice ? "stickslip sweep --shard " + o.shard : std::string("stickslip sweep");
  plan.resume = o.resume;
  plan.overwrite = o.overwrite;
  // Before DIR is touched, with what the run will hold (a large grid runs
  // window by window, also under MPI, and streams its outputs).
  run::check_result_memory(spec, threads, run::sweep_memory_window(spec, plan, exec.runner()),
                           !plan.slice && !run::streams_outputs(spec, plan, exec.runner()));
  check_output_dir(o.out_dir);
  progress_bar bar;
  wire_run_plan(plan, o.checkpoint_interval, stop, bar);

  try {
    auto out = run::sweep_into(spec, plan, io::make_metadata(inv.argc, inv.argv, io::to_toml(spec)),
                               exec.runner(), o.keep_journal);
    bar.finish();
    note_removed_outputs(out.removed_outputs);
    report(spec, plan, out, exec.runner());
    keep_until_exit(std::move(out));
  } catch (const error& e) {
    end_failed_run(e, bar, exec);
  }
}

}  // namespace

void add_sweep_command(CLI::App& app, const invocation& inv) {
  auto opts = std::make_shared<sweep_options>();
  auto* cmd = app.add_subcommand(
      "sweep",
      "Statistics (R, S_T/t_a, S_L/t_a, D, D_1, H) over a grid of model parameters, "
      "bit-identical for any thread count; writes results.nc, summary.json, summary.csv "
      "(and records.csv with --records) to DIR.");
  auto& o = *opts;
  add_model_flags(*cmd, o.model, flag_values::grid, model_parameters{});
  o.belt_start_opt =
      cmd->add_option("--belt-start", o.belt_start,
                      "starting belt level of every realization: stationary (the stationary law "
                      "of the belt, 50/50 for the paper), +1 / -1 (first / second of two "
                      "levels), or a level number 1..n (default stationary)")
          ->type_name("LEVEL")
          ->group("Model family (docs/models.md)");
  o.config_opt = cmd->add_option("--config", o.config,
                                 "TOML file with the same settings (docs/config.md); flags "
                                 "override it")
                     ->type_name("FILE");
  o.realizations_opt =
      cmd->add_option("--realizations", o.realizations, "realizations per grid point (default 2000)")
          ->type_name("N");
  cmd->add_option("--threads", o.threads, "worker threads, 0 = all cores (default 0)")
      ->type_name("T");
  o.block_size_opt =
      cmd->add_option("--block-size", o.block_size,
                      "realizations per work unit; part of the result's identity (default 50)")
          ->type_name("B");
  o.bins_opt = cmd->add_option("--bins", o.bins, "histogram bins (default 50)")->type_name("N");
  o.records_opt =
      cmd->add_flag("--records", o.records,
                    "keep raw per-realization records (records.csv; memory grows with N)");
  o.engine_opt = cmd->add_option("--engine", o.engine,
                                 "fast (default: SIMD lanes) or reference (one realization at a "
                                 "time, the plain exact path); results are bit-identical")
                     ->type_name("NAME");
  o.statistics_opt =
      cmd->add_option("--statistics", o.statistics,
                      fmt::format("what to compute and write, a comma list of {}. "
                                  "Groups: {}. Unselected statistics are not written, and the "
                                  "engine computes the family statistics and the histograms "
                                  "only when asked (docs/outputs.md, \"Choosing statistics\"; "
                                  "default: paper)",
                                  statistics_group_names(), statistics_group_descriptions()))
          ->type_name("LIST");
  o.burn_in_opt = cmd->add_option("--burn-in", o.burn_in,
                                  "count only [T, t_a]: every statistic over the window after "
                                  "the burn-in T [s], 0 <= T < t_a (default 0, the whole "
                                  "window; docs/outputs.md, \"Burn-in\")")
                      ->type_name("T");
  o.observe_times_opt =
      cmd->add_option("--observe-times", o.observe_times,
                      "also keep the ensemble's state at these times [s], ascending, 0 <= t <= "
                      "t_a, a list 't1,t2,...' or 'lin:a:b:n': the stick probability, mean and "
                      "variance of x, x', x' - v and the energy, belt level occupancy, "
                      "quantiles of x and x' over a coordinate `time` (docs/outputs.md, "
                      "\"Observe times\")")
          ->type_name("GRID");
  o.survival_bins_opt = cmd->add_option("--survival-bins", o.survival_bins,
                                        "bins of the survival grid: [0, d_max] for sticks, "
                                        "[0, t_a] for slips, the largest over the grid (default "
                                        "200)")
                            ->type_name("N");
  const char* precision = "Precision (docs/precision.md)";
  o.crn_opt = cmd->add_flag("--common-random-numbers", o.common_random_numbers,
                            "realization r of every grid point uses the same random numbers "
                            "(initial state, unit exponentials of the switch times): smooth "
                            "curves, low-variance differences; points are then correlated")
                  ->group(precision);
  o.target_opt = cmd->add_option("--target-ci", o.target_ci,
                                 fmt::format("run blocks at each point until the 95% half-width "
                                             "of the mean of STAT ({}) is <= HALFWIDTH",
                                             mean_statistic_names()))
                     ->type_name("STAT:HALFWIDTH")
                     ->group(precision);
  o.max_real_opt = cmd->add_option("--max-realizations", o.max_realizations,
                                   "with --target-ci: at most N realizations per point "
                                   "(default 1000000; below the minimum, 1000 by default, give "
                                   "--min-realizations too)")
                       ->type_name("N")
                       ->group(precision);
  o.min_real_opt = cmd->add_option("--min-realizations", o.min_realizations,
                                   "with --target-ci: at least N realizations per point before "
                                   "the stop rule applies (default 1000)")
                       ->type_name("N")
                       ->group(precision);
  cmd->add_option("-o,--output", o.out_dir,
                  "output directory; holds the checkpoint journal DIR/.journal while running")
      ->type_name("DIR")
      ->required();
  cmd->add_flag("--resume", o.resume,
                "continue the sweep journaled in DIR (after a crash, kill or time limit); "
                "refused if the configuration changed. Without a journal: nothing to do if DIR "
                "holds this configuration's finished results, refused if it holds another's "
                "(unless --overwrite), else starts afresh");
  cmd->add_option("--shard", o.shard,
                  "run only units with index % n == i and journal them in DIR (no final "
                  "outputs); combine shards with `stickslip merge`")
      ->type_name("i/n");
  cmd->add_option("--checkpoint-interval", o.checkpoint_interval,
                  "minimum seconds between journal segments (each is fsynced; more while a "
                  "checkpoint would cost over 5 %, up to 15 times this); 0 = after every unit "
                  "(default 2)")
      ->type_name("SECONDS");
  cmd->add_flag("--overwrite", o.overwrite,
                "replace the results of an earlier run in DIR (default: refuse and say which)");
  cmd->add_flag("--keep-journal", o.keep_journal,
                "keep DIR/.journal after the outputs are written (default: remove it)");
  cmd->add_flag("--json-histograms", o.json_histograms,
                "also write the joint (D, X) histograms into summary.json (default: results.nc only; they are most of its bytes)");
  cmd->callback([cmd, opts, inv] { run_sweep_command(*cmd, *opts, inv); });
}

}  // namespace stickslip::app
