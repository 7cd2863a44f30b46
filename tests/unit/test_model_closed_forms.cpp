// Closed-form checks of the model family engine (simulate_model), each
// against a formula derived in docs/model.md, not against the engine's code:
//   - the no-switch limit cycle with mu_s > mu_k (stick onset position,
//     stick and slip durations, amplitude);
//   - damped motion coming to rest at a resting (v = 0) belt level: the
//     turning points follow the logarithmic decrement q = exp(-gamma pi / omega_d)
//     about alternating centres +-a_k until one falls in the band;
//   - over- and critically damped motion at v = 0 never reaches x' = 0: one
//     slip, no event, x -> a_k from outside (the documented degenerate case).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "stickslip/model/belt_chain.hpp"
#include "stickslip/model/model_engine.hpp"

namespace stickslip {
namespace {

struct recorded {
  std::vector<episode> episodes;
  std::vector<event> events;
  std::vector<segment> segments;
};
struct recorder {
  recorded* out;
  void on_event(const event& e) { out->events.push_back(e); }
  void on_segment(const segment& s) { out->segments.push_back(s); }
  void on_episode(const episode& e) { out->episodes.push_back(e); }
};

recorded run(const oscillator_model& m, const model_initial_state& ic,
             const std::vector<level_switch>& switches = {}) {
  recorded r;
  recorder obs{&r};
  given_level_switches sw(switches);
  simulate_model(m, ic, sw, obs);
  return r;
}

// Limit cycle (docs/model.md): a stick at level V runs from the onset
// x_on = 2 a_k - a_s to the edge a_s, lasting 2 (a_s - a_k) / V; the slip
// leaves with x' = V at y = a_s - a_k from the centre a_k, so
// B = sqrt((omega (a_s - a_k))^2 + V^2), and runs the arc 2 pi - 2 alpha,
// tan alpha = omega (a_s - a_k) / V, back to x' = V at the mirror point
// 2 a_k - a_s. Amplitude: x in [a_k - B/omega, a_k + B/omega].
TEST(ModelClosedForms, NoSwitchLimitCycleWithStaticAboveKineticFriction) {
  for (double V : {1.0, -0.6, 2.5}) {
    oscillator_model m;
    m.static_friction = 5.0;
    m.kinetic_friction = 3.5;
    m.belt = two_level_belt(V, -2.0 * V, 1.0, 1.0);
    m.window = 60.0;
    const double as = m.static_band_half_width(), ak = m.kinetic_offset();
    const double w = m.natural_frequency(), s = V > 0 ? 1.0 : -1.0;
    const double gap = as - ak;
    const double onset = s * (2.0 * ak - as);
    const double stick = 2.0 * gap / std::abs(V);
    const double B = std::hypot(w * gap, V);
    const double slip = (2.0 * std::numbers::pi - 2.0 * std::atan(w * gap / std::abs(V))) / w;
    const recorded r = run(m, {0.3, 0.0, 0});
    int cycles = 0;
    for (std::size_t i = 1; i + 1 < r.episodes.size(); ++i) {
      const episode& e = r.episodes[i];
      if (e.kind != mode::stick || i < 2) continue;  // from the second stick on: the cycle
      EXPECT_NEAR(e.position_at_start, onset, 1e-12 * as) << "V " << V << " stick " << i;
      EXPECT_NEAR(e.duration(), stick, 1e-12 * m.window) << "V " << V;
      EXPECT_NEAR(r.episodes[i - 1].duration(), slip, 1e-12 * m.window) << "V " << V;
      ++cycles;
    }
    EXPECT_GE(cycles, static_cast<int>(m.window / (stick + slip)) - 2);
    // Amplitude: sample the last full slip densely; the sampling error near a
    // turning point is at most B omega dt^2 / 8.
    const episode& last_slip = r.episodes[r.episodes.size() - 2];
    ASSERT_EQ(last_slip.kind, mode::slip);
    double lo = 1e300, hi = -1e300;
    const int samples = 20000;
    for (const segment& g : r.segments) {
      if (g.kind != mode::slip || g.start < last_slip.start || g.end > last_slip.end) continue;
      for (int j = 0; j <= samples; ++j) {
        const double x = evaluate(g, g.start + (g.end - g.start) * j / samples).position;
        lo = std::min(lo, x);
        hi = std::max(hi, x);
      }
    }
    const double dt = slip / samples, sampling = B * w * dt * dt / 8 + 1e-12 * as;
    EXPECT_NEAR(hi, s * ak + B / w, sampling) << "V " << V;
    EXPECT_NEAR(lo, s * ak - B / w, sampling) << "V " << V;
  }
}

// At a resting level the slips are half-swings between turning points
// (x' = 0). From a turning point x_n outside the band the spring pulls
// towards the centre c_n = sgn(x_n) a_k, and half a damped period pi / omega_d
// later the mass turns again at x_{n+1} = c_n - q (x_n - c_n),
// q = exp(-gamma pi / omega_d) (logarithmic decrement). The first turning
// point with |x_n| <= a_s starts a stick that lasts until the next switch.
TEST(ModelClosedForms, DampedMotionComesToRestAtARestingLevel) {
  for (double zeta : {0.02, 0.1, 0.3}) {
    for (double ratio : {1.0, 1.4}) {
      oscillator_model m;
      m.kinetic_friction = 0.5;
      m.static_friction = 0.5 * ratio;
      m.damping = 2.0 * zeta * std::sqrt(m.stiffness * m.mass);
      m.belt = two_level_belt(0.0, 1.0, 0.2, 0.2);
      m.window = 40.0;
      const double as = m.static_band_half_width(), ak = m.kinetic_offset();
      const double w0 = m.natural_frequency(), gamma = m.decay_rate();
      const double wd = std::sqrt(w0 * w0 - gamma * gamma);
      const double q = std::exp(-gamma * std::numbers::pi / wd);
      const double x0 = 23.0 * as;
      const recorded r = run(m, {x0, 0.0, 0});
      double x = x0;
      std::size_t n = 0;
      while (std::abs(x) > as) {
        const double c = x > 0 ? ak : -ak;
        x = c - q * (x - c);
        ++n;
        ASSERT_LE(n, r.events.size()) << "zeta " << zeta << ": too few events";
        const event& e = r.events[n - 1];
        const double when = n * std::numbers::pi / wd;
        EXPECT_NEAR(e.time, when, 1e-12 * m.window) << "zeta " << zeta << " turn " << n;
        EXPECT_NEAR(e.position, x, 1e-11 * x0) << "zeta " << zeta << " turn " << n;
        EXPECT_EQ(e.velocity, 0.0);
        EXPECT_EQ(e.kind, std::abs(x) <= as ? event_kind::stick_onset : event_kind::slip_reversal)
            << "zeta " << zeta << " turn " << n;
      }
      EXPECT_GE(n, 2u);
      ASSERT_EQ(r.events.size(), n) << "zeta " << zeta;  // at rest until the window ends
      ASSERT_EQ(r.episodes.size(), 2u);
      EXPECT_EQ(r.episodes[1].kind, mode::stick);
      EXPECT_TRUE(r.episodes[1].censored);
      EXPECT_EQ(r.episodes[1].end, m.window);
    }
  }
}

// Over- and critically damped at v = 0 from rest outside the band: y = x - a_k
// decays without changing sign and x' < 0 throughout, so x' never returns to 0:
// no event, one slip. The position at t_a against the textbook forms
// y = y0 (r1 e^{r2 t} - r2 e^{r1 t}) / (r1 - r2) and y0 (1 + gamma t) e^{-gamma t}.
TEST(ModelClosedForms, OverAndCriticallyDampedMotionApproachesTheEquilibriumWithoutSticking) {
  for (double zeta : {1.0, 1.5, 4.0}) {
    oscillator_model m;
    m.mass = 1.0;
    m.kinetic_friction = 0.5;
    m.static_friction = 0.6;
    m.damping = zeta == 1.0 ? 2.0 * m.natural_frequency() : 2.0 * zeta * std::sqrt(m.stiffness);
    m.belt = two_level_belt(0.0, 1.0, 0.2, 0.2);
    m.window = 7.0;
    const double ak = m.kinetic_offset(), as = m.static_band_half_width();
    const double x0 = 4.0 * as, y0 = x0 - ak, gamma = m.decay_rate(), w0 = m.natural_frequency();
    const recorded r = run(m, {x0, 0.0, 0});
    EXPECT_TRUE(r.events.empty()) << "zeta " << zeta;
    ASSERT_EQ(r.episodes.size(), 1u);
    EXPECT_EQ(r.episodes[0].kind, mode::slip);
    const double t = m.window;
    double y;
    if (zeta == 1.0) {
      y = y0 * (1.0 + gamma * t) * std::exp(-gamma * t);
    } else {
      const double beta = std::sqrt(gamma * gamma - w0 * w0), r1 = -gamma + beta, r2 = -gamma - beta;
      y = y0 * (r1 * std::exp(r2 * t) - r2 * std::exp(r1 * t)) / (r1 - r2);
    }
    const phase_point end = evaluate(r.segments.back(), t);
    EXPECT_NEAR(end.position, ak + y, 1e-12 * x0) << "zeta " << zeta;
    EXPECT_GT(end.position, ak);
    EXPECT_LT(end.velocity, 0.0);
  }
}

}  // namespace
}  // namespace stickslip

