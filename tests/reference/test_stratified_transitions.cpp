// Every event transition of the model family's exact engine (simulate_model),
// at the scales users run, against the independent RK4 oracle
// (model_oracle.hpp): stratified scenarios, not only random ones.
//
// Random scenarios over many decades (test_model_oracle_agreement.cpp) rarely
// produce some transitions: a stick between a_k and a_s, moving inward, ended
// by a belt switch to the opposite level (mu_s > mu_k, symmetric belt), whose
// slip returns after half a period at 2 a_k - x, not at the mirror point. An
// engine got that branch wrong and no test saw it. Here the scenarios are
// drawn at the paper's scale (k = 4-80, m = 1, mu_k in the paper's [0.5, 7],
// mu_s / mu_k = 1 or in [1.25, 2], switch rates 0.5-10 per level, symmetric
// +-1, asymmetric two-level and three-level belts, undamped and lightly
// damped), each slip and stick is labelled by what started it and what ended
// it, and every transition the engine can take must occur >= 50 times among
// the scenarios with k in [20, 80] (the paper's stiffness range), each one
// checked against the oracle: identical episode sequences, boundaries within
// the oracle's error bound (model_agreement.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "reference/model_agreement.hpp"
#include "reference/model_oracle.hpp"
#include "reference/model_scenario.hpp"

namespace stickslip::reference {
namespace {

constexpr double steps_per_period = 800;

// One scenario at the paper's scale (see the header comment). Belt: kind 0
// symmetric +-1 (half of the scenarios), 1 two levels {1, v2} with v2 in
// [-2, -0.3] or [0.3, 2] away from 1, 2 three levels {1, -1, v3}, v3 in
// [-0.5, 0.5] (0 one time in three: a resting level). Damping: none in 60 %,
// else zeta in [0.02, 0.3]. Initial state uniform over |x| <= a_s + 1/w,
// |x'| <= 1, or (15 %) at the belt velocity inside the band, the start level
// uniform. Window 6-12 s.
model_scenario draw_paper_scale_scenario(std::mt19937_64& rng) {
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(rng); };
  auto log_uniform = [&](double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); };
  model_scenario s;
  oscillator_model& m = s.model;
  m.mass = 1.0;
  m.stiffness = log_uniform(4.0, 80.0);
  m.kinetic_friction = uniform(0.5, 7.0);
  m.static_friction = uniform(0, 1) < 0.25 ? m.kinetic_friction : m.kinetic_friction * uniform(1.25, 2.0);
  m.damping = uniform(0, 1) < 0.6 ? 0.0 : 2.0 * uniform(0.02, 0.3) * std::sqrt(m.stiffness);
  const double belt_pick = uniform(0, 1);
  std::vector<double> levels{1.0, -1.0};
  if (belt_pick >= 0.5 && belt_pick < 0.75) {
    levels[1] = uniform(0, 1) < 0.7 ? -uniform(0.3, 2.0) : uniform(0.3, 0.8) + (uniform(0, 1) < 0.5 ? 0.0 : 0.7);
  } else if (belt_pick >= 0.75) {
    levels.push_back(uniform(0, 1) < 1.0 / 3.0 ? 0.0 : uniform(-0.5, 0.5));
  }
  const std::size_t n = levels.size();
  std::vector<double> q(n * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double rate = log_uniform(0.5, 10.0);
    for (std::size_t j = 0; j < n; ++j)
      if (j != i) q[i * n + j] = rate / static_cast<double>(n - 1);
    q[i * n + i] = -rate;
  }
  m.belt = markov_belt{levels, q};
  m.window = uniform(6.0, 12.0);
  const double reach = m.static_band_half_width() + 1.0 / m.natural_frequency();
  s.ic.level = static_cast<std::size_t>(std::uniform_int_distribution<>(0, static_cast<int>(n) - 1)(rng));
  s.ic.position = uniform(-reach, reach);
  s.ic.velocity = uniform(-1.0, 1.0);
  if (uniform(0, 1) < 0.15) {  // at the belt velocity inside the band: a stick at t = 0
    s.ic.velocity = levels[s.ic.level];
    s.ic.position = uniform(-0.95, 0.95) * m.static_band_half_width() - m.damping * s.ic.velocity / m.stiffness;
  }
  std::size_t level = s.ic.level;
  double t = 0.0;
  while (true) {
    const double rate = -q[level * n + level];
    t += std::exponential_distribution<>(rate)(rng);
    if (t >= m.window) break;
    std::size_t next = std::uniform_int_distribution<std::size_t>(0, n - 2)(rng);
    if (next >= level) ++next;
    level = next;
    s.switches.push_back({t, level});
  }
  return s;
}

