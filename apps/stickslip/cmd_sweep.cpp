// `stickslip sweep`: the paper's statistics over a parameter grid, on all
// cores, bit-identical for any thread count, written to DIR.
//
// Three steps, each its own function:
//   (a) build_sweep_spec: TOML file (--config) + flags -> validated sweep_spec.
//       Nothing is touched on disk before this has succeeded.
//   (b) run_journaled: every finished unit goes to the checkpoint journal
//       DIR/.journal (io/journal.hpp); --resume reloads it first and runs
//       only what is missing; --shard i/n runs one slice; under mpirun the
//       units are spread over the ranks (backends/mpi). A progress bar on
//       stderr when it is a terminal.
//   (c) write_results: io::write_all(results.nc, summary.json, summary.csv,
//       records.csv) with the first run's metadata (kept in the journal), then
//       the journal is removed unless --keep-journal.
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
#include "progress.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/io/journal.hpp"
#include "stickslip/io/metadata.hpp"
#include "stickslip/io/output_files.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/sweep.hpp"
#ifdef STICKSLIP_HAVE_MPI
#include "stickslip/mpi/distributed_sweep.hpp"
#endif

namespace stickslip::app {
namespace {

struct sweep_options {
  model_flags model;
  std::string config;
  std::string realizations, block_size, bins, threads = "0";
  bool records = false;
  std::string engine;
  std::string out_dir;
  bool resume = false, keep_journal = false, overwrite = false;
  std::string shard;                       // "i/n"
  std::string checkpoint_interval = "2";   // seconds between journal segments
  CLI::Option *config_opt = nullptr, *realizations_opt = nullptr, *block_size_opt = nullptr,
              *bins_opt = nullptr, *records_opt = nullptr, *engine_opt = nullptr;
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

// (a) The resolved, validated spec: defaults < --config file < --preset < flags.
sweep_spec build_sweep_spec(const CLI::App& cmd, const sweep_options& o) {
  sweep_spec spec = o.config_opt->count() > 0 ? io::read_sweep_toml_file(o.config) : sweep_spec{};
  spec.base = apply_preset(o.model, spec.base);
  apply_model_flags(cmd, o.model, spec);
  spec.seed = resolve_seed(o.model, spec.seed);
  spec.max_events = resolve_max_events(o.model, spec.max_events);
  if (o.realizations_opt->count() > 0)
    spec.realizations = io::parse_unsigned("--realizations", o.realizations, 1, max_realizations);
  if (o.block_size_opt->count() > 0)
    spec.block_size = io::parse_unsigned("--block-size", o.block_size, 1, max_block_size);
  if (o.bins_opt->count() > 0)
    spec.histograms.bins = static_cast<std::size_t>(io::parse_unsigned("--bins", o.bins, 1, max_histogram_bins));
  if (o.records_opt->count() > 0) spec.keep_records = o.records;
  if (o.engine_opt->count() > 0) spec.engine = io::parse_engine("--engine", o.engine);
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

// The results live in memory until they are written: per grid point the
// accumulators, four histograms and the convergence trace (every block up
// to 64, then 32 entries per doubling: records_convergence_after), plus the
// raw records when kept; the writers hold about as much again. An absurd
// grid must be refused with a clear error before it exhausts memory
// (std::bad_alloc or the OOM killer), so estimate and compare with the RAM.
void check_result_memory(const sweep_spec& spec) {
  const double points = static_cast<double>(point_count(spec));
  const double blocks = static_cast<double>(blocks_per_point(spec));
  const double trace = std::min(blocks, 64.0) + 32.0 * std::max(0.0, std::log2(blocks / 64.0)) + 1;
  const double per_point = 1024.0 + 4.0 * 8.0 * static_cast<double>(spec.histograms.bins) +
                           40.0 * trace;
  const double records = spec.keep_records ? 96.0 * static_cast<double>(spec.realizations) : 0.0;
  const double bytes = 2.0 * points * (per_point + records);
  const double ram = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) *
                     static_cast<double>(::sysconf(_SC_PAGE_SIZE));
  if (ram > 0 && bytes > 0.8 * ram)
    throw error(exit_code::invalid_input,
                fmt::format("invalid grid size: the results would need about {:.3g} GiB (estimated "
                            "memory; allowed: <= 80% of this machine's {:.3g} GiB): "
                            "use fewer grid points or bins",
                            bytes / (1u << 30), ram / (1u << 30)));
}

// --shard i/n: this process runs the units whose index (point-major, as
// unit_at numbers them) is i modulo n.
struct shard_spec {
  std::uint64_t index = 0, count = 1;
  [[nodiscard]] bool owns(const sweep_spec& s, const work_unit& u) const {
    return (u.point * blocks_per_point(s) + u.block) % count == index;
  }
};

std::optional<shard_spec> parse_shard(const std::string& text) {
  if (text.empty()) return std::nullopt;
  const auto slash = text.find('/');
  if (slash == std::string::npos)
    throw invalid_value("--shard", text, "i/n with 0 <= i < n, e.g. 3/16");
  shard_spec sh;
  sh.count = io::parse_unsigned("--shard (n)", text.substr(slash + 1), 1, 1u << 20);
  sh.index = io::parse_unsigned("--shard (i)", text.substr(0, slash), 0, sh.count - 1);
  return sh;
}

// SIGINT/SIGTERM (Ctrl-C, a job scheduler's time limit) and SIGUSR1 stop
// handing out new units; the units in flight finish and are journaled, so
// --resume loses nothing. SIGUSR1 is the one to use under mpirun: mpirun
// forwards it to every rank, while on SIGTERM it kills the ranks itself
// (under srun: `#SBATCH --signal=USR1@120`; docs/scaling.md). Restores the
// previous handlers when it goes out of scope.
std::atomic<int> stop_signal{0};
extern "C" void on_stop_signal(int sig) { stop_signal.store(sig); }
constexpr int stop_signals[] = {SIGINT, SIGTERM, SIGUSR1};
class stop_on_signals {
 public:
  stop_on_signals() {
    stop_signal.store(0);
    for (std::size_t i = 0; i < std::size(stop_signals); ++i)
      old_[i] = std::signal(stop_signals[i], on_stop_signal);
  }
  ~stop_on_signals() {
    for (std::size_t i = 0; i < std::size(stop_signals); ++i) std::signal(stop_signals[i], old_[i]);
  }
  stop_on_signals(const stop_on_signals&) = delete;
  stop_on_signals& operator=(const stop_on_signals&) = delete;

