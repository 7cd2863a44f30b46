// stickslip_compare: the side-by-side comparison with ODE solvers (bench/compare.sh).
//   emit  --dir D ...   write one scenario file per realization for Octave
//   table --dir D ...   time exact / CVODE / odeint on the full window, read
//                       Octave's results for the short window, print the table
// Both take the same grid options; scenarios are pure functions of them.
#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <ctime>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "cvode_solver.hpp"
#include "hybrid_driver.hpp"
#include "odeint_solver.hpp"
#include "scenario.hpp"

namespace sb = stickslip::bench;

namespace {

struct grid_options {
  std::vector<double> lambdas{0.1, 3.8, 30.0};
  std::vector<double> stiffnesses{4.0, 40.0};
  double mu = 5.0;
  int realizations = 2;
  std::uint64_t seed = 1;
  double window = 50.0;
  double octave_window = 10.0;
  double min_seconds = 0.5;  // per timed method and group
  std::string dir = "bench-compare";
};

struct group {
  double k, lambda;
  std::vector<sb::scenario> scenarios;
};

std::vector<group> make_groups(const grid_options& o) {
  std::vector<group> groups;
  int id = 0;
  for (double k : o.stiffnesses)
    for (double lambda : o.lambdas) {
      group g{k, lambda, {}};
      stickslip::model_parameters p;
      p.stiffness = k;
      p.friction_coefficient = o.mu;
      p.switch_rate = lambda;
      p.window = o.window;
      for (int r = 0; r < o.realizations; ++r)
        g.scenarios.push_back(sb::make_scenario(id++, p, o.seed, static_cast<std::uint64_t>(r)));
      groups.push_back(std::move(g));
    }
  return groups;
}

std::string scenario_path(const grid_options& o, int id, const char* ext) {
  return fmt::format("{}/scenario_{:03d}.{}", o.dir, id, ext);
}

// CPU time of this thread: the machine may be shared, and Octave reports
// cputime too, so every method is charged its own CPU seconds.
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Run `fn` over the group's scenarios, repeating until `min_seconds` of CPU
// time have passed; returns CPU seconds per realization and the results of
// the first pass.
double time_group(const group& g, double min_seconds,
                  const std::function<sb::method_run(const sb::scenario&)>& fn,
                  std::vector<sb::method_run>& results) {
  results.clear();
  const double t0 = thread_cpu_seconds();
  std::size_t runs = 0;
  double elapsed = 0.0;
  do {
    for (const auto& s : g.scenarios) {
      auto r = fn(s);
      if (results.size() < g.scenarios.size()) results.push_back(std::move(r));
      ++runs;
    }
    elapsed = thread_cpu_seconds() - t0;
  } while (elapsed < min_seconds);
  return elapsed / static_cast<double>(runs);
}

std::string format_time(double s) {
  if (s >= 3600.0) return fmt::format("{:.2f} h", s / 3600.0);
  if (s >= 60.0) return fmt::format("{:.1f} min", s / 60.0);
  if (s >= 1.0) return fmt::format("{:.2f} s", s);
  if (s >= 1e-3) return fmt::format("{:.2f} ms", s * 1e3);
  return fmt::format("{:.1f} µs", s * 1e6);
}

struct row {
  std::string method;
  double seconds = 0.0;
  bool extrapolated = false;
  sb::stick_comparison cmp;
  double exact_sticks = 0.0;  // per realization, on the compared window
  double steps = 0.0;         // per realization
};

void print_row(const row& r, double exact_seconds) {
  const std::string t = (r.extrapolated ? "~" : "") + format_time(r.seconds) + (r.extrapolated ? " (extrap.)" : "");
  const std::string err = r.method.rfind("exact", 0) == 0 ? "reference" : fmt::format("{:.1e} s", r.cmp.max_boundary_error);
  const std::string spurious = r.cmp.spurious == 0 ? "0" : fmt::format("{} (max {:.0e} s)", r.cmp.spurious, r.cmp.max_spurious_duration);
  fmt::print("| {} | {} | {:.3g}× | {} | {} | {} | {:.1f} | {:.3g} |\n", r.method, t,
             r.seconds / exact_seconds, err, spurious, r.cmp.missed, r.exact_sticks, r.steps);
}

sb::stick_comparison total_comparison(const group& g, const std::vector<sb::method_run>& exact,
                                      const std::vector<sb::method_run>& method) {
  sb::stick_comparison all;
  for (std::size_t i = 0; i < g.scenarios.size(); ++i) {
    const auto c = sb::compare_sticks(exact[i].sticks, method[i].sticks);
    all.matched += c.matched;
    all.spurious += c.spurious;
    all.missed += c.missed;
    all.max_boundary_error = std::max(all.max_boundary_error, c.max_boundary_error);
    all.max_spurious_duration = std::max(all.max_spurious_duration, c.max_spurious_duration);
  }
  return all;
}

double mean_sticks(const std::vector<sb::method_run>& runs) {
  double n = 0;
  for (const auto& r : runs) n += static_cast<double>(r.sticks.size());
  return n / static_cast<double>(runs.size());
}

double mean_steps(const std::vector<sb::method_run>& runs) {
  double n = 0;
  for (const auto& r : runs) n += static_cast<double>(r.steps);
  return n / static_cast<double>(runs.size());
}

// Print the exact and a method's sticks of one scenario side by side.
void diff(const grid_options& o, int id, const std::string& method) {
  for (const auto& g : make_groups(o))
    for (const auto& s : g.scenarios) {
      if (s.id != id) continue;
      constexpr double tol = 1e-9;
      sb::method_run run;
      double window = o.window;
      if (method == "cvode") {
        sb::cvode_adams solver(tol, tol);
        run = sb::run_hybrid(s, window, solver);
      } else if (method == "odeint") {
        sb::odeint_dopri5 solver(tol, tol);
        run = sb::run_hybrid(s, window, solver);
      } else {
        double c = 0, w = 0;
        run = sb::read_method_file(scenario_path(o, id, "octave"), c, w);
        window = o.octave_window;
      }
      const auto exact = sb::run_exact(s, window);
      fmt::print("scenario {} (k = {}, lambda = {}, realization {}), window {} s\n", id, g.k, g.lambda,
                 s.realization, window);
      for (const auto& e : exact.sticks) fmt::print("exact  stick {:.12f} {:.12f}{}\n", e.start, e.end, e.censored ? " censored" : "");
      for (const auto& e : run.sticks) fmt::print("{} stick {:.12f} {:.12f}{}\n", method, e.start, e.end, e.censored ? " censored" : "");
    }
}

void emit(const grid_options& o) {
  std::filesystem::create_directories(o.dir);
  for (const auto& g : make_groups(o))
    for (const auto& s : g.scenarios) sb::write_scenario_file(scenario_path(o, s.id, "txt"), s, o.octave_window);
}

void table(const grid_options& o) {
  constexpr double tol = 1e-9;
  fmt::print("Scenarios: mu = {}, m = 1, g = 9.81, V = 1, seed {}, realizations 0..{} per (k, lambda), "
             "initial conditions and switch times from the core's Philox streams.\n",
             o.mu, o.seed, o.realizations - 1);
  fmt::print("Exact, CVODE and odeint: full {} s windows. Octave ode45: {} s windows, time scaled by {}/{} "
             "to one {} s realization (~ = extrapolated); its errors are on the short window.\n",
             o.window, o.octave_window, o.window, o.octave_window, o.window);
  fmt::print("Times are CPU seconds of one core per {} s realization.\n", o.window);
  fmt::print("Sticks are matched by start time (within 1e-3 s); boundary error = max |t - t_exact| over the "
             "starts and ends of matched sticks.\n\n");
  for (const auto& g : make_groups(o)) {
    fmt::print("### k = {}, lambda = {}\n\n", g.k, g.lambda);
    fmt::print("| method | time per realization | time / exact | max boundary error | spurious sticks | missed sticks | exact sticks per realization | steps per realization |\n");
    fmt::print("|---|---|---|---|---|---|---|---|\n");
    std::vector<sb::method_run> exact, runs;
    const double exact_s = time_group(g, o.min_seconds, [&](const sb::scenario& s) { return sb::run_exact(s, o.window); }, exact);
    stickslip::event_counts events;
    for (const auto& e : exact) events += e.counts;
    row ex{"exact (ours)", exact_s, false, {}, mean_sticks(exact), 0.0};
    print_row(ex, exact_s);

    auto solver_row = [&](const std::string& name, const std::function<sb::method_run(const sb::scenario&)>& fn) {
      const double s = time_group(g, o.min_seconds, fn, runs);
      print_row(row{name, s, false, total_comparison(g, exact, runs), mean_sticks(exact), mean_steps(runs)}, exact_s);
    };
    solver_row("CVODE Adams, tol 1e-9", [&](const sb::scenario& s) {
      sb::cvode_adams solver(tol, tol);
      return sb::run_hybrid(s, o.window, solver);
    });
    solver_row("odeint dopri5, tol 1e-9", [&](const sb::scenario& s) {
      sb::odeint_dopri5 solver(tol, tol);
      return sb::run_hybrid(s, o.window, solver);
    });
    solver_row("odeint dopri5, tol 1e-9, max step 1e-4", [&](const sb::scenario& s) {
      sb::odeint_dopri5 solver(tol, tol, 1e-4);
      return sb::run_hybrid(s, o.window, solver);
    });

    // Octave ode45 on the short window.
    std::vector<sb::method_run> octave, exact_short;
    double cpu = 0.0;
    bool have_octave = true;
    for (const auto& s : g.scenarios) {
      const auto path = scenario_path(o, s.id, "octave");
      if (!std::filesystem::exists(path)) {
        have_octave = false;
        break;
      }
      double c = 0.0, w = 0.0;
      octave.push_back(sb::read_method_file(path, c, w));
      cpu += c;
      exact_short.push_back(sb::run_exact(s, o.octave_window));
    }
    if (have_octave) {
      const double per = cpu / static_cast<double>(g.scenarios.size()) * (o.window / o.octave_window);
      row r{fmt::format("Octave ode45 (paper), {} s window", o.octave_window), per, o.octave_window < o.window,
            total_comparison(g, exact_short, octave), mean_sticks(exact_short), mean_steps(octave)};
      print_row(r, exact_s);
    } else {
      fmt::print("| Octave ode45 (paper) | not run | | | | | | |\n");
    }
    const double n = static_cast<double>(g.scenarios.size());
    fmt::print("\nExact events per realization: {:.1f} belt switches, {:.1f} stick onsets, {:.1f} stick breaks, "
               "{:.1f} slip reversals; {:.3g} events/s.\n\n",
               events.belt_switches / n, events.stick_onsets / n, events.stick_breaks / n,
               events.slip_reversals / n, static_cast<double>(events.total()) / n / exact_s);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"stickslip_compare: exact method vs ODE solvers with events"};
  app.require_subcommand(1);
  grid_options o;
  auto add_grid = [&](CLI::App* c) {
    c->add_option("--dir", o.dir, "scenario and result directory");
    c->add_option("--lambda", o.lambdas, "switch rates")->delimiter(',');
    c->add_option("--k", o.stiffnesses, "stiffnesses")->delimiter(',');
    c->add_option("--mu", o.mu, "friction coefficient");
    c->add_option("--realizations", o.realizations, "realizations per (k, lambda)");
    c->add_option("--seed", o.seed, "seed");
    c->add_option("--window", o.window, "full window t_a [s]");
    c->add_option("--octave-window", o.octave_window, "Octave's short window [s]");
  };
  auto* e = app.add_subcommand("emit", "write scenario files for Octave");
  add_grid(e);
  auto* t = app.add_subcommand("table", "run the C++ methods and print the table");
  add_grid(t);
  t->add_option("--min-seconds", o.min_seconds, "minimum timing per method and group");
  auto* d = app.add_subcommand("diff", "print one scenario's sticks: exact and a method");
  add_grid(d);
  int diff_id = 0;
  std::string diff_method = "octave";
  d->add_option("--id", diff_id, "scenario id")->required();
  d->add_option("--method", diff_method, "octave, cvode or odeint");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& err) {
    return app.exit(err);
  }
  try {
    if (e->parsed()) emit(o);
    if (t->parsed()) table(o);
    if (d->parsed()) diff(o, diff_id, diff_method);
  } catch (const std::exception& ex) {
    fmt::print(stderr, "stickslip_compare: {}\n", ex.what());
    return 1;
  }
  return 0;
}
