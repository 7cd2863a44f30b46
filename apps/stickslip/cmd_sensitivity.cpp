// `stickslip sensitivity`: Sobol' indices of a per-realization statistic over
// uncertain model parameters (docs/uncertainty.md). The model flags take laws
// for the uncertain inputs (`--mu 'uniform(2,7)'`) and values for the rest.
//
// This file only parses and prints. The study is a sweep_spec with
// sensitivity_statistic set (uncertainty/sensitivity_design.hpp), run by the
// run layer like any sweep: journal, --resume, --shard, MPI, the writer lock
// and the progress bar are the sweep's. The outputs are sensitivity.nc,
// summary.json and the figure sensitivity.{png,svg} (with its .dat and .gp).
#include <fmt/format.h>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>

#include "commands.hpp"
#include "execution.hpp"
#include "model_flags.hpp"
#include "progress.hpp"
#include "run_wiring.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/io/metadata.hpp"
#include "stickslip/io/result_file.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/run/journaled_run.hpp"
#include "stickslip/study/sensitivity_figure.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/uncertainty/parameter_law.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"
#include "stickslip/uncertainty/sobol.hpp"

namespace stickslip::app {
namespace {

struct sensitivity_options {
  model_flags model;
  std::string statistic = "R";
  std::string samples, target_halfwidth, max_samples, min_samples, block_size;
  std::string threads = "0", format = "text", out_dir, shard, checkpoint_interval = "2";
  bool resume = false, overwrite = false, keep_journal = false, no_figure = false;
  CLI::Option *samples_opt = nullptr, *target_opt = nullptr, *max_opt = nullptr,
              *min_opt = nullptr, *block_opt = nullptr;
};

sweep_spec build_spec(const CLI::App& cmd, const sensitivity_options& o) {
  sweep_spec spec;
  apply_model_flags(cmd, o.model, spec, /*grids_allowed=*/false);
  spec.seed = resolve_seed(o.model, spec.seed);
  spec.max_events = resolve_max_events(o.model, spec.max_events);
  sensitivity_choice c;
  c.statistic = o.statistic;
  auto rows = [](const char* flag, const std::string& text) {  // variances need two rows
    return io::parse_unsigned(flag, text, 2, max_realizations);
  };
  if (o.samples_opt->count() > 0) c.samples = rows("--samples", o.samples);
  if (o.max_opt->count() > 0) c.max_samples = rows("--max-samples", o.max_samples);
  if (o.min_opt->count() > 0) c.min_samples = rows("--min-samples", o.min_samples);
  if (o.block_opt->count() > 0)
    c.block_size = io::parse_unsigned("--block-size", o.block_size, 1, max_block_size);
  if (o.target_opt->count() > 0)
    c.target_halfwidth = io::parse_number("--target-halfwidth", o.target_halfwidth);
  set_sensitivity_design(spec, c);
  validate(spec);
  return spec;
}

void print_text(const result_set& rs, const run::run_outcome& out, const std::string& dir) {
  const auto est = sobol_indices(rs.points.front().stats.sensitivity);
  const auto& q = sensitivity_quantity(rs.spec);
  fmt::print("Sobol' indices of E[{} | theta]: {} samples, {} realizations, {:.3g} s\n",
             q.summary_name, est.rows, est.rows * runs_per_row(rs.spec),
             out.elapsed_this_run);
  fmt::print("{:<10} {:<34} {:>26} {:>26} {:>26}\n", "input", "law", "first order [95% CI]",
             "total order [95% CI]", "first order in STAT");
  auto ci = [](const interval_estimate& e) {
    return fmt::format("{:.4f} [{:.4f}, {:.4f}]", e.value, e.low, e.high);
  };
  for (std::size_t i = 0; i < rs.spec.uncertain.size(); ++i)
    fmt::print("{:<10} {:<34} {:>26} {:>26} {:>26}\n", rs.spec.uncertain[i].symbol,
               to_string(rs.spec.uncertain[i].law), ci(est.first_order[i]), ci(est.total_order[i]),
               ci(est.response_first_order[i]));
  fmt::print("shares of Var {}: parameters {}, intrinsic {}\n", q.summary_name,
             ci(est.parameter_share), ci(est.intrinsic_share));
  fmt::print("-> {}\n", dir);
}

void run_sensitivity_command(const CLI::App& cmd, const sensitivity_options& o,
                             const invocation& inv) {
  std::signal(SIGXFSZ, SIG_IGN);
  run::stop_token stop;
  run::stop_on_signals signals(stop);
  const auto threads =
      static_cast<unsigned>(io::parse_unsigned("--threads", o.threads, 0, 1u << 16));
  execution exec(threads);
  if (exec.is_worker()) return exec.serve();

  if (o.format != "text" && o.format != "json")
    throw invalid_value("--format", o.format, "text or json");
  const sweep_spec spec = build_spec(cmd, o);
  std::error_code ec;
  if (std::filesystem::exists(o.out_dir, ec) && !std::filesystem::is_directory(o.out_dir, ec))
    throw invalid_value("-o (output directory)", o.out_dir,
                        "a directory or a path that does not exist");
  run::run_plan plan;
  plan.dir = o.out_dir;
  plan.slice = run::parse_shard(o.shard);
  plan.writer = plan.slice ? "stickslip sensitivity --shard " + o.shard
                           : std::string("stickslip sensitivity");
  plan.replace_advice =
      "add --overwrite to replace them, --resume to continue an interrupted study, or choose "
      "another -o DIR";
  plan.resume = o.resume;
  plan.overwrite = o.overwrite;
  progress_bar bar;
  wire_run_plan(plan, o.checkpoint_interval, stop, bar);
  // The study's warning (undefined indices) as its sensitivity.nc records
  // it: the same for a run just written and a finished one --resume finds.
  const auto recorded_warning = [&] {
    const io::result_file written((std::filesystem::path(plan.dir) / io::sensitivity_file).string());
    return written.attribute("warning");
  };
  try {
    const auto out = run::sweep_into(spec, plan,
                                     io::make_metadata(inv.argc, inv.argv, io::to_toml(spec)),
                                     exec.runner(), o.keep_journal);
    bar.finish();
    if (plan.slice) {
      fmt::print(stderr, "shard {}/{}: {} units journaled in {}; combine the shards with "
                         "`stickslip merge`\n",
                 plan.slice->index, plan.slice->count, out.computed_units, plan.dir);
      return;
    }
    if (out.already_complete) {
      fmt::print(stderr, "stickslip: {} already holds this study's complete results: nothing "
                         "to do (summary.json has them)\n", plan.dir);
      if (const auto note = recorded_warning(); !note.empty())
        fmt::print(stderr, "stickslip: warning: {}\n", note);
      if (o.format == "json") {  // the finished study's numbers, as a run would print them
        std::ifstream in(std::filesystem::path(plan.dir) / io::summary_json_file);
        fmt::print("{}", std::string(std::istreambuf_iterator<char>(in), {}));
      }
      return;
    }
    const result_set& rs = *out.results;
    // Undefined indices (variance 0) have no bars to draw: no figure. Wide
    // ones are drawn, with their warning.
    const auto warning = recorded_warning();
    const bool undefined = sobol_indices(rs.points.front().stats.sensitivity).variance == 0.0;
    if (!warning.empty())
      fmt::print(stderr, "stickslip: warning: {}{}\n", warning, undefined ? "; no figure is drawn" : "");
    if (!o.no_figure && !undefined) {
      const auto f = study::write_sensitivity_figure(rs, o.out_dir, true);
      if (!f.rendered)
        fmt::print(stderr, "stickslip: note: the figure was not rendered (gnuplot with pngcairo "
                           "and svg is needed); its data and script are in {}\n", o.out_dir);
    }
    // After the figure: its files, drawn again, are not named as removed.
    note_removed_outputs(out.removed_outputs);
    if (o.format == "json")
      fmt::print("{}", io::sensitivity_json(rs));
    else
      print_text(rs, out, o.out_dir);
  } catch (const error& e) {
    end_failed_run(e, bar, exec);
  }
}

}  // namespace

void add_sensitivity_command(CLI::App& app, const invocation& inv) {
  auto opts = std::make_shared<sensitivity_options>();
  auto* cmd = app.add_subcommand(
      "sensitivity",
      "Sobol' indices of a statistic over uncertain model parameters given as laws "
      "(--mu 'uniform(2,7)'): first and total order of the mean response, the response's "
      "own first order, and the parameter vs intrinsic shares, each with a 95% interval; "
      "writes sensitivity.nc, summary.json and a figure to DIR (docs/uncertainty.md).");
  auto& o = *opts;
  add_model_flags(*cmd, o.model, flag_values::grid, model_parameters{});
  cmd->add_option("--statistic", o.statistic,
                  fmt::format("the per-realization statistic (default R): {}",
                              sensitivity_statistic_names()))
      ->type_name("NAME");
  o.samples_opt = cmd->add_option("--samples", o.samples,
                                  "design rows N (default 4096); each row runs d + 3 "
                                  "realizations for d uncertain inputs")
                      ->type_name("N");
  o.target_opt = cmd->add_option("--target-halfwidth", o.target_halfwidth,
                                 "run rows until every index and share has a 95% half-width "
                                 "<= H (0 < H <= 0.5), or the statistic has been constant over "
                                 "every row at --min-samples (its indices are then undefined)")
                     ->type_name("H");
  o.max_opt = cmd->add_option("--max-samples", o.max_samples,
                              "with --target-halfwidth: at most N rows (default 1000000)")
                  ->type_name("N");
  o.min_opt = cmd->add_option("--min-samples", o.min_samples,
                              "with --target-halfwidth: at least N rows before the stop rule "
                              "applies (default 1000)")
                  ->type_name("N");
  o.block_opt = cmd->add_option("--block-size", o.block_size,
                                "rows per work unit; part of the result's identity (default 64)")
                    ->type_name("B");
  cmd->add_option("--threads", o.threads, "worker threads, 0 = all cores (default 0)")
      ->type_name("T");
  cmd->add_option("--format", o.format, "text (default) or json on stdout")->type_name("FMT");
  cmd->add_option("-o,--output", o.out_dir, "output directory")->type_name("DIR")->required();
  cmd->add_flag("--resume", o.resume, "continue the study journaled in DIR");
  cmd->add_option("--shard", o.shard, "run only units with index % n == i (combine with merge)")
      ->type_name("i/n");
  cmd->add_option("--checkpoint-interval", o.checkpoint_interval,
                  "minimum seconds between journal segments (more while a checkpoint would "
                  "cost over 5 %, up to 15 times this; default 2)")
      ->type_name("SECONDS");
  cmd->add_flag("--overwrite", o.overwrite, "replace the results of an earlier run in DIR");
  cmd->add_flag("--keep-journal", o.keep_journal, "keep DIR/.journal after the outputs are written");
  cmd->add_flag("--no-figure", o.no_figure, "do not draw sensitivity.{png,svg}");
  cmd->callback([cmd, opts, inv] { run_sensitivity_command(*cmd, *opts, inv); });
}

}  // namespace stickslip::app
