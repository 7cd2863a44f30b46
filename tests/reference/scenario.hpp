// Random scenarios for the oracle comparison, and helpers that run the exact
// integrator on them. Scenario generation uses std::mt19937_64 with a fixed
// seed, so every run of the tests sees the same scenarios.
#pragma once
#include <cmath>
#include <random>
#include <vector>

#include "stickslip/belt_switches.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/observer.hpp"

namespace stickslip::reference {

struct scenario {
  model_parameters params;
  initial_conditions ic;
  std::vector<double> switch_times;  // sorted, all < params.window
};

// lambda in [0.01, 100], mu in [0.01, 20], k in [0.5, 100] (all log-uniform, so
// both ends of each range are exercised); m, V in [0.5, 2]; t_a in [1, 5] s.
// Initial state: 45% the paper's law (x0, x'0 uniform on [-1, 1]), 45% scaled
// to the band (|x0| up to 2 (a + V/w), |x'0| up to 2 V), 10% starting exactly
// on the belt velocity (x'0 = +-V), which exercises the start-in-stick path.
// Switch times: cumulative Exp(lambda) waits up to t_a.
inline scenario draw_scenario(std::mt19937_64& rng) {
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(rng); };
  auto log_uniform = [&](double lo, double hi) {
    return std::exp(uniform(std::log(lo), std::log(hi)));
  };
  scenario s;
  model_parameters& p = s.params;
  p.switch_rate = log_uniform(0.01, 100.0);
  p.friction_coefficient = log_uniform(0.01, 20.0);
  p.stiffness = log_uniform(0.5, 100.0);
  p.mass = uniform(0.5, 2.0);
  p.belt_speed = uniform(0.5, 2.0);
  p.window = uniform(1.0, 5.0);
  const double a = p.band_half_width(), w = p.natural_frequency(), V = p.belt_speed;
  s.ic.belt_direction = uniform(0.0, 1.0) < 0.5 ? 1 : -1;
  const double pick = uniform(0.0, 1.0);
  if (pick < 0.45) {
    s.ic.position = uniform(-1.0, 1.0);
    s.ic.velocity = uniform(-1.0, 1.0);
  } else if (pick < 0.9) {
    const double scale = a + V / w;
    s.ic.position = uniform(-2.0, 2.0) * scale;
    s.ic.velocity = uniform(-2.0, 2.0) * V;
  } else {
    s.ic.position = uniform(-1.5, 1.5) * a;
    s.ic.velocity = (uniform(0.0, 1.0) < 0.5 ? 1.0 : -1.0) * V;
  }
  std::exponential_distribution<> wait(p.switch_rate);
  for (double t = wait(rng); t < p.window; t += wait(rng)) s.switch_times.push_back(t);
  return s;
}

// Everything the exact integrator reports for one scenario.
struct exact_run {
  std::vector<episode> episodes;
  std::vector<event> events;
  std::vector<segment> segments;
  event_counts counts;
};

struct recording_observer {
  exact_run* out;
  void on_event(const event& e) { out->events.push_back(e); }
  void on_segment(const segment& s) { out->segments.push_back(s); }
  void on_episode(const episode& e) { out->episodes.push_back(e); }
};

inline exact_run run_exact(const model_parameters& p, const initial_conditions& ic,
                           const std::vector<double>& switch_times) {
  exact_run r;
  recording_observer obs{&r};
  given_switches sw(switch_times);
  r.counts = simulate(p, ic, sw, obs);
  return r;
}

}  // namespace stickslip::reference
