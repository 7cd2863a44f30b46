// `stickslip simulate`: one realization, as an episode table (CSV or JSON),
// optionally with its events and a sampled trajectory for plotting.
//
// By default the realization is drawn exactly as the sweep draws realization
// r of the point with these parameters (simulate_realization: initial
// conditions and Poisson switches from the Philox streams keyed by
// (seed, point_key(params), r)), so any sweep realization can be replayed alone.
// Replay mode fixes any of x0, x'0, the belt start (the others are still drawn
// from the stream) and/or the belt switch times.
// With laws for parameters (--mu 'gamma(mean=5,cv=0.2)'), --realization R
// replays realization R of the sweep point with those laws: the values it
// drew, then its run (io::replay_uncertain); they are printed.
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "model_flags.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/io/output_files.hpp"
#include "stickslip/io/realization_output.hpp"
#include "stickslip/io/uncertain_replay.hpp"
#include "stickslip/replay.hpp"
#include "stickslip/statistics.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::app {
namespace {

struct simulate_options {
  model_flags model;
  std::string realization = "0";
  std::string x0, xdot0, belt_start;
  std::string switch_times, switch_times_file;
  std::string format = "csv";
  std::string output;
  bool events = false;
  std::string events_file;
  std::string trajectory_step, trajectory_file;
  bool overwrite = false;
  bool common_random_numbers = false;
  std::string burn_in;
  CLI::Option* burn_in_opt = nullptr;
  CLI::Option *x0_opt = nullptr, *xdot0_opt = nullptr, *belt_opt = nullptr;
  CLI::Option *times_opt = nullptr, *times_file_opt = nullptr, *trajectory_opt = nullptr;
  CLI::Option *events_file_opt = nullptr, *trajectory_file_opt = nullptr;
  CLI::Option* realization_opt = nullptr;
};

// A file flag without the output it names would write nothing: refused
// before the run, naming both flags, instead of silently ignored.
void check_file_flags(const simulate_options& o) {
  if (o.events_file_opt->count() > 0 && !o.events)
    throw invalid_value("--events-file", o.events_file,
                        "only together with --events, which writes the events to it");
  if (o.events_file_opt->count() > 0 && o.format == "json")
    throw invalid_value("--events-file", o.events_file,
                        "only with --format csv: with --format json, --events puts the events "
                        "in the JSON output (its key \"events\")");
  if (o.trajectory_file_opt->count() > 0 && o.trajectory_opt->count() == 0)
    throw invalid_value("--trajectory-file", o.trajectory_file,
                        "only together with --trajectory DT, which writes the samples to it");
}

// The given belt switches: times, and with `t level` lines the levels.
void set_given_switches(const simulate_options& o, replay_request& req) {
  if (o.times_opt->count() > 0 && o.times_file_opt->count() > 0)
    throw invalid_value("--switch-times-file", o.switch_times_file,
                        "either --switch-times or --switch-times-file, not both");
  const std::size_t levels = req.parameters.levels().size();
  if (o.times_opt->count() > 0) req.switch_times = io::parse_switch_time_list("--switch-times", o.switch_times);
  if (o.times_file_opt->count() == 0) return;
  auto schedule = io::read_switch_schedule_file(o.switch_times_file, levels);
  req.switch_times = std::move(schedule.times);
  if (!schedule.levels.empty()) req.switch_levels = std::move(schedule.levels);
}

// Realization R of a point with laws, drawn and run as the sweep does. One
// trajectory of an uncertain model is only defined as a given realization,
// and it is replayed whole: its inputs are not fixed one by one.
io::realization_report run_uncertain(const simulate_options& o, replay_request req,
                                     std::vector<uncertain_parameter> laws) {
  if (o.realization_opt->count() == 0) throw io::realization_required(laws);
  for (const CLI::Option* fixed : {o.x0_opt, o.xdot0_opt, o.times_opt, o.times_file_opt})
    if (fixed->count() > 0)
      throw io::fixed_input_with_laws(fixed->get_name(), fixed->as<std::string>(), laws);
  if (o.belt_opt->count() > 0)  // the sweep's --belt-start: the law of the starting level
    req.initial.belt_start = io::parse_belt_start("--belt-start", o.belt_start,
                                                  req.parameters.levels().size());
  req.keep_events = o.events;
  req.keep_segments = o.trajectory_opt->count() > 0;
  return io::replay_uncertain(req, std::move(laws));
}

// One realization through the core's replay (the same as Python's
// stickslip.simulate): drawn as realization R of the sweep point, with any
// of x0, x'0, the belt start and the switch times fixed by flags.
io::realization_report run_one(const CLI::App& cmd, const simulate_options& o) {
  replay_request req;
  req.parameters = apply_scalar_flags(cmd, o.model, apply_preset(o.model, model_parameters{}));
  req.seed = resolve_seed(o.model, req.seed);
  req.max_events = resolve_max_events(o.model, req.max_events);
  req.realization = io::parse_unsigned("--realization", o.realization);
  req.common_random_numbers = o.common_random_numbers;
  if (o.burn_in_opt->count() > 0)
    req.burn_in = io::parse_number("--burn-in", o.burn_in);  // 0 <= T < t_a: replay()
  if (auto laws = given_laws(cmd, o.model); !laws.empty())
    return run_uncertain(o, std::move(req), std::move(laws));
  set_given_switches(o, req);
  if (o.x0_opt->count() > 0) req.x0 = io::parse_number("--x0 (initial position)", o.x0);
  if (o.xdot0_opt->count() > 0)
    req.xdot0 = io::parse_number("--xdot0 (initial velocity)", o.xdot0);
  if (o.belt_opt->count() > 0)
    if (const int b = io::parse_belt_start("--belt-start", o.belt_start,
                                           req.parameters.levels().size());
        b != 0)
      req.belt_start = b;
  req.keep_events = o.events;
  req.keep_segments = o.trajectory_opt->count() > 0;
  auto trace = replay(req);
  return {std::move(req), std::move(trace), {}, {}};
}

// A file next to the -o output, or in the current directory for stdout.
std::string beside_output(const simulate_options& o, const std::string& name) {
  if (o.output.empty() || o.output == "-") return name;
  return (std::filesystem::path(o.output).parent_path() / name).string();
}

// The files this run writes (the table itself goes to stdout without -o).
std::vector<io::text_output> planned_files(const simulate_options& o,
                                           const io::realization_report& run, double dt) {
  std::vector<io::text_output> files;
  const bool to_stdout = o.output.empty() || o.output == "-";
  if (!to_stdout)
    files.push_back({"-o", o.output, [&] {
                       return o.format == "json" ? io::realization_json(run, o.events)
                                                 : io::episodes_csv(run);
                     }});
  if (o.events && o.format == "csv")
    files.push_back({"--events-file",
                     o.events_file.empty() ? beside_output(o, "events.csv") : o.events_file,
                     [&] { return io::events_csv(run); }});
  if (dt > 0)
    files.push_back({"--trajectory-file",
                     o.trajectory_file.empty() ? beside_output(o, "trajectory.csv")
                                               : o.trajectory_file,
                     [&run, dt] { return io::trajectory_csv(run, dt); }});
  return files;
}

void run_simulate(const CLI::App& cmd, const simulate_options& o) {
  check_file_flags(o);
  // Check the trajectory step before the run.
  double dt = 0;
  if (o.trajectory_opt->count() > 0) {
    dt = io::parse_number("--trajectory (sampling step DT)", o.trajectory_step);
    if (!(dt > 0)) throw invalid_parameter("--trajectory (sampling step DT)", dt, "> 0");
  }
  const auto run = run_one(cmd, o);
  if (dt > 0 && run.request.parameters.window / dt > 1e7)
    throw invalid_parameter("--trajectory (sampling step DT)", dt,
                            fmt::format(">= t_a / 1e7 = {}", run.request.parameters.window / 1e7));

  // All files or none, and none replaced unless asked.
  const auto files = planned_files(o, run, dt);
  io::write_text_files(files, o.overwrite,
                       "add --overwrite to replace it, or choose another file (-o, "
                       "--events-file, --trajectory-file)");
  if (o.output.empty() || o.output == "-") {
    const std::string table =
        o.format == "json" ? io::realization_json(run, o.events) : io::episodes_csv(run);
    std::fwrite(table.data(), 1, table.size(), stdout);
  }

  const auto& s = run.trace.record;
  std::string drawn;
  for (std::size_t i = 0; i < run.uncertain.size(); ++i)
    drawn += fmt::format("{}{} = {} (drawn from {})", i ? ", " : "", run.uncertain[i].symbol,
                         run.drawn[i], to_string(run.uncertain[i].law));
  const std::string over =
      run.request.burn_in > 0.0 ? fmt::format(" over [{}, t_a]", run.request.burn_in) : "";
  fmt::print(stderr, "seed {} realization {}: {}{}S_T = {}, S_L = {}, R = {:.6g}{} ({} events)\n",
             run.request.seed, run.request.realization, drawn, drawn.empty() ? "" : "; ",
             s.sticks, s.slips, s.stick_fraction, over, s.events.total());
}

}  // namespace

