// The exact engine of the model family (simulate_model) against the
// independent RK4 oracle (model_oracle.hpp) on random scenarios spanning the
// family: mu_s = mu_k and mu_s > mu_k, undamped, under-, critically and
// over-damped slips, 2 to 4 belt levels with a resting (v = 0) level in a
// quarter of them, level-dependent rates.
//
// What must agree: the episode sequences exactly (count and modes), and every
// boundary and start position within the oracle's error, with the bound of
// test_oracle_agreement.cpp: tol_t = 10 kappa E(N) + 1e-12 t_a,
// E(N) = t_a (2 pi / N)^4 / 120, kappa = 1 + B / V_min (B the largest orbit
// speed amplitude, V_min the slowest moving level).
//
// Near-degenerate scenarios are regenerated (counted, and required rare):
// a stick shorter than 10 stick resolutions; a contact whose stick force
// |k x + c v| lies within 1e3 tol of mu_s m g (stick vs reversal flips); an
// event within 1e3 tol_t of a belt switch; a near tangency the oracle flags
// (an extremum of x' within its resolution of v).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>

#include "reference/model_agreement.hpp"
#include "reference/model_oracle.hpp"
#include "reference/model_scenario.hpp"
#include "stickslip/statistics.hpp"

namespace stickslip::reference {
namespace {

constexpr std::uint64_t scenario_seed = 0xfa417'5eedULL;
constexpr int scenario_count = 1000;
constexpr double steps_per_period = 800;

TEST(ModelOracleAgreement, RandomFamilyScenariosHaveIdenticalEpisodeSequences) {
  std::mt19937_64 rng(scenario_seed);
  const auto t0 = std::chrono::steady_clock::now();
  int accepted = 0, regenerated = 0, sticks = 0, with_stick = 0;
  int undamped = 0, under = 0, critical = 0, over = 0, unequal = 0, resting = 0, many_levels = 0;
  int rest_sticks = 0;
  double max_ratio = 0;
  while (accepted < scenario_count) {
    const model_scenario s = draw_model_scenario(rng);
    const scenario_run run = run_both(s, steps_per_period);
    const model_exact_run& exact = run.exact;
    if (run.degenerate) {
      ++regenerated;
      std::printf("regenerated (%s): %s\n", run.degenerate->c_str(), describe(s).c_str());
      continue;
    }
    ++accepted;
    const auto d = expect_agreement(s, run);
    if (!d) return;
    max_ratio = std::max(max_ratio, d->time / run.tol.time);
    int n_sticks = 0;
    for (const episode& e : exact.episodes) {
      n_sticks += e.kind == mode::stick;
      rest_sticks += e.kind == mode::stick && e.belt_velocity == 0.0;
    }
    sticks += n_sticks;
    with_stick += n_sticks > 0;
    const oscillator_model& m = s.model;
    const double zeta = m.damping_ratio();
    undamped += m.damping == 0.0;
    under += m.damping > 0.0 && zeta < 1.0;
    critical += m.damping > 0.0 && zeta == 1.0;
    over += zeta > 1.0;
    unequal += m.static_friction > m.kinetic_friction;
    many_levels += m.belt.level_count() > 2;
    resting += std::find(m.belt.levels.begin(), m.belt.levels.end(), 0.0) != m.belt.levels.end();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf(
      "model oracle agreement: %d scenarios (%d regenerated), %d sticks (%d at rest), %d with a "
      "stick; undamped %d, under %d, critical %d, over %d; mu_s > mu_k %d; > 2 levels %d; a "
      "resting level %d; max boundary error %.3g of tolerance; %.2f s\n",
      accepted, regenerated, sticks, rest_sticks, with_stick, undamped, under, critical, over,
      unequal, many_levels, resting, max_ratio, seconds);
  EXPECT_LE(regenerated, scenario_count / 10);
  EXPECT_GT(with_stick, scenario_count / 2);
  EXPECT_GT(critical, 30);
  EXPECT_GT(over, 50);
  EXPECT_GT(under, 200);
  EXPECT_GT(rest_sticks, 20);
}


// Hand-picked starts on the edges of the cases, each with one right answer
// that both integrators must give (no degeneracy filter): on the outward band
// edge at belt velocity (a zero-length stick: slip on; with mu_s = mu_k no
// return until a switch, with mu_s > mu_k a return and a stick), on the
// inward edge (a stick across the band), outside the band at belt velocity (a
// reversal), at rest on a resting level inside and outside the band, and
// belt switches at t = 0, for c = 0, under- and over-damped. g = 8, m = 1,
// k = 4, mu_k = 0.5: a_k = 1 exactly.
TEST(ModelOracleAgreement, EdgeStartsAndSwitchesAtZero) {
  int checked = 0;
  for (double c : {0.0, 0.8, 10.0}) {
    for (double mu_s : {0.5, 0.75}) {
      oscillator_model m;
      m.gravity = 8.0;
      m.kinetic_friction = 0.5;
      m.static_friction = mu_s;
      m.damping = c;
      m.belt = markov_belt{{1.0, -1.0, 0.0}, {-2, 1, 1, 1, -2, 1, 1, 1, -2}};
      m.window = 8.0;
      const double as = m.static_band_half_width();
      auto edge = [&](double v, double s) { return s * as - c * v / m.stiffness; };
      const model_scenario cases[] = {
          {m, {edge(1.0, 1.0), 1.0, 0}, {}},
          {m, {edge(-1.0, -1.0), -1.0, 1}, {}},
          {m, {edge(1.0, -1.0), 1.0, 0}, {}},
          {m, {edge(1.0, 1.0) + 2.0, 1.0, 0}, {}},
          {m, {0.4, 0.0, 2}, {{3.0, 0}}},
          {m, {3.0 * as, 0.0, 2}, {}},
          {m, {0.0, 1.0, 0}, {{0.0, 1}, {3.0, 2}}},
          {m, {0.3, -1.0, 0}, {{0.0, 2}}},
          {m, {edge(1.0, 1.0), 1.0, 0}, {{0.0, 1}, {1.0, 0}}},
          {m, {0.2, 0.7, 1}, {{0.0, 2}, {0.1, 0}, {0.2, 1}}},
      };
      for (const model_scenario& s : cases) {
        const model_exact_run exact = run_model_exact(s);
        const model_oracle_result oracle = integrate_model_reference(
            s.model, s.ic, s.switches, {.steps_per_period = steps_per_period});
        const tolerance tol = tolerance_for(s, exact, steps_per_period);
        const auto d = compare(exact.episodes, oracle.episodes);
        ASSERT_TRUE(d.has_value()) << describe(s) << "\nexact:\n"
                                   << episodes_text(exact.episodes) << "oracle:\n"
                                   << episodes_text(oracle.episodes);
        EXPECT_LE(d->time, tol.time) << describe(s);
        EXPECT_LE(d->position, tol.position) << describe(s);
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 60);
}


// The parameters of a family scenario (for realization_observer).
model_parameters parameters_of(const oscillator_model& m) {
  model_parameters p;
  p.mass = m.mass;
  p.stiffness = m.stiffness;
  p.gravity = m.gravity;
  p.damping = m.damping;
  p.static_friction = m.static_friction;
  p.kinetic_friction = m.kinetic_friction;
  p.belt_levels = m.belt.levels;
  p.belt_generator = m.belt.generator;
  p.window = m.window;
  return p;
}

// The dissipation statistics (friction power W_f, damping power W_c, times
// t_a) of realization_observer on the exact engine, against the oracle's
// Simpson integrals of mu_k m g |v - x'| and c x'^2 along its RK4 path, on
// random family scenarios (another seed than the episode test; the same
// near-degenerate filter). Bound: each of the n_ev events may sit tol_t off,
// moving |v - x'| <= u = V_max + B (B the largest slip speed) worth of
// relative travel, and the errors do not add up (the oracle's events are
// located to rounding, its error is the RK4 path's), so tol_D = tol_t
// (mu_k m g + c u) u + a relative 1e-12 of the energy turnover. The oracle also closes its own
// energy balance: belt work = dissipation + change of energy.
TEST(ModelOracleAgreement, DissipationAgreesWithTheOracle) {
  std::mt19937_64 rng(0xd155'1fa7eULL);
  int accepted = 0, damped = 0;
  double worst = 0, worst_balance = 0;
  while (accepted < 300) {
    const model_scenario s = draw_model_scenario(rng);
    const scenario_run run = run_both(s, steps_per_period);
    const model_oracle_result& oracle = run.oracle;
    const tolerance& tol = run.tol;
    if (run.degenerate) continue;
    ++accepted;
    realization_observer obs(parameters_of(s.model));
    obs.reset(0, s.ic.position, s.ic.velocity, 1);
    given_level_switches sw(s.switches);
    simulate_model(s.model, s.ic, sw, obs);
    obs.finish();
    const double ta = s.model.window;
    const double friction = obs.record().friction_power * ta;
    const double damping = obs.record().damping_power * ta;
    const double u = tol.position / tol.time;  // V_max + B
    const double force = s.model.kinetic_friction * s.model.mass * s.model.gravity;
    const double turnover = oracle.friction_dissipation + oracle.damping_dissipation +
                            oracle.initial_energy + oracle.final_energy + std::abs(oracle.belt_work);
    const double bound = tol.time * (force + s.model.damping * u) * u + 1e-12 * turnover;
    EXPECT_NEAR(friction, oracle.friction_dissipation, bound) << describe(s);
    EXPECT_NEAR(damping, oracle.damping_dissipation, bound) << describe(s);
    if (s.model.damping == 0.0) {
      EXPECT_EQ(damping, 0.0);
    }
    const double balance = oracle.belt_work - oracle.friction_dissipation -
                           oracle.damping_dissipation - (oracle.final_energy - oracle.initial_energy);
    EXPECT_LE(std::abs(balance), bound) << describe(s);
    worst = std::max({worst, std::abs(friction - oracle.friction_dissipation) / bound,
                      std::abs(damping - oracle.damping_dissipation) / bound});
    worst_balance = std::max(worst_balance, std::abs(balance) / bound);
    damped += s.model.damping > 0.0;
  }
  std::printf("dissipation vs oracle: %d scenarios (%d damped), worst error %.3g of the bound, "
              "oracle's own balance %.3g of it\n",
              accepted, damped, worst, worst_balance);
  EXPECT_GT(damped, 150);
}

}  // namespace
}  // namespace stickslip::reference
