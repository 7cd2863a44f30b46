#include "scenario.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "stickslip/belt_switches.hpp"
#include "stickslip/observer.hpp"
#include "stickslip/random_stream.hpp"

namespace stickslip::bench {

scenario make_scenario(int id, const model_parameters& params, std::uint64_t seed,
                       std::uint64_t realization) {
  scenario s;
  s.id = id;
  s.seed = seed;
  s.realization = realization;
  s.params = params;
  const auto key = point_key(params);
  s.initial = draw_initial_conditions(initial_condition_law{}, seed, key, realization);
  poisson_switches sw(params.switch_rate, seed, key, realization);
  for (double t = sw.next(); t < params.window; t = sw.next()) s.switch_times.push_back(t);
  return s;
}

namespace {

struct stick_recorder : observer_base {
  std::vector<stick_interval>* sticks;
  void on_episode(const episode& e) {
    if (e.kind == mode::stick) sticks->push_back({e.start, e.end, e.censored});
  }
};

}  // namespace

method_run run_exact(const scenario& s, double window) {
  method_run out;
  model_parameters p = s.params;
  p.window = window;
  given_switches sw(s.switch_times);
  stick_recorder rec;
  rec.sticks = &out.sticks;
  out.counts = simulate(p, s.initial, sw, rec);
  return out;
}

stick_comparison compare_sticks(const std::vector<stick_interval>& exact,
                                const std::vector<stick_interval>& method,
                                double match_tolerance) {
  stick_comparison c;
  std::size_t i = 0, j = 0;
  while (i < exact.size() || j < method.size()) {
    if (i < exact.size() && j < method.size() &&
        std::abs(exact[i].start - method[j].start) < match_tolerance) {
      ++c.matched;
      // The start of a stick at t = 0 and the end of a censored stick are not events.
      if (exact[i].start > 0.0) c.max_boundary_error = std::max(c.max_boundary_error, std::abs(exact[i].start - method[j].start));
      if (!exact[i].censored || !method[j].censored)
        c.max_boundary_error = std::max(c.max_boundary_error, std::abs(exact[i].end - method[j].end));
      ++i;
      ++j;
    } else if (j < method.size() && (i == exact.size() || method[j].start < exact[i].start)) {
      ++c.spurious;
      c.max_spurious_duration = std::max(c.max_spurious_duration, method[j].end - method[j].start);
      ++j;
    } else {
      ++c.missed;
      ++i;
    }
  }
  return c;
}

void write_scenario_file(const std::string& path, const scenario& s, double window) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f << std::setprecision(17);
  const auto& p = s.params;
  f << "id " << s.id << "\nseed " << s.seed << "\nrealization " << s.realization
    << "\nlambda " << p.switch_rate << "\nm " << p.mass << "\nk " << p.stiffness << "\ng "
    << p.gravity << "\nmu " << p.friction_coefficient << "\nV " << p.belt_speed << "\nwindow "
    << window << "\nx0 " << s.initial.position << "\nxdot0 " << s.initial.velocity << "\nbelt "
    << s.initial.belt_direction << "\n";
  std::size_t n = 0;
  while (n < s.switch_times.size() && s.switch_times[n] < window) ++n;
  f << "switches " << n;
  for (std::size_t i = 0; i < n; ++i) f << ' ' << s.switch_times[i];
  f << "\n";
  if (!f) throw std::runtime_error("error writing " + path);
}

method_run read_method_file(const std::string& path, double& cpu_seconds, double& wall_seconds) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error("cannot read " + path);
  method_run out;
  std::string line;
  while (std::getline(f, line)) {
    std::istringstream in(line);
    std::string key;
    in >> key;
    if (key == "cpu") in >> cpu_seconds;
    else if (key == "wall") in >> wall_seconds;
    else if (key == "steps") in >> out.steps;
    else if (key == "counts")
      in >> out.counts.belt_switches >> out.counts.stick_onsets >> out.counts.stick_breaks >>
          out.counts.slip_reversals;
    else if (key == "stick") {
      stick_interval s;
      int censored = 0;
      in >> s.start >> s.end >> censored;
      s.censored = censored != 0;
      out.sticks.push_back(s);
    }
  }
  return out;
}

}  // namespace stickslip::bench