namespace stickslip {
namespace {

// A strongly over-damped slip that lasts long: e^{r2 t} underflows while
// e^{2 beta t} overflows (2 beta t > 709); the closed form must still give
// e^{-gamma t} sinh(beta t) / beta = (e^{r1 t} - e^{r2 t}) / (2 beta), not
// 0 * inf. Here zeta = 4, omega_0 = 2, t = 60 s: 2 beta t ~ 930.
TEST(ModelClosedForms, LongOverDampedSlipStaysFinite) {
  oscillator_model m;
  m.mass = 1.0;
  m.stiffness = 4.0;
  m.damping = 2.0 * 4.0 * 2.0;
  m.kinetic_friction = 0.5;
  m.static_friction = 0.6;
  m.belt = two_level_belt(0.0, 1.0, 1e-9, 1e-9);
  m.window = 60.0;
  const double ak = m.kinetic_offset(), as = m.static_band_half_width();
  const double x0 = 4.0 * as, y0 = x0 - ak, gamma = m.decay_rate(), w0 = m.natural_frequency();
  struct last_segment : observer_base {
    segment last{};
    void on_segment(const segment& s) { last = s; }
  } obs;
  given_level_switches none({});
  simulate_model(m, {x0, 0.0, 0}, none, obs);
  const double beta = std::sqrt(gamma * gamma - w0 * w0), r1 = -w0 * w0 / (gamma + beta);
  const double r2 = -gamma - beta;
  for (double t : {10.0, 45.0, 60.0}) {
    const phase_point p = evaluate(obs.last, t);
    const double y = y0 * (r1 * std::exp(r2 * t) - r2 * std::exp(r1 * t)) / (r1 - r2);
    ASSERT_TRUE(std::isfinite(p.position)) << "t " << t;
    EXPECT_NEAR(p.position, ak + y, 1e-12 * x0) << "t " << t;
  }
}

}  // namespace
}  // namespace stickslip
