// `stickslip simulate`: one realization, as an episode table (CSV or JSON),
// optionally with its events and a sampled trajectory for plotting.
//
// By default the realization is drawn exactly as the sweep draws realization
// r of the point with these parameters (simulate_realization: initial
// conditions and Poisson switches from the Philox streams keyed by
// (seed, point_key(params), r)), so any sweep realization can be replayed alone.
// Replay mode fixes any of x0, x'0, the belt start (the others are still drawn
// from the stream) and/or the belt switch times.
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "model_flags.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
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
  CLI::Option *x0_opt = nullptr, *xdot0_opt = nullptr, *belt_opt = nullptr;
  CLI::Option *times_opt = nullptr, *times_file_opt = nullptr, *trajectory_opt = nullptr;
};

// Everything the integrator reports about one realization.
struct recorder : observer_base {
  bool keep_events = false, keep_segments = false;  // only what an output needs
  std::vector<episode> episodes;
  std::vector<event> events;
  std::vector<segment> segments;
  void on_event(const event& e) {
    if (keep_events) events.push_back(e);
  }
  void on_segment(const segment& s) {
    if (keep_segments) segments.push_back(s);
  }
  void on_episode(const episode& e) { episodes.push_back(e); }
};

struct realization_run {
  model_parameters params;
  std::uint64_t seed = 1, realization = 0;
  initial_conditions ic;
  bool given_x0 = false, given_xdot0 = false, given_belt = false, given_switches = false;
  event_counts counts;
  realization_record record;
  recorder rec;
};

// Shortest decimal text that reads back to the same double.
std::string num(double v) { return fmt::format("{}", v); }
std::string json_num(double v) { return std::isfinite(v) ? num(v) : "null"; }

std::optional<std::vector<double>> given_switch_times(const simulate_options& o) {
  if (o.times_opt->count() > 0) return io::parse_switch_time_list("--switch-times", o.switch_times);
  if (o.times_file_opt->count() > 0) return io::read_switch_times_file(o.switch_times_file);
  return std::nullopt;
}

int parse_belt_start(const std::string& text) {
  if (text == "+1" || text == "1") return 1;
  if (text == "-1") return -1;
  if (text == "random") return 0;
  throw invalid_value("--belt-start", text, "+1, -1 or random");
}

realization_run run_one(const CLI::App& cmd, const simulate_options& o) {
  realization_run run;
  run.params = resolve_scalar_model(cmd, o.model, model_parameters{});
  sweep_spec spec;  // the sweep's defaults: initial-condition law, seed 1
  spec.seed = run.seed = resolve_seed(o.model, spec.seed);
  spec.max_events = resolve_max_events(o.model, spec.max_events);
  run.realization = io::parse_unsigned("--realization", o.realization);
  spec.base = run.params;
  validate(spec);  // the sweep's checks for one point, e.g. lambda * ta vs max_events
  run.rec.keep_events = o.events;
  run.rec.keep_segments = o.trajectory_opt->count() > 0;

  const auto key = point_key(run.params);
  run.ic = draw_initial_conditions(spec.initial, spec.seed, key, run.realization);
  if (o.x0_opt->count() > 0) {
    run.ic.position = io::parse_number("--x0 (initial position)", o.x0);
    run.given_x0 = true;
  }
  if (o.xdot0_opt->count() > 0) {
    run.ic.velocity = io::parse_number("--xdot0 (initial velocity)", o.xdot0);
    run.given_xdot0 = true;
  }
  if (o.belt_opt->count() > 0) {
    if (const int b = parse_belt_start(o.belt_start); b != 0) {
      run.ic.belt_direction = b;
      run.given_belt = true;
    }
  }
  validate(run.ic);
  const auto times = given_switch_times(o);
  run.given_switches = times.has_value();

  realization_observer stats(run.params.window);
  stats.reset(run.realization, run.ic.position, run.ic.velocity, run.ic.belt_direction);
  observer_pair<recorder, realization_observer> both{run.rec, stats};
  if (times) {
    given_switches sw(*times);
    run.counts = simulate(run.params, run.ic, sw, both, spec.max_events);
  } else if (!run.given_x0 && !run.given_xdot0 && !run.given_belt) {
    run.counts = simulate_realization(spec, run.params, run.realization, both);
  } else {
    poisson_switches sw(run.params.switch_rate, spec.seed, key, run.realization);
    run.counts = simulate(run.params, run.ic, sw, both, spec.max_events);
  }
  stats.finish();
  run.record = stats.record();
  run.record.events = run.counts;
  return run;
}