 private:
  void (*old_[std::size(stop_signals)])(int) = {};
};

// What a run needs besides the spec.
struct run_plan {
  std::string dir;
  unsigned threads = 0;
  std::optional<shard_spec> shard;
  bool resume = false;
  std::chrono::duration<double> checkpoint_interval{2.0};
};

struct run_outcome {
  std::optional<result_set> results;  // absent for a shard
  io::run_metadata metadata;          // the first run's, from the journal if resumed
  std::uint64_t resumed_units = 0, computed_units = 0;
  double elapsed_this_run = 0;
};

// (b) Journal, resume, shard, and the run itself (threads, or MPI ranks when
// `coordinate` is given: it runs the units instead of run_units).
using unit_runner = std::function<void(const sweep_spec&, ordered_merger&, const sweep_hooks&)>;
run_outcome run_journaled(const sweep_spec& spec, const run_plan& plan, const invocation& inv,
                          const unit_runner& runner) {
  const auto t0 = std::chrono::steady_clock::now();
  run_outcome out;
  io::journal_contents loaded;
  if (io::journal_exists(plan.dir)) {
    if (!plan.resume)
      throw invalid_value("-o (output directory)", plan.dir,
                          "a directory without the journal of an unfinished sweep (found " +
                              io::journal_path(plan.dir) +
                              "): add --resume to continue that sweep, or remove the journal");
    loaded = io::read_journal(plan.dir, &spec, [](const std::string& problem) {
      fmt::print(stderr, "stickslip: journal: {}\n", problem);
    });
    if (loaded.damaged)
      fmt::print(stderr, "stickslip: journal: {} damaged file(s) or record(s) skipped; their "
                         "units are recomputed\n", loaded.damaged);
  } else if (plan.resume) {
    fmt::print(stderr, "stickslip: no journal in {}: starting the sweep from the beginning\n",
               plan.dir);
  }
  out.metadata = loaded.metadata ? *loaded.metadata
                                 : io::make_metadata(inv.argc, inv.argv, io::to_toml(spec));

  ordered_merger merger(spec);
  if (plan.shard) merger.discard_results();  // a shard only journals (merge combines them)
  std::vector<char> done(unit_count(spec), 0);
  for (auto& [u, r] : loaded.units) {
    done[u.point * blocks_per_point(spec) + u.block] = 1;
    merger.add(u, std::move(r));
    ++out.resumed_units;
  }
  loaded.units.clear();

  const std::string tag =
      plan.shard ? fmt::format("shard-{}-of-{}", plan.shard->index, plan.shard->count) : "run";
  io::journal_writer journal(plan.dir, spec, out.metadata, tag, plan.checkpoint_interval);
  progress_bar bar;
  sweep_hooks hooks;
  auto to_run = [&](const work_unit& u) {
    return !done[u.point * blocks_per_point(spec) + u.block] &&
           (!plan.shard || plan.shard->owns(spec, u));
  };
  std::optional<work_meter> work;  // the ETA weighs units by their expected work
  if (bar.active()) {
    work.emplace(spec, to_run);
    hooks.progress = [&](std::uint64_t d, std::uint64_t total) {
      bar.update(d, total, work->fraction());
    };
  }
  hooks.unit_done = [&](const work_unit& u, const block_result& r) {
    journal.add(u, r);
    if (work) work->add(u);
  };
  hooks.wanted = [&](const work_unit& u) { return stop_signal.load() == 0 && to_run(u); };
  runner(spec, merger, hooks);
  journal.flush();
  bar.finish();
  out.computed_units = journal.units_written();
  out.elapsed_this_run = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (const int sig = stop_signal.load())
    throw error(static_cast<exit_code>(128 + sig),
                fmt::format("interrupted by signal {}: {} finished units are journaled in {}; "
                            "continue with the same command and --resume",
                            sig, merger.merged_units(), io::journal_path(plan.dir)));
  if (plan.shard) return out;
  if (!merger.complete())
    throw error(exit_code::internal, "sweep ended with units missing from the merge");
  out.results = make_result_set(spec, std::move(merger));
  out.results->elapsed_seconds = loaded.elapsed_seconds + out.elapsed_this_run;
  return out;
}

}  // namespace

// After a failed NetCDF write (disk full, `ulimit -f`), HDF5 1.10 keeps a
// half-closed file and segfaults in its atexit teardown (H5_term_library ->
// H5F__close_cb). The error is already known and the outputs are already
// rolled back, so report it the way main() does and leave without running
// the library's exit handlers: a clear error, not a crash.
[[noreturn]] void exit_after_failed_write(const error& e) {
  std::fflush(stdout);
  fmt::print(stderr, "stickslip: error: {}\n", e.what());
  std::fflush(stderr);
  std::_Exit(static_cast<int>(e.code()));
}

namespace {

// (c) All outputs, atomically, with the first run's metadata; then the
// journal has served its purpose.
void write_results(const result_set& rs, const io::run_metadata& meta, const std::string& dir,
                   bool keep_journal) {
  try {
    io::write_all(rs, meta, dir);
  } catch (const error& e) {
    if (e.code() == exit_code::io_failure)
      exit_after_failed_write(error(e.code(), std::string(e.what()) +
                                                  "; the finished units stay in the journal: "
                                                  "rerun with --resume to write the outputs"));
    throw;
  }
  if (!keep_journal) io::remove_journal(dir);
}

// A deterministic failure (work bound, invalid input) cannot be fixed by
// --resume: remove what this run created so a failed sweep leaves nothing.
// Other failures (disk full, I/O, signals) keep the journal for --resume.
void clean_up_after_failure(const error& e, const std::string& dir, bool dir_existed,
                            bool journal_existed) {
  if (e.code() != exit_code::work_bound && e.code() != exit_code::invalid_input) return;
  std::error_code ec;
  if (!dir_existed)
    std::filesystem::remove_all(dir, ec);
  else if (!journal_existed)
    io::remove_journal(dir);
}

void report(const sweep_spec& spec, const run_plan& plan, const run_outcome& out,
            unsigned threads, int ranks) {
  const std::string thread_text = fmt::format("{} thread{}", threads, threads == 1 ? "" : "s");
  const std::string where =
      ranks > 1 ? fmt::format("{} ranks x {}", ranks, thread_text) : thread_text;
  const std::string resumed =
      out.resumed_units ? fmt::format(", {} units from the journal", out.resumed_units) : "";
  if (plan.shard) {
    fmt::print(stderr, "shard {}/{}: {} units in {:.3g} s ({}{}) journaled in {}; combine the "
                       "shards with `stickslip merge`\n",
               plan.shard->index, plan.shard->count, out.computed_units, out.elapsed_this_run,
               where, resumed, io::journal_path(plan.dir));
    return;
  }
  const std::uint64_t n = point_count(spec) * spec.realizations;
  fmt::print(stderr, "{} realizations in {:.3g} s ({} grid points, {}{}) -> {}\n", n,
             out.elapsed_this_run, point_count(spec), where, resumed, plan.dir);
}

void run_sweep_command(const CLI::App& cmd, const sweep_options& o, const invocation& inv) {
  // Past `ulimit -f` a write must fail with EFBIG (reported), not kill us.
  std::signal(SIGXFSZ, SIG_IGN);
  // From here to the end (outputs written): a stop signal sets stop_signal
  // (no unit starts after it), on every rank until workers ignore it below.
  stop_on_signals signals;
  const auto threads =
      static_cast<unsigned>(io::parse_unsigned("--threads", o.threads, 0, 1u << 16));
  const unsigned resolved_threads = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
#ifdef STICKSLIP_HAVE_MPI
  std::optional<mpi::session> ses;
  if (mpi::launched_by_mpi()) {
    ses.emplace();
    if (!ses->is_root()) {
      // Rank 0 decides when to stop: on a stop signal (mpirun forwards
      // SIGUSR1 to every rank) it hands out no more units and tells the
      // workers to stop once the units they hold are done and journaled. A
      // worker that died on the signal would make rank 0 abort instead.
      for (const int sig : stop_signals) std::signal(sig, SIG_IGN);
      return mpi::serve(*ses, threads);  // rank 0 reports everything
    }
  }
  const int ranks = ses ? ses->size() : 1;
  auto cancel_workers = [&] {
    if (ses) mpi::cancel(*ses);
  };
#else
  const int ranks = 1;
  auto cancel_workers = [] {};
#endif

  sweep_spec spec;
  run_plan plan;
  bool dir_existed = false, journal_existed = false;
  try {
    spec = build_sweep_spec(cmd, o);
    check_result_memory(spec);
    check_output_dir(o.out_dir);
    if (!o.resume && !o.overwrite)
      io::refuse_to_replace(io::existing_sweep_results(o.out_dir), "the results of an earlier run",
                            "add --overwrite to replace them, --resume to continue an "
                            "interrupted sweep, or choose another -o DIR");
    plan.dir = o.out_dir;
    plan.threads = threads;
    plan.shard = parse_shard(o.shard);
    plan.resume = o.resume;
    const double interval = io::parse_number("--checkpoint-interval", o.checkpoint_interval);
    if (!(interval >= 0) || interval > 86400)
      throw invalid_parameter("--checkpoint-interval", interval, "0 .. 86400 seconds");
    plan.checkpoint_interval = std::chrono::duration<double>(interval);
    dir_existed = std::filesystem::exists(plan.dir);
    journal_existed = io::journal_exists(plan.dir);
  } catch (...) {
    cancel_workers();
    throw;
  }

  unit_runner runner = [threads](const sweep_spec& s, ordered_merger& m, const sweep_hooks& h) {
    run_units(s, threads, m, h);
  };
#ifdef STICKSLIP_HAVE_MPI
  if (ses)
    runner = [&](const sweep_spec& s, ordered_merger& m, const sweep_hooks& h) {
      mpi::coordinate(*ses, s, threads, m, h);
    };
  bool coordinated = false;
  auto inner = runner;
  runner = [&](const sweep_spec& s, ordered_merger& m, const sweep_hooks& h) {
    coordinated = true;
    inner(s, m, h);
  };
#endif
  try {
    auto out = run_journaled(spec, plan, inv, runner);
    if (out.results) {
      out.results->threads = resolved_threads;
      write_results(*out.results, out.metadata, plan.dir, o.keep_journal);
    }
    report(spec, plan, out, resolved_threads, ranks);
  } catch (const error& e) {
#ifdef STICKSLIP_HAVE_MPI
    if (!coordinated) cancel_workers();
#endif
    clean_up_after_failure(e, plan.dir, dir_existed, journal_existed);
    throw;
  } catch (...) {
#ifdef STICKSLIP_HAVE_MPI
    if (!coordinated) cancel_workers();
#endif
    throw;
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
  cmd->add_option("-o,--output", o.out_dir,
                  "output directory; holds the checkpoint journal DIR/.journal while running")
      ->type_name("DIR")
      ->required();
  cmd->add_flag("--resume", o.resume,
                "continue the sweep journaled in DIR (after a crash, kill or time limit); "
                "refused if the configuration changed; starts afresh if DIR has no journal");
  cmd->add_option("--shard", o.shard,
                  "run only units with index % n == i and journal them in DIR (no final "
                  "outputs); combine shards with `stickslip merge`")
      ->type_name("i/n");
  cmd->add_option("--checkpoint-interval", o.checkpoint_interval,
                  "seconds between journal segments (each is fsynced); 0 = after every unit "
                  "(default 2)")
      ->type_name("SECONDS");
  cmd->add_flag("--overwrite", o.overwrite,
                "replace the results of an earlier run in DIR (default: refuse and say which)");
  cmd->add_flag("--keep-journal", o.keep_journal,
                "keep DIR/.journal after the outputs are written (default: remove it)");
  cmd->callback([cmd, opts, inv] { run_sweep_command(*cmd, *opts, inv); });
}

}  // namespace stickslip::app