// What started an episode and what ended it, read from the engine's events
// (the labels are the test's, from the physics; the engine has no such
// names). A stick ended by a switch to the opposite level of an undamped
// model leaves a "mirror" slip when sigma (x - sigma a_k) < 0 (|x| inside
// the kinetic band) and a "half turn" slip otherwise.
std::vector<std::string> transitions(const model_scenario& s, const model_exact_run& r) {
  const oscillator_model& m = s.model;
  const bool damped = m.damping > 0.0;
  const bool equal = m.static_friction == m.kinetic_friction;
  const double ak = m.kinetic_offset();
  const std::string regime = damped ? "damped " : "undamped ";
  std::vector<std::string> out;
  mode now = r.episodes.front().kind;
  std::string cause = "start";
  double v = m.belt.levels[s.ic.level];
  auto end = [&](const std::string& how) {
    out.push_back(regime + (now == mode::stick ? "stick(" : "slip(") + cause + ") -> " + how);
  };
  for (const event& e : r.events) {
    switch (e.kind) {
      case event_kind::belt_switch:
        end("switch");
        if (now == mode::stick) {
          const double sigma = e.belt_velocity > v ? 1.0 : -1.0;
          if (v == 0.0)
            cause = "switch from rest";
          else if (!damped && e.belt_velocity == -v)
            cause = sigma * (e.position - sigma * ak) < 0.0 ? "mirror" : "half turn";
          else
            cause = "switch from stick";
        } else {
          cause = "switch in slip";
        }
        now = mode::slip;
        v = e.belt_velocity;
        break;
      case event_kind::stick_onset:
        end("onset");
        now = mode::stick;
        cause = "onset";
        break;
      case event_kind::stick_break:
        end("break");
        now = mode::slip;
        cause = equal ? "break, graze" : "break, return";
        break;
      case event_kind::slip_reversal:
        end("reversal");
        cause = "reversal";
        break;
    }
  }
  end("t_a");
  return out;
}

TEST(StratifiedTransitions, EveryTransitionAtThePapersScaleAgreesWithTheOracle) {
  std::mt19937_64 rng(0x57a7'1f1edULL);
  std::map<std::string, int> count;  // among the accepted scenarios with k in [20, 80]
  int accepted = 0, regenerated = 0, paper_scale = 0;
  while (accepted < 10000) {
    const model_scenario s = draw_paper_scale_scenario(rng);
    const scenario_run run = run_both(s, steps_per_period);
    if (run.degenerate) {
      ++regenerated;
      continue;
    }
    ++accepted;
    if (!expect_agreement(s, run)) return;
    if (s.model.stiffness < 20.0) continue;
    ++paper_scale;
    for (const std::string& t : transitions(s, run.exact)) ++count[t];
  }
  std::printf("stratified transitions: %d scenarios (%d with k >= 20), %d regenerated\n", accepted,
              paper_scale, regenerated);
  for (const auto& [name, n] : count) std::printf("  %6d  %s\n", n, name.c_str());
  EXPECT_LE(regenerated, accepted / 10);
  // Every transition seen must be seen >= 50 times, except these, which the
  // physics makes rare at this scale (the window ending during a rare kind
  // of slip, a reversal right after a switch out of a stick; counts of the
  // k >= 20 half): listed so that a new label, or one that fades, fails the
  // test instead of passing unnoticed.
  const std::set<std::string> rare = {
      "undamped slip(switch from stick) -> reversal",  // 17 of 10,000 scenarios
      "undamped slip(half turn) -> t_a",               // 32
      "undamped slip(reversal) -> t_a",                // 30
      "undamped slip(switch from rest) -> t_a",        // 11
      "damped slip(reversal) -> t_a",                  // 10
      "damped slip(switch from rest) -> t_a",          // 18
  };

  for (const auto& [name, n] : count) {
    if (!rare.count(name)) {
      EXPECT_GE(n, 50) << name;
    }
  }
  // And the ones that matter most must be there at all: the transitions of
  // each kind of slip start, undamped and damped, and the half turn.
  const char* required[] = {
      "undamped slip(half turn) -> onset",      "undamped slip(half turn) -> switch",
      "undamped slip(mirror) -> onset",         "undamped slip(switch from stick) -> onset",
      "undamped slip(switch from rest) -> onset", "undamped slip(break, graze) -> switch",
      "undamped slip(break, return) -> onset",  "undamped slip(reversal) -> onset",
      "undamped stick(onset) -> break",         "undamped stick(start) -> switch",
      "damped slip(switch from stick) -> onset", "damped slip(break, return) -> onset",
      "damped slip(break, graze) -> switch",    "damped slip(reversal) -> onset",
      "damped stick(onset) -> break",           "damped slip(start) -> reversal",
  };
  for (const char* name : required) EXPECT_GE(count[name], 50) << name;
}

}  // namespace
}  // namespace stickslip::reference