std::string episodes_csv(const realization_run& r) {
  std::string out = "mode,start,end,x_start,belt_velocity,censored\n";
  for (const auto& e : r.rec.episodes)
    out += fmt::format("{},{},{},{},{},{}\n", to_string(e.kind), num(e.start), num(e.end),
                       num(e.position_at_start), num(e.belt_velocity), e.censored ? 1 : 0);
  return out;
}

std::string events_csv(const realization_run& r) {
  std::string out = "kind,time,x,xdot,v\n";
  for (const auto& e : r.rec.events)
    out += fmt::format("{},{},{},{},{}\n", to_string(e.kind), num(e.time), num(e.position),
                       num(e.velocity), num(e.belt_velocity));
  return out;
}

std::string to_json(const realization_run& r, bool with_events) {
  std::string out = "{\n  \"parameters\": {";
  for (std::size_t i = 0; i < std::size(parameter_names); ++i)
    out += fmt::format("{}\"{}\": {}", i ? ", " : "", parameter_names[i],
                       json_num(parameter_by_name(r.params, parameter_names[i])));
  out += "},\n";
  out += fmt::format("  \"seed\": {},\n  \"realization\": {},\n", r.seed, r.realization);
  out += fmt::format(
      "  \"initial_conditions\": {{\"x0\": {}, \"xdot0\": {}, \"belt_start\": {}, "
      "\"given\": {{\"x0\": {}, \"xdot0\": {}, \"belt_start\": {}}}}},\n",
      json_num(r.ic.position), json_num(r.ic.velocity), r.ic.belt_direction, r.given_x0,
      r.given_xdot0, r.given_belt);
  out += fmt::format("  \"switch_times\": \"{}\",\n", r.given_switches ? "given" : "poisson");
  const auto& s = r.record;
  out += fmt::format(
      "  \"statistics\": {{\"sticks\": {}, \"slips\": {}, \"stick_fraction\": {}, "
      "\"first_stick_start\": {}, \"first_stick_duration\": {}, \"first_stick_censored\": {}}},\n",
      s.sticks, s.slips, json_num(s.stick_fraction),
      s.sticks ? json_num(s.first_stick_start) : "null",
      s.sticks ? json_num(s.first_stick_duration) : "null", s.first_stick_censored);
  out += fmt::format(
      "  \"event_counts\": {{\"belt_switch\": {}, \"stick_onset\": {}, \"stick_break\": {}, "
      "\"slip_reversal\": {}}},\n",
      r.counts.belt_switches, r.counts.stick_onsets, r.counts.stick_breaks,
      r.counts.slip_reversals);
  out += "  \"episodes\": [";
  for (std::size_t i = 0; i < r.rec.episodes.size(); ++i) {
    const auto& e = r.rec.episodes[i];
    out += fmt::format(
        "{}\n    {{\"mode\": \"{}\", \"start\": {}, \"end\": {}, \"x_start\": {}, "
        "\"belt_velocity\": {}, \"censored\": {}}}",
        i ? "," : "", to_string(e.kind), json_num(e.start), json_num(e.end),
        json_num(e.position_at_start), json_num(e.belt_velocity), e.censored);
  }
  out += "\n  ]";
  if (with_events) {
    out += ",\n  \"events\": [";
    for (std::size_t i = 0; i < r.rec.events.size(); ++i) {
      const auto& e = r.rec.events[i];
      out += fmt::format(
          "{}\n    {{\"kind\": \"{}\", \"time\": {}, \"x\": {}, \"xdot\": {}, \"v\": {}}}",
          i ? "," : "", to_string(e.kind), json_num(e.time), json_num(e.position),
          json_num(e.velocity), json_num(e.belt_velocity));
    }
    out += "\n  ]";
  }
  out += "\n}\n";
  return out;
}

// t, x, x', v on the grid k*dt plus both ends of every closed-form segment
// (every event instant, so jumps of v and corners of x' are drawn exactly).
std::string trajectory_csv(const realization_run& r, double dt) {
  std::string out = "t,x,xdot,v,mode\n";
  auto row = [&](const segment& s, double t) {
    const auto p = evaluate(s, t);
    out += fmt::format("{},{},{},{},{}\n", num(t), num(p.position), num(p.velocity),
                       num(s.belt_velocity), to_string(s.kind));
  };
  for (const auto& s : r.rec.segments) {
    row(s, s.start);
    for (auto k = static_cast<std::uint64_t>(std::floor(s.start / dt)) + 1;; ++k) {
      const double t = static_cast<double>(k) * dt;
      if (t >= s.end) break;
      if (t > s.start) row(s, t);
    }
    if (s.end > s.start) row(s, s.end);
  }
  return out;
}

