// Regression: zero-length episodes at t = 0.
//
// Found by the reference oracle (tests/reference): a state that starts on the
// outward band edge at belt velocity (x0 = sgn(v) a, x'0 = v) is the grazing
// contact, a "stick" of zero time; the integrator reported it as a stick
// episode [0, 0] (plus a stick_break event), where the oracle reports one slip.
// The same happened when a belt switch at t = 0 ended the initial stick
// (stick [0, 0]), or turned an initial slip into a stick (slip [0, 0]).
// Episodes are maximal stick or slip intervals: none may have zero length.
#include <gtest/gtest.h>

#include <vector>

#include "regression/recorded.hpp"
#include "stickslip/belt_switches.hpp"
#include "stickslip/integrator.hpp"

namespace stickslip {
namespace {

using regression::recorded;

// g = 8, mu = 0.5, m = 1, k = 4: a = mu m g / k = 1 exactly, so x0 = +-a is
// exactly on the band edge.
model_parameters unit_band() {
  model_parameters p;
  p.gravity = 8.0;
  p.friction_coefficient = 0.5;
  p.mass = 1.0;
  p.stiffness = 4.0;
  p.belt_speed = 1.0;
  p.window = 10.0;
  return p;
}

recorded run(const initial_conditions& ic, const std::vector<double>& switch_times = {}) {
  recorded r;
  given_switches sw(switch_times);
  simulate(unit_band(), ic, sw, r);
  return r;
}

void expect_positive_alternating(const recorded& r) {
  ASSERT_FALSE(r.episodes.empty());
  EXPECT_EQ(r.episodes.front().start, 0.0);
  for (std::size_t i = 0; i < r.episodes.size(); ++i) {
    EXPECT_GT(r.episodes[i].end, r.episodes[i].start) << "episode " << i;
    if (i + 1 < r.episodes.size()) {
      EXPECT_NE(r.episodes[i].kind, r.episodes[i + 1].kind);
    }
  }
}

TEST(ZeroLengthEpisodeAtStart, StartOnOutwardEdgeAtBeltVelocityIsPureGrazing) {
  ASSERT_EQ(unit_band().band_half_width(), 1.0);
  for (int belt : {+1, -1}) {
    const recorded r = run({belt * 1.0, belt * 1.0, belt});
    expect_positive_alternating(r);
    ASSERT_EQ(r.episodes.size(), 1u) << "belt " << belt;
    EXPECT_EQ(r.episodes[0].kind, mode::slip);
  }
}

TEST(ZeroLengthEpisodeAtStart, BeltSwitchAtZeroEndsTheInitialStickBeforeItStarts) {
  const recorded r = run({0.0, 1.0, +1}, {0.0});
  expect_positive_alternating(r);
  EXPECT_EQ(r.episodes.front().kind, mode::slip);
}

TEST(ZeroLengthEpisodeAtStart, BeltSwitchAtZeroOntoTheMassVelocityStartsAStick) {
  // x'0 = -V with the belt at +V: the switch at t = 0 makes v = x'0.
  const recorded r = run({0.3, -1.0, +1}, {0.0});
  expect_positive_alternating(r);
  EXPECT_EQ(r.episodes.front().kind, mode::stick);
}

}  // namespace
}  // namespace stickslip
