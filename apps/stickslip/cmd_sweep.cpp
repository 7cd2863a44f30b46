// `stickslip sweep`: the paper's statistics over a parameter grid, on all
// cores, bit-identical for any thread count, written to DIR.
//
// Three steps, each its own function:
//   (a) build_sweep_spec: TOML file (--config) + flags -> validated sweep_spec.
//       Nothing is touched on disk before this has succeeded.
//   (b) run_with_progress: run_sweep with a progress bar on stderr (tty only).
//   (c) write_results: io::write_all(results.nc, summary.json, summary.csv,
//       records.csv) with the resolved spec as TOML in the metadata.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "model_flags.hpp"
#include "progress.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/io/metadata.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::app {
namespace {

struct sweep_options {
  model_flags model;
  std::string config;
  std::string realizations, block_size, bins, threads = "0";
  bool records = false;
  std::string out_dir;
  CLI::Option *config_opt = nullptr, *realizations_opt = nullptr, *block_size_opt = nullptr,
              *bins_opt = nullptr, *records_opt = nullptr;
};

// Grid axes that come from flags: lambda first, then mu, then the others in
// the order they were given.
int axis_rank(const std::string& symbol) {
  return symbol == "lambda" ? 0 : symbol == "mu" ? 1 : 2;
}

// Applies the model flags to `spec`. A single number sets the fixed value
// (and drops any axis of that parameter from the file); a list or a
// lin:/log: range makes an axis, replacing the file's values in place or
// appending a new axis after the file's axes.
void apply_model_flags(const CLI::App& cmd, const model_flags& f, sweep_spec& spec) {
  std::vector<axis> added;
  for (const auto* flag : given_model_flags(cmd, f)) {
    const auto& sym = flag->symbol;
    auto in_file = std::find_if(spec.axes.begin(), spec.axes.end(),
                                [&](const axis& a) { return a.name == sym; });
    if (io::is_single_value(flag->text)) {
      parameter_by_name(spec.base, sym) = io::parse_number(flag_label(sym), flag->text);
      if (in_file != spec.axes.end()) spec.axes.erase(in_file);
      continue;
    }
    auto values = io::parse_grid("--" + sym, flag->text);
    if (in_file != spec.axes.end())
      in_file->values = std::move(values);
    else
      added.push_back({sym, std::move(values)});
  }
  std::stable_sort(added.begin(), added.end(), [](const axis& a, const axis& b) {
    return axis_rank(a.name) < axis_rank(b.name);
  });
  spec.axes.insert(spec.axes.end(), added.begin(), added.end());
}

// (a) The resolved, validated spec: defaults < --config file < flags.
sweep_spec build_sweep_spec(const CLI::App& cmd, const sweep_options& o) {
  sweep_spec spec = o.config_opt->count() > 0 ? io::read_sweep_toml_file(o.config) : sweep_spec{};
  apply_model_flags(cmd, o.model, spec);
  spec.seed = resolve_seed(o.model, spec.seed);
  spec.max_events = resolve_max_events(o.model, spec.max_events);
  if (o.realizations_opt->count() > 0)
    spec.realizations = io::parse_unsigned("--realizations", o.realizations, 1);
  if (o.block_size_opt->count() > 0)
    spec.block_size = io::parse_unsigned("--block-size", o.block_size, 1);
  if (o.bins_opt->count() > 0)
    spec.histograms.bins = static_cast<std::size_t>(io::parse_unsigned("--bins", o.bins, 1));
  if (o.records_opt->count() > 0) spec.keep_records = o.records;
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

// (b) Runs every work unit, drawing a progress bar when stderr is a terminal.
result_set run_with_progress(const sweep_spec& spec, unsigned threads) {
  progress_bar bar;
  sweep_hooks hooks;
  if (bar.active())
    hooks.progress = [&bar](std::uint64_t done, std::uint64_t total) { bar.update(done, total); };
  auto rs = run_sweep(spec, threads, hooks);
  bar.finish();
  return rs;
}

// (c) All outputs, atomically, with the resolved configuration as metadata.
void write_results(const result_set& rs, const invocation& inv, const std::string& dir) {
  io::write_all(rs, io::make_metadata(inv.argc, inv.argv, io::to_toml(rs.spec)), dir);
}

void run_sweep_command(const CLI::App& cmd, const sweep_options& o, const invocation& inv) {
  const sweep_spec spec = build_sweep_spec(cmd, o);
  const auto threads =
      static_cast<unsigned>(io::parse_unsigned("--threads", o.threads, 0, 1u << 16));
  check_output_dir(o.out_dir);
  const auto rs = run_with_progress(spec, threads);
  write_results(rs, inv, o.out_dir);
  const std::uint64_t n = point_count(spec) * spec.realizations;
  fmt::print(stderr, "{} realizations in {:.3g} s ({} grid points, {} threads) -> {}\n", n,
             rs.elapsed_seconds, point_count(spec), rs.threads, o.out_dir);
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
  cmd->add_option("-o,--output", o.out_dir, "output directory (created after a successful run)")
      ->type_name("DIR")
      ->required();
  cmd->callback([cmd, opts, inv] { run_sweep_command(*cmd, *opts, inv); });
}

}  // namespace stickslip::app