// Writes `text` to `path` atomically (path.tmp, then rename), creating the
// parent directory if needed.
void write_file(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  std::error_code ec;
  if (const auto dir = std::filesystem::path(path).parent_path(); !dir.empty())
    std::filesystem::create_directories(dir, ec);
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw io_error(tmp, "cannot open for writing");
    f << text;
    f.flush();
    if (!f) throw io_error(tmp, "write failed");
  }
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw io_error(path, "cannot rename from " + tmp);
  }
}

// A file next to the -o output, or in the current directory for stdout.
std::string beside_output(const simulate_options& o, const std::string& name) {
  if (o.output.empty() || o.output == "-") return name;
  return (std::filesystem::path(o.output).parent_path() / name).string();
}

void run_simulate(const CLI::App& cmd, const simulate_options& o) {
  // Check the trajectory step before the run.
  double dt = 0;
  if (o.trajectory_opt->count() > 0) {
    dt = io::parse_number("--trajectory (sampling step DT)", o.trajectory_step);
    if (!(dt > 0)) throw invalid_parameter("--trajectory (sampling step DT)", dt, "> 0");
  }
  const auto run = run_one(cmd, o);
  if (dt > 0 && run.params.window / dt > 1e7)
    throw invalid_parameter("--trajectory (sampling step DT)", dt,
                            fmt::format(">= t_a / 1e7 = {}", run.params.window / 1e7));

  const std::string table = o.format == "json" ? to_json(run, o.events) : episodes_csv(run);
  if (o.output.empty() || o.output == "-")
    std::fwrite(table.data(), 1, table.size(), stdout);
  else
    write_file(o.output, table);
  if (o.events && o.format == "csv")
    write_file(o.events_file.empty() ? beside_output(o, "events.csv") : o.events_file,
               events_csv(run));
  if (dt > 0)
    write_file(o.trajectory_file.empty() ? beside_output(o, "trajectory.csv") : o.trajectory_file,
               trajectory_csv(run, dt));

  const auto& s = run.record;
  fmt::print(stderr, "seed {} realization {}: S_T = {}, S_L = {}, R = {:.6g} ({} events)\n",
             run.seed, run.realization, s.sticks, s.slips, s.stick_fraction, run.counts.total());
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
  cmd->add_option("--realization", o.realization,
                  "realization index R: the same streams as realization R of a sweep (default 0)")
      ->type_name("R");
  const char* replay = "Replay (fixed inputs instead of random draws)";
  o.x0_opt = cmd->add_option("--x0", o.x0, "initial position x0 [m] (default: drawn)")
                 ->type_name("X")
                 ->group(replay);
  o.xdot0_opt = cmd->add_option("--xdot0", o.xdot0, "initial velocity x'0 [m/s] (default: drawn)")
                    ->type_name("U")
                    ->group(replay);
  o.belt_opt = cmd->add_option("--belt-start", o.belt_start,
                               "initial belt direction: +1, -1 or random (default: drawn)")
                   ->type_name("+1|-1")
                   ->group(replay);
  o.times_opt = cmd->add_option("--switch-times", o.switch_times,
                                "belt switch times t1,t2,... (sorted, >= 0) instead of Poisson")
                    ->type_name("LIST")
                    ->group(replay);
  o.times_file_opt =
      cmd->add_option("--switch-times-file", o.switch_times_file,
                      "file with one switch time per line ('#' comments allowed)")
          ->type_name("FILE")
          ->group(replay)
          ->excludes(o.times_opt);
  const char* output = "Output";
  cmd->add_option("--format", o.format, "episode table format: csv or json (default csv)")
      ->check(CLI::IsMember({"csv", "json"}))
      ->group(output);
  cmd->add_option("-o,--output", o.output, "write the episode table to FILE (default stdout)")
      ->type_name("FILE")
      ->group(output);
  cmd->add_flag("--events", o.events,
                "also output the events (kind,time,x,xdot,v): a key \"events\" in JSON, "
                "the --events-file in CSV")
      ->group(output);
  cmd->add_option("--events-file", o.events_file,
                  "CSV file for --events in CSV format (default events.csv next to -o, or in "
                  "the current directory)")
      ->type_name("FILE")
      ->group(output);
  o.trajectory_opt =
      cmd->add_option("--trajectory", o.trajectory_step,
                      "sample t,x,x',v every DT seconds plus at every event, into "
                      "--trajectory-file")
          ->type_name("DT")
          ->group(output);
  cmd->add_option("--trajectory-file", o.trajectory_file,
                  "CSV file for --trajectory (default trajectory.csv next to -o, or in the "
                  "current directory)")
      ->type_name("FILE")
      ->group(output);
  cmd->callback([cmd, opts] { run_simulate(*cmd, *opts); });
}

}  // namespace stickslip::app
