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

#include <cmath>
#include <cstddef>
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

}  // namespace
}  // namespace stickslip
