// Regression: a stick shorter than the resolution of t was dropped, leaving
// two slips next to each other.
//
// Found by fuzz_model_family: with mu_s one ulp above mu_k the slip that
// leaves the outward band edge (x' = v, x'' = sgn(v) (mu_k - mu_s) g) comes
// back to x' = v at 2 a_k - a_s, a few ulps (~5e-20 m) inside the edge. The
// stick from there would break after (a_s - x) / |v| ~ 5.4e-18 s, below half
// an ulp of t (6.9e-18 s at t ~ 0.07), so its break time rounds to t: the engines reported a stick onset and a stick break at one time
// and dropped the stick [t, t], so `simulate` printed three slips in a row
// (S_T = 1, S_L = 3). A touch of x' = v for no representable time is a
// grazing touch, not a stick (the engines' rule for the outward edge): the
// slip goes on, one slip episode, no onset and no break.
// Oracles: the invariants of a realization (episodes of positive length that
// alternate, one stick episode per onset or initial stick, one break per
// stick that reaches the edge); the same model with mu_s - mu_k large
// enough for those sticks to last a representable time (they are kept);
// and the contact rule itself on hand-made states.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <random>
#include <vector>

#include "regression/recorded.hpp"
#include "stickslip/event_physics.hpp"
#include "stickslip/model/belt_chain.hpp"
#include "stickslip/model/model_engine.hpp"

