// Exact cases of the integrator: hand-derived event sequences (derived here
// from the equation of motion, not from integrator.hpp), the no-switch case
// (one stick of (a - x_start)/V, then a pure grazing slip), and the
// conditional law of a stick's duration D given its start x0:
//   D = min(W, d(x0)),  W ~ Exp(lambda),  d(x0) = (a - sgn(v) x0) / V
// (memorylessness of the Poisson switches at the stick onset, a stopping time).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "stickslip/belt_switches.hpp"
#include "stickslip/initial_conditions.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/observer.hpp"

namespace stickslip {
namespace {

using std::numbers::pi;

struct recorded {
  std::vector<episode> episodes;
  std::vector<event> events;
  std::vector<segment> segments;
  event_counts counts;
  void on_event(const event& e) { events.push_back(e); }
  void on_segment(const segment& s) { segments.push_back(s); }
  void on_episode(const episode& e) { episodes.push_back(e); }
};

template <class Switches>
recorded run(const model_parameters& p, const initial_conditions& ic, Switches& sw) {
  recorded r;
  r.counts = simulate(p, ic, sw, r);
  return r;
}
recorded run(const model_parameters& p, const initial_conditions& ic,
             const std::vector<double>& switch_times = {}) {
  given_switches sw(switch_times);
  return run(p, ic, sw);
}

// m = 1, k = 4 (w = 2), g = 9.81, mu = 0.5: a = 1.22625, a w = 2.4525 > V = 1.
model_parameters paper_like(double window = 50.0) {
  model_parameters p;
  p.friction_coefficient = 0.5;
  p.window = window;
  return p;
}

constexpr double rel = 1e-12;  // rounding of a handful of libm calls

// x0 = 0, x'0 = 0, belt +V: slip about c = +a, x = a (1 - cos wt), x' = a w sin wt.
// x' = V at sin(w t1) = V/(a w): x1 = a (1 - sqrt(1 - (V/aw)^2)) is inside the
// band, so a stick of (a - x1)/V follows; it breaks at +a and the mass then
// moves on x = a + (V/w) sin(w (t - t_b)), touching x' = V once per period.
TEST(IntegratorExact, NoSwitchOneStickOfBandLengthThenPureGrazing) {
  const model_parameters p = paper_like();
  const double a = p.band_half_width(), w = p.natural_frequency(), V = p.belt_speed;
  const double q = V / (a * w);
  const double t1 = std::asin(q) / w;
  const double x1 = a * (1.0 - std::sqrt(1.0 - q * q));
  const double tb = t1 + (a - x1) / V;
  const recorded r = run(p, {0.0, 0.0, +1});

  ASSERT_EQ(r.episodes.size(), 3u);
  EXPECT_EQ(r.episodes[0].kind, mode::slip);
  EXPECT_EQ(r.episodes[1].kind, mode::stick);
  EXPECT_EQ(r.episodes[2].kind, mode::slip);
  EXPECT_NEAR(r.episodes[1].start, t1, rel * p.window);
  EXPECT_NEAR(r.episodes[1].position_at_start, x1, rel * a);
  EXPECT_NEAR(r.episodes[1].duration(), (a - r.episodes[1].position_at_start) / V, rel * p.window);
  EXPECT_NEAR(r.episodes[1].end, tb, rel * p.window);
  EXPECT_EQ(r.episodes[2].end, p.window);
  EXPECT_TRUE(r.episodes[2].censored);
  EXPECT_EQ(r.counts.stick_onsets, 1u);
  EXPECT_EQ(r.counts.stick_breaks, 1u);
  EXPECT_EQ(r.counts.slip_reversals, 0u);
  EXPECT_EQ(r.counts.belt_switches, 0u);

  // The grazing slip, sampled over its ~14 periods against the closed form
  // above: x' <= V (it touches x' = V at x = a, never crosses).
  const segment& last = r.segments.back();
  ASSERT_EQ(last.kind, mode::slip);
  EXPECT_EQ(last.end, p.window);
  int touches = 0;
  for (double t = last.start; t <= p.window; t += 1e-3) {
    const phase_point s = evaluate(last, t);
    EXPECT_NEAR(s.position, a + V / w * std::sin(w * (t - tb)), 1e-11);
    EXPECT_NEAR(s.velocity, V * std::cos(w * (t - tb)), 1e-11);
    EXPECT_LE(s.velocity, V * (1 + 1e-15));
    touches += std::abs(s.velocity - V) < 1e-5;
  }
  EXPECT_GE(touches, 14);  // it really comes back to x' = V every period
}

// The same with the belt running at -V: the mirror image x -> -x.
TEST(IntegratorExact, NoSwitchMirrorImageForNegativeBelt) {
  const model_parameters p = paper_like();
  const recorded plus = run(p, {0.0, 0.0, +1});
  const recorded minus = run(p, {0.0, 0.0, -1});
  ASSERT_EQ(plus.episodes.size(), minus.episodes.size());
  for (std::size_t i = 0; i < plus.episodes.size(); ++i) {
    EXPECT_EQ(plus.episodes[i].kind, minus.episodes[i].kind);
    EXPECT_NEAR(plus.episodes[i].start, minus.episodes[i].start, 1e-13);
    EXPECT_NEAR(plus.episodes[i].position_at_start, -minus.episodes[i].position_at_start, 1e-13);
  }
}

// No switch, many random initial states and parameters: at most one stick;
// if there is one it lasts exactly (a - sgn(v) x_start)/V (or is cut by t_a),
// and the slip after it never sticks again.
TEST(IntegratorExact, NoSwitchAtMostOneStickOfExactLength) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<> u(0.0, 1.0);
  int with_stick = 0;
  for (int i = 0; i < 2000; ++i) {
    model_parameters p;
    p.friction_coefficient = std::exp(std::log(0.01) + u(rng) * std::log(2000.0));
    p.stiffness = std::exp(std::log(0.5) + u(rng) * std::log(200.0));
    p.belt_speed = 0.5 + 1.5 * u(rng);
    p.window = 5.0 + 45.0 * u(rng);
    const double a = p.band_half_width(), w = p.natural_frequency(), V = p.belt_speed;
    const initial_conditions ic{(4 * u(rng) - 2) * (a + V / w), (4 * u(rng) - 2) * V,
                                u(rng) < 0.5 ? 1 : -1};
    const recorded r = run(p, ic);
    std::vector<episode> sticks;
    for (const episode& e : r.episodes)
      if (e.kind == mode::stick) sticks.push_back(e);
    ASSERT_LE(sticks.size(), 1u) << "i=" << i;
    if (sticks.empty()) continue;
    ++with_stick;
    const episode& s = sticks[0];
    const double sv = s.belt_velocity > 0 ? 1.0 : -1.0;
    const double d = (a - sv * s.position_at_start) / V;
    if (s.censored) {
      EXPECT_LE(s.duration(), d * (1 + rel) + rel * p.window);
    } else {
      EXPECT_NEAR(s.duration(), d, rel * (p.window + d)) << "i=" << i;
      EXPECT_EQ(r.episodes.back().kind, mode::slip);
      EXPECT_EQ(r.counts.stick_breaks, 1u);
    }
  }
  EXPECT_GT(with_stick, 1000);
}

// x0 = 0, x'0 = 0 with a w < V: the slip orbit about +a has speed amplitude
// a w < V, so x' never reaches the belt: one slip over the whole window.
TEST(IntegratorExact, OrbitBelowBeltSpeedNeverSticks) {
  model_parameters p = paper_like(30.0);
  p.friction_coefficient = 0.1;  // a w = 0.4905 < 1
  const recorded r = run(p, {0.0, 0.0, +1});
  ASSERT_EQ(r.episodes.size(), 1u);
  EXPECT_EQ(r.episodes[0].kind, mode::slip);
  EXPECT_EQ(r.counts.total(), 0u);
}

// Starting on the belt velocity inside the band: a stick from t = 0 that
// lasts (a - sgn(v) x0)/V.
TEST(IntegratorExact, StartOnBeltInsideBandSticksAtOnce) {
  const model_parameters p = paper_like(10.0);
  const double a = p.band_half_width();
  for (int belt : {+1, -1}) {
    const double x0 = 0.3 * a;
    const recorded r = run(p, {x0, belt * p.belt_speed, belt});
    ASSERT_GE(r.episodes.size(), 2u);
    EXPECT_EQ(r.episodes[0].kind, mode::stick);
    EXPECT_EQ(r.episodes[0].start, 0.0);
    EXPECT_NEAR(r.episodes[0].end, (a - belt * x0) / p.belt_speed, rel);
  }
}

// x0 = -4.5 a, x'0 = V (belt +V): outside the band, so the slip starts with
// sigma = sgn(x0) = -1 about c = -a: w y = B sin(theta), x' = B cos(theta),
// theta0 = -beta, beta = atan(3.5 a w / V). x' = V again at theta = +beta,
// at x = -a + 3.5 a = 2.5 a: outside, so the slip reverses (sigma = +1,
// c = +a, y = 1.5 a, theta = gamma = atan(1.5 a w / V)) and runs its whole
// region to theta = 2 pi - gamma, x = a - 1.5 a = -0.5 a: inside, a stick of
// 1.5 a / V, then a break at +a and grazing.
TEST(IntegratorExact, ReversalThenStickHandDerived) {
  const model_parameters p = paper_like(20.0);
  const double a = p.band_half_width(), w = p.natural_frequency(), V = p.belt_speed;
  const double beta = std::atan(3.5 * a * w / V), gamma = std::atan(1.5 * a * w / V);
  const double t_reversal = 2.0 * beta / w;
  const double t_stick = t_reversal + (2.0 * pi - 2.0 * gamma) / w;
  const recorded r = run(p, {-4.5 * a, V, +1});

  ASSERT_EQ(r.episodes.size(), 3u);
  EXPECT_EQ(r.episodes[1].kind, mode::stick);
  EXPECT_NEAR(r.episodes[1].start, t_stick, rel * p.window);
  EXPECT_NEAR(r.episodes[1].position_at_start, -0.5 * a, rel * a);
  EXPECT_NEAR(r.episodes[1].end, t_stick + 1.5 * a / V, rel * p.window);
  ASSERT_EQ(r.counts.slip_reversals, 1u);
  const auto rev = std::find_if(r.events.begin(), r.events.end(), [](const event& e) {
    return e.kind == event_kind::slip_reversal;
  });
  ASSERT_NE(rev, r.events.end());
  EXPECT_NEAR(rev->time, t_reversal, rel * p.window);
  EXPECT_NEAR(rev->position, 2.5 * a, rel * a);
  EXPECT_EQ(r.counts.stick_onsets, 1u);
  EXPECT_EQ(r.counts.stick_breaks, 1u);
}

// A belt switch at t_s ends a stick at x_s (belt +V -> -V). The mass keeps
// x' = +V; the slip (sigma = -1, c = -a, y = x_s + a) has theta0 = atan2(w y, V)
// and meets x' = -V first at theta = pi - theta0, where sin(theta) and hence
// x are the same: a new stick starts at x_s after (pi - 2 theta0)/w and lasts
// (a + x_s)/V (belt -V, outward edge -a).
TEST(IntegratorExact, BeltSwitchDuringStickReturnsToTheSamePosition) {
  const model_parameters p = paper_like(20.0);
  const double a = p.band_half_width(), w = p.natural_frequency(), V = p.belt_speed;
  const double x0 = -0.8 * a, t_switch = 0.7;  // stick from t = 0, edge at 1.8 a / V > 0.7
  const double xs = x0 + V * t_switch;
  const double theta0 = std::atan2(w * (xs + a), V);
  const double t_return = t_switch + (pi - 2.0 * theta0) / w;
  const recorded r = run(p, {x0, V, +1}, std::vector<double>{t_switch});

  ASSERT_GE(r.episodes.size(), 3u);
  EXPECT_EQ(r.episodes[0].kind, mode::stick);
  EXPECT_EQ(r.episodes[0].end, t_switch);
  EXPECT_EQ(r.episodes[2].kind, mode::stick);
  EXPECT_NEAR(r.episodes[2].start, t_return, rel * p.window);
  EXPECT_NEAR(r.episodes[2].position_at_start, xs, rel * a);
  EXPECT_LT(r.episodes[2].belt_velocity, 0.0);
  EXPECT_NEAR(r.episodes[2].end, t_return + (a + xs) / V, rel * p.window);
}

// ---- conditional law of the stick duration -------------------------------

struct stick_sample {
  double duration, full;  // D and d(x0)
};

// All sticks from `realizations` Poisson realizations whose start T has
// T + d(x0) < t_a, so that t_a cannot cut them: selecting on (T, x0), which
// are known at the onset, leaves the law of D given x0 unchanged.
std::vector<stick_sample> uncensorable_sticks(const model_parameters& p, int realizations,
                                              std::uint64_t seed) {
  struct collector : observer_base {
    const model_parameters* p;
    std::vector<stick_sample>* out;
    void on_episode(const episode& e) {
      if (e.kind != mode::stick || !(e.duration() > 0)) return;
      const double sv = e.belt_velocity > 0 ? 1.0 : -1.0;
      const double d = (p->band_half_width() - sv * e.position_at_start) / p->belt_speed;
      if (e.start + d < p->window) out->push_back({e.duration(), d});
    }
  };
  std::vector<stick_sample> out;
  collector c;
  c.p = &p;
  c.out = &out;
  for (int i = 0; i < realizations; ++i) {
    const auto ic = draw_initial_conditions({}, seed, 0, static_cast<std::uint64_t>(i));
    poisson_switches sw(p.switch_rate, seed, 0, static_cast<std::uint64_t>(i));
    simulate(p, ic, sw, c);
  }
  return out;
}

class StickDurationLaw : public ::testing::TestWithParam<double> {};

// For each stick: E[D | x0] = (1 - e^{-lambda d}) / lambda,
// E[D^2 | x0] = 2 (1 - e^{-lambda d} (1 + lambda d)) / lambda^2,
// P(D = d | x0) = e^{-lambda d}. The sums over sticks of (D - E[D|x0]) and of
// (1{D = d} - e^{-lambda d}) divided by their standard errors are N(0, 1);
// a randomized probability integral transform of D is Uniform(0, 1) (KS).
TEST_P(StickDurationLaw, MatchesMinOfExponentialAndTimeToEdge) {
  model_parameters p = paper_like(50.0);
  p.switch_rate = GetParam();
  const std::vector<stick_sample> sticks = uncensorable_sticks(p, 1000, 77);
  ASSERT_GT(sticks.size(), 5000u);
  const double lambda = p.switch_rate;
  double mean_dev = 0, mean_var = 0, atom_dev = 0, atom_var = 0;
  std::vector<double> pit;
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<> u(0.0, 1.0);
  for (const stick_sample& s : sticks) {
    const double d = s.full, e = std::exp(-lambda * d);
    ASSERT_LE(s.duration, d * (1 + 1e-12) + 1e-12);  // D <= d(x0) always
    const double m1 = (1 - e) / lambda;
    const double m2 = 2.0 * (1 - e * (1 + lambda * d)) / (lambda * lambda);
    mean_dev += s.duration - m1;
    mean_var += m2 - m1 * m1;
    const bool at_edge = s.duration >= d * (1 - 1e-9);
    atom_dev += (at_edge ? 1.0 : 0.0) - e;
    atom_var += e * (1 - e);
    // CDF 1 - e^{-lambda D} below d, atom of mass e at d.
    pit.push_back(at_edge ? (1 - e) + u(rng) * e : 1 - std::exp(-lambda * s.duration));
  }
  const double z_mean = mean_dev / std::sqrt(mean_var);
  const double z_atom = atom_dev / std::sqrt(atom_var);
  std::sort(pit.begin(), pit.end());
  double ks = 0;
  const double n = static_cast<double>(pit.size());
  for (std::size_t i = 0; i < pit.size(); ++i)
    ks = std::max({ks, (i + 1) / n - pit[i], pit[i] - i / n});
  std::printf("lambda=%g: %zu sticks, z(mean)=%.2f z(atom)=%.2f sqrt(n) KS=%.3f\n", lambda,
              sticks.size(), z_mean, z_atom, std::sqrt(n) * ks);
  // 4.5 standard errors; sqrt(n) KS < 1.95 is the 0.1% level of Kolmogorov's law.
  EXPECT_LT(std::abs(z_mean), 4.5);
  EXPECT_LT(std::abs(z_atom), 4.5);
  EXPECT_LT(std::sqrt(n) * ks, 1.95);
}

INSTANTIATE_TEST_SUITE_P(SwitchRates, StickDurationLaw, ::testing::Values(0.3, 1.0, 4.0));

}  // namespace
}  // namespace stickslip