void add_simulate_command(CLI::App& app, const invocation&) {
  auto opts = std::make_shared<simulate_options>();
  auto* cmd = app.add_subcommand(
      "simulate",
      "Simulate one realization exactly and print its episodes (CSV or JSON). Random by "
      "default, drawn exactly as realization R of a sweep point; replay a given scenario "
      "with --x0/--xdot0/--belt-start and --switch-times[-file].");
  auto& o = *opts;
  add_model_flags(*cmd, o.model, flag_values::scalar, model_parameters{});
  o.realization_opt =
      cmd->add_option("--realization", o.realization,
                      "realization index R: the same streams as realization R of a sweep "
                      "(default 0); required with a law for a parameter, whose drawn values "
                      "are printed")
          ->type_name("R");
  cmd->add_flag("--common-random-numbers", o.common_random_numbers,
                "the streams of a sweep run with --common-random-numbers (the same for every "
                "grid point) instead of this point's own");
  o.burn_in_opt =
      cmd->add_option("--burn-in", o.burn_in,
                      "count only [T, t_a] in the realization's statistics (S_T, S_L, R, D_1), "
                      "as a sweep with --burn-in T does; the episodes are the whole window "
                      "(default 0)")
          ->type_name("T");
  const char* replay = "Replay (fixed inputs instead of random draws)";
  o.x0_opt = cmd->add_option("--x0", o.x0, "initial position x0 [m] (default: drawn)")
                 ->type_name("X")
                 ->group(replay);
  o.xdot0_opt = cmd->add_option("--xdot0", o.xdot0, "initial velocity x'0 [m/s] (default: drawn)")
                    ->type_name("U")
                    ->group(replay);
  o.belt_opt = cmd->add_option("--belt-start", o.belt_start,
                               "initial belt level: +1 / -1 (first / second of two levels), "
                               "a level number 1..n, or stationary (default: drawn)")
                   ->type_name("LEVEL")
                   ->group(replay);
  o.times_opt = cmd->add_option("--switch-times", o.switch_times,
                                "belt switch times t1,t2,... (sorted, >= 0) instead of Poisson")
                    ->type_name("LIST")
                    ->group(replay);
  o.times_file_opt =
      cmd->add_option("--switch-times-file", o.switch_times_file,
                      "file with one switch per line: 't' (two levels: go to the other one) "
                      "or 't level' (level number 1..n); '#' comments allowed; not together "
                      "with --switch-times")
          ->type_name("FILE")
          ->group(replay);
  const char* output = "Output";
  cmd->add_option("--format", o.format, "episode table format: csv or json (default csv)")
      ->type_name("csv|json")
      ->check(CLI::IsMember({"csv", "json"}))
      ->group(output);
  cmd->add_option("-o,--output", o.output, "write the episode table to FILE (default stdout)")
      ->type_name("FILE")
      ->group(output);
  cmd->add_flag("--events", o.events,
                "also output the events (kind,time,x,xdot,v): a key \"events\" in JSON, "
                "the --events-file in CSV")
      ->group(output);
  o.events_file_opt =
      cmd->add_option("--events-file", o.events_file,
                      "CSV file for --events in CSV format (default events.csv next to -o, or "
                      "in the current directory); only with --events")
          ->type_name("FILE")
          ->group(output);
  o.trajectory_opt =
      cmd->add_option("--trajectory", o.trajectory_step,
                      "sample t,x,x',v every DT seconds plus at every event, into "
                      "--trajectory-file")
          ->type_name("DT")
          ->group(output);
  o.trajectory_file_opt =
      cmd->add_option("--trajectory-file", o.trajectory_file,
                      "CSV file for --trajectory (default trajectory.csv next to -o, or in the "
                      "current directory); only with --trajectory")
          ->type_name("FILE")
          ->group(output);
  cmd->add_flag("--overwrite", o.overwrite,
                "replace output files that already exist (default: refuse and say which)")
      ->group(output);
  cmd->callback([cmd, opts] { run_simulate(*cmd, *opts); });
}

}  // namespace stickslip::app