namespace stickslip {
namespace {

using regression::recorded;

// The fuzzer's model: levels 0.01 and 0, no switch in [0, 0.1], starting
// stuck on the inner band edge at x' = v.
oscillator_model fuzzer_model(double static_friction) {
  oscillator_model m;
  m.mass = 0.0228760208502688;
  m.stiffness = 1000.0;
  m.gravity = 9.81;
  m.kinetic_friction = 0.88670581033261642;
  m.static_friction = static_friction;
  m.belt = markov_belt{{0.01, 0.0}, {-1.0, 1.0, 1.0, -1.0}};
  m.window = 0.1;
  return m;
}

struct run_result {
  recorded r;
  event_counts counts;
};

run_result run(double static_friction) {
  const std::vector<level_switch> none;
  given_level_switches sw(none);
  run_result out;
  out.counts = simulate_model(fuzzer_model(static_friction),
                              model_initial_state{-0.00019898898893724184, 0.01, 0}, sw, out.r);
  return out;
}

// Episodes tile [0, t_a] with positive lengths and alternate; the stick
// episodes are the initial stick plus one per onset.
void expect_consistent(const run_result& x, double window) {
  const auto& e = x.r.episodes;
  ASSERT_FALSE(e.empty());
  EXPECT_EQ(e.front().start, 0.0);
  EXPECT_EQ(e.back().end, window);
  std::size_t sticks = 0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    EXPECT_GT(e[i].end, e[i].start) << "episode " << i;
    if (i + 1 < e.size()) {
      EXPECT_EQ(e[i].end, e[i + 1].start) << "episode " << i;
      EXPECT_NE(e[i].kind, e[i + 1].kind) << "episodes " << i << " and " << i + 1;
    }
    if (e[i].kind == mode::stick) ++sticks;
  }
  const std::size_t initial = e.front().kind == mode::stick ? 1 : 0;
  EXPECT_EQ(sticks, initial + static_cast<std::size_t>(x.counts.stick_onsets));
}

TEST(StickShorterThanTimeResolution, IsAGrazingTouchNotADroppedStick) {
  const double mu_k = 0.88670581033261642;
  const double mu_s = std::nextafter(mu_k, 1.0);
  const run_result x = run(mu_s);
  expect_consistent(x, 0.1);
  // the initial stick to the outward edge, then one slip to t_a: it comes
  // back to x' = v twice (t ~ 0.0698 and 0.0999), each time for no time
  ASSERT_EQ(x.r.episodes.size(), 2u);
  EXPECT_EQ(x.r.episodes[0].kind, mode::stick);
  EXPECT_NEAR(x.r.episodes[0].end, 0.039797797787448366, 1e-15);
  EXPECT_EQ(x.r.episodes[1].kind, mode::slip);
  EXPECT_TRUE(x.r.episodes[1].censored);
  EXPECT_EQ(x.counts.stick_onsets, 0);
  EXPECT_EQ(x.counts.stick_breaks, 1);
  for (const event& ev : x.r.events)
    EXPECT_NE(ev.kind, event_kind::stick_onset) << "at t = " << ev.time;
}

// Sticks that last a representable time are kept: with mu_s = mu_k (1 + 1e-9)
// each return sticks for 2 (a_s - a_k) / v ~ 4e-11 s (~3e6 ulps of t).
TEST(StickShorterThanTimeResolution, ShortButRepresentableSticksAreKept) {
  const double mu_k = 0.88670581033261642;
  const run_result x = run(mu_k * (1.0 + 1e-9));
  expect_consistent(x, 0.1);
  ASSERT_EQ(x.r.episodes.size(), 6u);  // stick, slip, stick, slip, stick, slip
  EXPECT_EQ(x.counts.stick_onsets, 2);
  const oscillator_model m = fuzzer_model(mu_k * (1.0 + 1e-9));
  const double as = m.static_friction * m.mass * m.gravity / m.stiffness;
  const double ak = m.kinetic_offset();
  for (std::size_t i : {2u, 4u}) {
    EXPECT_EQ(x.r.episodes[i].kind, mode::stick);
    EXPECT_NEAR(x.r.episodes[i].end - x.r.episodes[i].start, 2.0 * (as - ak) / 0.01, 1e-15);
  }
  // the slips between them take one period of the reversal arc: they
  // return where the one-ulp model touched x' = v for no time
  EXPECT_NEAR(x.r.episodes[2].start, 0.06984957151634662, 1e-9);
  EXPECT_NEAR(x.r.episodes[4].start, 0.09990134524524487, 1e-9);
}

// The shared contact rule (simulate, the lanes, simulate_model): a = 1, v = 1.
TEST(StickShorterThanTimeResolution, ContactRuleOnHandMadeStates) {
  using detail::physics::contact_outcome;
  using detail::physics::resolve_contact;
  const double below = std::nextafter(1.0, 0.0);  // 1 - 2^-53: a stick of 1.1e-16 s
  // at t = 1000 (ulp 1.1e-13) that stick has no length: a grazing touch,
  // leaving from the edge itself
  auto c = resolve_contact(1000.0, below, 1.0, 1.0, 1.0);
  EXPECT_EQ(c.outcome, contact_outcome::grazing);
  EXPECT_EQ(c.x, 1.0);
  EXPECT_EQ(c.sigma, 1.0);
  // at t = 0.07 (ulp 1.4e-17) it lasts 8 ulps: a stick where it touched
  c = resolve_contact(0.07, below, 1.0, 1.0, 1.0);
  EXPECT_EQ(c.outcome, contact_outcome::stick);
  EXPECT_EQ(c.x, below);
  // on the edge: grazing at any t; the inward edge sticks; v = -1 mirrors
  EXPECT_EQ(resolve_contact(0.0, 1.0, 1.0, 1.0, 1.0).outcome, contact_outcome::grazing);
  EXPECT_EQ(resolve_contact(1000.0, -below, -1.0, 1.0, 1.0).outcome, contact_outcome::stick);
  c = resolve_contact(1000.0, -below, -1.0, -1.0, 1.0);
  EXPECT_EQ(c.outcome, contact_outcome::grazing);
  EXPECT_EQ(c.x, -1.0);
  EXPECT_EQ(c.sigma, -1.0);
  // beyond the band's side: a reversal, x unchanged
  c = resolve_contact(1000.0, -1.5, 1.0, 1.0, 1.0);
  EXPECT_EQ(c.outcome, contact_outcome::reversal);
  EXPECT_EQ(c.x, -1.5);
}

// The same rule about a band centre b != 0 (damped models: b = -c v / k)
// and at a resting level (v = 0: no outward edge), a = 1, b = 0.25.
TEST(StickShorterThanTimeResolution, ContactRuleAboutABandCentreAndAtRest) {
  using detail::physics::contact_outcome;
  using detail::physics::resolve_contact;
  const double b = 0.25;
  // on the outward edge x = b + a: a grazing touch, leaving from the edge
  auto c = resolve_contact(3.0, 1.25, 1.0, 2.0, 1.0, b);
  EXPECT_EQ(c.outcome, contact_outcome::grazing);
  EXPECT_EQ(c.x, 1.25);
  EXPECT_EQ(c.sigma, 1.0);
  // the edge b - a is the outward one for v < 0: a grazing touch there
  c = resolve_contact(3.0, -0.75, -1.0, -2.0, 1.0, b);
  EXPECT_EQ(c.outcome, contact_outcome::grazing);
  EXPECT_EQ(c.x, -0.75);
  EXPECT_EQ(c.sigma, -1.0);
  // at rest the same state sticks (sgn 0 is taken as -1, but the band has no
  // outward edge at v = 0)
  EXPECT_EQ(resolve_contact(3.0, -0.75, -1.0, 0.0, 1.0, b).outcome, contact_outcome::stick);
  // inside the band about b (not about 0): a stick where it touched
  c = resolve_contact(3.0, -0.6, 1.0, 2.0, 1.0, b);
  EXPECT_EQ(c.outcome, contact_outcome::stick);
  EXPECT_EQ(c.x, -0.6);
  // x - b = -1.1 < -a from sigma = +1: a reversal, x unchanged
  c = resolve_contact(3.0, -0.85, 1.0, 2.0, 1.0, b);
  EXPECT_EQ(c.outcome, contact_outcome::reversal);
  EXPECT_EQ(c.x, -0.85);
  EXPECT_EQ(c.sigma, -1.0);
  // from sigma = -1 the band's side is x - b <= a: stuck at the clamped
  // inward edge b - a
  c = resolve_contact(3.0, -0.85, -1.0, 2.0, 1.0, b);
  EXPECT_EQ(c.outcome, contact_outcome::stick);
  EXPECT_EQ(c.x, -0.75);
  // the mode at t = 0 about b: the outward edge leaves it, except at rest
  using detail::physics::mode_at_start;
  EXPECT_TRUE(mode_at_start(1.25, 2.0, 2.0, 1.0, b).on_outward_edge);
  EXPECT_TRUE(mode_at_start(-0.75, -2.0, -2.0, 1.0, b).on_outward_edge);
  EXPECT_EQ(mode_at_start(-0.75, 0.0, 0.0, 1.0, b).kind, mode::stick);
  EXPECT_EQ(mode_at_start(-0.85, 2.0, 2.0, 1.0, b).sigma, -1.0);  // a reversal: sgn(x - b)
  EXPECT_TRUE(mode_at_start(-0.85, 2.0, 2.0, 1.0, b).after_reversal);
  // the departure from the edge: grazing with mu_s = mu_k, away otherwise
  EXPECT_TRUE(detail::physics::leave_edge(-2.0, true).grazing);
  EXPECT_TRUE(detail::physics::leave_edge(-2.0, false).after_reversal);
  EXPECT_EQ(detail::physics::leave_edge(-2.0, false).sigma, -1.0);
}

// decide_contact divides for the break time only where the gap to the edge
// is below |v| t 2^-49 (or t < 2^-900): elsewhere the break is strictly
// after t. Oracle: the undivided rule, t + gap / |v| <= t, on states whose
// gaps straddle the bound by a few ulps of t, over t from 2^-1000 to 2^40.
TEST(StickShorterThanTimeResolution, TheGatedBreakTimeCheckIsTheDirectOne) {
  using detail::physics::contact_outcome;
  using detail::physics::resolve_contact;
  std::mt19937_64 gen(20261128);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t by_rounding = 0, kept = 0, on_edge = 0;
  for (int i = 0; i < 200000; ++i) {
    const double a = std::ldexp(1.0 + unit(gen), static_cast<int>(unit(gen) * 20) - 10);
    // |v| mostly in 2^+-15; one state in ten in 2^+-250, where |v| t 2^-49
    // may overflow (the division runs) or underflow (the gap decides)
    const double speed =
        unit(gen) < 0.9 ? std::ldexp(1.0 + unit(gen), static_cast<int>(unit(gen) * 30) - 15)
                        : std::ldexp(1.0 + unit(gen), static_cast<int>(unit(gen) * 500) - 250);
    // mostly t within 2^+-60 of a / |v|, where a gap can both round into
    // the edge's ulp and not; else anywhere in [2^-1000, 2^40]
    const double t = unit(gen) < 0.8
                         ? std::ldexp(a / speed * (1.0 + unit(gen)), static_cast<int>(unit(gen) * 120) - 60)
                         : std::ldexp(1.0 + unit(gen), -1000 + static_cast<int>(unit(gen) * 1040));
    const double v = unit(gen) < 0.5 ? speed : -speed;
    const double s = v > 0 ? 1.0 : -1.0;
    const double b = unit(gen) < 0.5 ? 0.0 : s * a * unit(gen);
    // a gap of 2^-58 .. 2^-44 times |v| t (ulps of t around the bound)
    const double gap = speed * t * std::ldexp(1.0 + unit(gen), -58 + static_cast<int>(unit(gen) * 14));
    if (gap >= a) continue;  // beyond the band: a reversal (above)
    const double x = b + s * (a - gap);
    const auto c = resolve_contact(t, x, s, v, a, b);
    // the undivided rule on the state the rule sees (x clamped to the band)
    const double xc = std::clamp(x, b - a, b + a);
    const double g = a - s * (xc - b);
    const bool no_length = g <= 0.0 || t + g / speed <= t;
    ASSERT_EQ(c.outcome, no_length ? contact_outcome::grazing : contact_outcome::stick)
        << "t " << t << " a " << a << " v " << v << " b " << b << " x " << x;
    (g <= 0.0 ? on_edge : no_length ? by_rounding : kept) += 1;
  }
  // every branch, often: on the edge, a break that rounds to t, a stick
  std::printf("on the edge %zu, break rounds to t %zu, stick kept %zu\n", on_edge, by_rounding,
              kept);
  EXPECT_GT(on_edge, 10000u);
  EXPECT_GT(by_rounding, 10000u);
  EXPECT_GT(kept, 10000u);
}

}  // namespace
}  // namespace stickslip
