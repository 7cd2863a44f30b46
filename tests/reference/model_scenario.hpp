// Random scenarios across the model family for the oracle comparison, and a
// helper that runs the exact engine on them. std::mt19937_64 with a fixed
// seed: every run of the tests sees the same scenarios.
#pragma once
#include <cmath>
#include <random>
#include <vector>

#include "stickslip/model/belt_chain.hpp"
#include "stickslip/model/model_engine.hpp"

namespace stickslip::reference {

struct model_scenario {
  oscillator_model model;
  model_initial_state ic;
  std::vector<level_switch> switches;  // all < window
};

// mu_k in [0.01, 20] (log-uniform); mu_s = mu_k 35% of the time, else
// mu_k (1 + r), r in [0.01, 2] log-uniform; k in [0.5, 100], m in [0.5, 2];
// damping: 30% none, 10% critical (m = 1, c = 2 sqrt(k), exactly), else
// damping ratio in [0.02, 4] log-uniform (under- and over-damped); 2 to 4
// belt levels in [-2, 2] (|v| >= 0.2 or exactly 0, a zero level in a quarter
// of the scenarios), off-diagonal rates in [0.01, 30] / (n - 1) log-uniform,
// some 0 when n > 2; t_a in [1, 5] s. Initial state as in scenario.hpp (with
// the largest level speed), starting level uniform. Switches: the chain
// simulated by std::exponential_distribution and a discrete draw.
inline model_scenario draw_model_scenario(std::mt19937_64& rng) {
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(rng); };
  auto log_uniform = [&](double lo, double hi) {
    return std::exp(uniform(std::log(lo), std::log(hi)));
  };
  model_scenario s;
  oscillator_model& m = s.model;
  m.kinetic_friction = log_uniform(0.01, 20.0);
  m.static_friction =
      uniform(0, 1) < 0.35 ? m.kinetic_friction : m.kinetic_friction * (1.0 + log_uniform(0.01, 2.0));
  m.stiffness = log_uniform(0.5, 100.0);
  m.mass = uniform(0.5, 2.0);
  const double damping_pick = uniform(0, 1);
  if (damping_pick < 0.3) {
    m.damping = 0.0;
  } else if (damping_pick < 0.4) {
    m.mass = 1.0;
    m.damping = 2.0 * m.natural_frequency();  // gamma = omega_0 exactly
  } else {
    m.damping = 2.0 * log_uniform(0.02, 4.0) * std::sqrt(m.stiffness * m.mass);
  }
  const int n = uniform(0, 1) < 0.5 ? 2 : (uniform(0, 1) < 0.6 ? 3 : 4);
  const bool with_rest = uniform(0, 1) < 0.25;
  std::vector<double> levels;
  while (static_cast<int>(levels.size()) < n) {
    double v = uniform(-2.0, 2.0);
    if (with_rest && levels.empty()) v = 0.0;
    else if (std::abs(v) < 0.2) continue;
    bool distinct = true;
    for (double u : levels) distinct = distinct && std::abs(u - v) > 0.05;
    if (distinct) levels.push_back(v);
  }
  std::vector<double> q(static_cast<std::size_t>(n * n), 0.0);
  for (int i = 0; i < n; ++i) {
    double row = 0.0;
    while (!(row > 0.0)) {
      row = 0.0;
      for (int j = 0; j < n; ++j) {
        if (j == i) continue;
        const double r = (n > 2 && uniform(0, 1) < 0.2) ? 0.0 : log_uniform(0.01, 30.0) / (n - 1);
        q[static_cast<std::size_t>(i * n + j)] = r;
        row += r;
      }
    }
    q[static_cast<std::size_t>(i * n + i)] = -row;
  }
  m.belt = markov_belt{levels, q};
  m.window = uniform(1.0, 5.0);

  s.ic.level = static_cast<std::size_t>(std::uniform_int_distribution<>(0, n - 1)(rng));
  double vmax = 0;
  for (double v : levels) vmax = std::max(vmax, std::abs(v));
  const double a = m.static_band_half_width(), w = m.natural_frequency();
  const double pick = uniform(0, 1);
  if (pick < 0.45) {
    s.ic.position = uniform(-1.0, 1.0);
    s.ic.velocity = uniform(-1.0, 1.0);
  } else if (pick < 0.9) {
    const double scale = a + vmax / w;
    s.ic.position = uniform(-2.0, 2.0) * scale;
    s.ic.velocity = uniform(-2.0, 2.0) * vmax;
  } else {
    s.ic.position = uniform(-1.5, 1.5) * a - m.damping * levels[s.ic.level] / m.stiffness;
    s.ic.velocity = levels[s.ic.level];
  }
  std::size_t level = s.ic.level;
  double t = 0.0;
  while (true) {
    const double rate = -q[level * static_cast<std::size_t>(n) + level];
    t += std::exponential_distribution<>(rate)(rng);
    if (t >= m.window) break;
    const std::size_t nn = static_cast<std::size_t>(n);
    const double u = uniform(0.0, rate);
    double acc = 0.0;
    std::size_t next = level;
    for (std::size_t j = 0; j < nn; ++j) {
      if (j == level || q[level * nn + j] == 0.0) continue;
      next = j;  // the last positive rate takes any rounding remainder
      acc += q[level * nn + j];
      if (u < acc) break;
    }
    level = next;
    s.switches.push_back({t, level});
  }
  return s;
}

struct model_exact_run {
  std::vector<episode> episodes;
  std::vector<event> events;
  std::vector<segment> segments;
  event_counts counts;
};

struct model_recording_observer {
  model_exact_run* out;
  void on_event(const event& e) { out->events.push_back(e); }
  void on_segment(const segment& s) { out->segments.push_back(s); }
  void on_episode(const episode& e) { out->episodes.push_back(e); }
};

inline model_exact_run run_model_exact(const model_scenario& s) {
  model_exact_run r;
  model_recording_observer obs{&r};
  given_level_switches sw(s.switches);
  r.counts = simulate_model(s.model, s.ic, sw, obs);
  return r;
}

}  // namespace stickslip::reference
