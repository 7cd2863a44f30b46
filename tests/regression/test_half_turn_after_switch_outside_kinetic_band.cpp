// Regression: an undamped stick between a_k and a_s (mu_s > mu_k), ended by
// a belt switch to the opposite level, returned at the mirror point.
//
// Found by a user with SciPy (DOP853, events on relative rest): k = 40,
// m = 1, g = 9.81, mu_s = 6, mu_k = 4, so a_k = 0.981, a_s = 1.4715. The mass
// sticks at x0 = 1.2 on the -1 belt and moves inward; at t = 0.1 it is at
// x = 1.1 and the belt switches to +1. The slip about c = a_k starts at
// (w y, x') = (w 0.119, -1): on the outer side of the centre, so the orbit
// turns through the far side and comes back to x' = +1 after half a period,
// pi / w, at x = 2 a_k - 1.1 = 0.862. The engines returned at the mirror
// point (the same x) after 0.2927 s, the answer only from the inner side.
// Oracles: the closed form above (rigid rotation of (w y, x') by pi), and
// the same command with c = 1e-9 (the damped engine, certified brackets).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "regression/recorded.hpp"
#include "stickslip/model/belt_chain.hpp"
#include "stickslip/model/model_engine.hpp"

namespace stickslip {
namespace {

using regression::recorded;

oscillator_model users_model(double damping) {
  oscillator_model m;
  m.stiffness = 40.0;
  m.static_friction = 6.0;
  m.kinetic_friction = 4.0;
  m.damping = damping;
  m.belt = markov_belt{{1.0, -1.0}, {-1.0, 1.0, 1.0, -1.0}};
  m.window = 1.5;
  return m;
}

recorded run(double damping) {
  const std::vector<level_switch> switches{{0.1, 0}};
  given_level_switches sw(switches);
  recorded r;
  (void)simulate_model(users_model(damping), model_initial_state{1.2, -1.0, 1}, sw, r);
  return r;
}

TEST(HalfTurnAfterSwitchOutsideKineticBand, ReturnsAfterHalfAPeriodAtTheFarPoint) {
  const oscillator_model m = users_model(0.0);
  const double ak = m.kinetic_offset(), w = m.natural_frequency();
  const double x_switch = 1.1;
  ASSERT_GT(x_switch, ak);
  ASSERT_LT(x_switch, m.static_band_half_width());
  const recorded r = run(0.0);
  ASSERT_GE(r.episodes.size(), 3u);
  EXPECT_EQ(r.episodes[0].kind, mode::stick);
  EXPECT_NEAR(r.episodes[0].end, 0.1, 1e-15);
  EXPECT_EQ(r.episodes[1].kind, mode::slip);
  const double t_return = 0.1 + std::numbers::pi / w;  // 0.596729...
  EXPECT_NEAR(r.episodes[1].end, t_return, 1e-12);
  EXPECT_NEAR(r.episodes[2].position_at_start, 2.0 * ak - x_switch, 1e-12);
  EXPECT_NEAR(r.episodes[1].end, 0.596729, 5e-7);
}

// The damped engine with a damping too small to matter (c = 1e-9) finds the
// same return by certified root isolation, not by the undamped closed forms.
TEST(HalfTurnAfterSwitchOutsideKineticBand, AgreesWithTheNearlyUndampedEngine) {
  const recorded exact = run(0.0), damped = run(1e-9);
  ASSERT_EQ(exact.episodes.size(), damped.episodes.size());
  for (std::size_t i = 0; i < exact.episodes.size(); ++i) {
    EXPECT_EQ(exact.episodes[i].kind, damped.episodes[i].kind) << i;
    EXPECT_NEAR(exact.episodes[i].end, damped.episodes[i].end, 1e-7) << i;
    EXPECT_NEAR(exact.episodes[i].position_at_start, damped.episodes[i].position_at_start, 1e-7) << i;
  }
}

}  // namespace
}  // namespace stickslip
