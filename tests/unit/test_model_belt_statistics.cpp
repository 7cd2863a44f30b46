// Statistical checks of the family with the Markov belt source, fixed seeds,
// tolerances from the standard error (never a magic number):
//   - the fraction of time at each belt level, measured on the engine's
//     pieces of motion, against the stationary law pi from the matrix-tree
//     (Kirchhoff) formula, starting from draw_stationary_level (so the
//     expectation is pi exactly at any window);
//   - the law of a stick's duration given its start x0 at level i with
//     level-dependent rates: D = min(W, d(x0)), W ~ Exp(q_i),
//     d = (a_s - sgn(v)(x0 - b)) / |v|, b = -c v / k: E[D] = (1 - e^{-q d}) / q,
//     E[D^2] = 2 (1 - e^{-q d} (1 + q d)) / q^2, P(D = d) = e^{-q d}.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "stickslip/model/belt_chain.hpp"
#include "stickslip/model/model_engine.hpp"

namespace stickslip {
namespace {

constexpr double z_bound = 4.0;  // |estimate - expectation| <= 4 standard errors

struct occupancy_observer : observer_base {
  const std::vector<double>* levels;
  std::vector<double> time;
  void on_segment(const segment& s) {
    for (std::size_t i = 0; i < levels->size(); ++i)
      if ((*levels)[i] == s.belt_velocity) time[i] += s.end - s.start;
  }
};

// pi_i proportional to the sum over spanning trees directed into i of the
// product of their rates (three levels: three trees per level).
std::vector<double> kirchhoff_three(const markov_belt& b) {
  auto q = [&](int i, int j) { return b.rate(static_cast<std::size_t>(i), static_cast<std::size_t>(j)); };
  std::vector<double> pi{q(1, 0) * q(2, 0) + q(1, 2) * q(2, 0) + q(2, 1) * q(1, 0),
                         q(0, 1) * q(2, 1) + q(0, 2) * q(2, 1) + q(2, 0) * q(0, 1),
                         q(0, 2) * q(1, 2) + q(0, 1) * q(1, 2) + q(1, 0) * q(0, 2)};
  const double sum = pi[0] + pi[1] + pi[2];
  for (double& p : pi) p /= sum;
  return pi;
}

void check_occupancy(const oscillator_model& m, const std::vector<double>& pi, std::uint64_t seed) {
  const belt_chain chain(m.belt);
  const std::size_t n = m.belt.level_count();
  const int realizations = 20000;
  std::vector<double> sum(n, 0.0), sum2(n, 0.0);
  for (int r = 0; r < realizations; ++r) {
    const auto ru = static_cast<std::uint64_t>(r);
    const std::size_t start = draw_stationary_level(chain, seed, 0, ru);
    markov_level_switches sw(chain, start, seed, 0, ru);
    occupancy_observer obs;
    obs.levels = &m.belt.levels;
    obs.time.assign(n, 0.0);
    simulate_model(m, {0.1, 0.0, start}, sw, obs);
    for (std::size_t i = 0; i < n; ++i) {
      const double f = obs.time[i] / m.window;
      sum[i] += f;
      sum2[i] += f * f;
    }
  }
  double total = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double mean = sum[i] / realizations;
    const double se = std::sqrt((sum2[i] / realizations - mean * mean) / (realizations - 1));
    std::printf("level %zu: occupancy %.5f +- %.5f, stationary %.5f\n", i, mean, se, pi[i]);
    EXPECT_LE(std::abs(mean - pi[i]), z_bound * se) << "level " << i;
    total += mean;
  }
  EXPECT_NEAR(total, 1.0, 1e-12);  // the pieces tile the window
}

TEST(ModelBeltStatistics, StationaryLawMatchesTheMatrixTreeFormula) {
  const markov_belt b{{-1.0, 0.0, 2.0}, {-3.0, 1.0, 2.0, 0.5, -0.7, 0.2, 1.5, 0.0, -1.5}};
  const std::vector<double> expected = kirchhoff_three(b), got = stationary_law(b);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(got[i], expected[i], 1e-14);
  const std::vector<double> two = stationary_law(two_level_belt(1.0, -1.0, 3.0, 1.0));
  EXPECT_NEAR(two[0], 0.25, 1e-15);  // pi_1 = q_21 / (q_12 + q_21)
}

TEST(ModelBeltStatistics, OccupancyOfThreeLevelsIsTheStationaryLaw) {
  oscillator_model m;
  m.damping = 0.4;
  m.static_friction = 6.0;
  m.kinetic_friction = 4.0;
  m.belt = markov_belt{{-1.0, 0.0, 2.0}, {-3.0, 1.0, 2.0, 0.5, -0.7, 0.2, 1.5, 0.0, -1.5}};
  m.window = 10.0;
  check_occupancy(m, kirchhoff_three(m.belt), 2024);
}

TEST(ModelBeltStatistics, OccupancyOfTwoUnequalLevelsIsTheStationaryLaw) {
  oscillator_model m;
  m.belt = two_level_belt(1.0, -0.3, 2.0, 0.5);  // pi = (0.5, 2) / 2.5
  m.window = 8.0;
  check_occupancy(m, {0.2, 0.8}, 77);
}

TEST(ModelBeltStatistics, StickDurationGivenItsStartWithLevelDependentRates) {
  oscillator_model m;
  m.damping = 0.3;
  m.static_friction = 6.0;
  m.kinetic_friction = 4.0;
  m.belt = two_level_belt(0.8, -0.4, 1.7, 0.35);
  const belt_chain chain(m.belt);
  const double as = m.static_band_half_width();
  for (std::size_t level : {0u, 1u}) {
    const double v = m.belt.levels[level], q = m.belt.leaving_rate(level);
    const double b = -m.damping * v / m.stiffness, s = v > 0 ? 1.0 : -1.0;
    // Start inside the band, 0.8 / q_i from the edge ahead (an atom e^{-0.8}).
    const double x0 = b + s * (as - 0.8 / q * std::abs(v));
    const double d = (as - s * (x0 - b)) / std::abs(v);
    m.window = d + 1.0;  // longer than the stick: no censoring
    const double mean = (1.0 - std::exp(-q * d)) / q;
    const double second = 2.0 * (1.0 - std::exp(-q * d) * (1.0 + q * d)) / (q * q);
    const double atom = std::exp(-q * d);
    const int realizations = 20000;
    double sum = 0;
    int full = 0;
    for (int r = 0; r < realizations; ++r) {
      markov_level_switches sw(chain, level, 99, level, static_cast<std::uint64_t>(r));
      struct first_stick : observer_base {
        double duration = -1;
        void on_episode(const episode& e) {
          if (duration < 0 && e.kind == mode::stick) duration = e.duration();
        }
      } obs;
      simulate_model(m, {x0, v, level}, sw, obs);
      ASSERT_GE(obs.duration, 0.0);
      sum += obs.duration;
      full += std::abs(obs.duration - d) <= 1e-12 * d;
    }
    const double se = std::sqrt((second - mean * mean) / realizations);
    const double got = sum / realizations;
    std::printf("level %zu: E[D] %.5f +- %.5f (law %.5f); P(D = d) %.4f (law %.4f)\n", level, got,
                se, mean, static_cast<double>(full) / realizations, atom);
    EXPECT_LE(std::abs(got - mean), z_bound * se) << "level " << level;
    const double atom_se = std::sqrt(atom * (1.0 - atom) / realizations);
    EXPECT_LE(std::abs(static_cast<double>(full) / realizations - atom), z_bound * atom_se);
  }
}

}  // namespace
}  // namespace stickslip
