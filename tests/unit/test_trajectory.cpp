// The one trajectory sampler: sample_trajectory over hand-made
// closed-form segments, checked against the motion written out here
// independently, and against the samples Fig. 2 uses.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "stickslip/study/figures.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/trajectory.hpp"

namespace stickslip {
namespace {

// A stick on [0, 0.25] at v = 1 from x = 0.5, then a slip on [0.25, 1] with
// centre c = 2, omega = 2, from x = 0.75, x' = 1, v = -1.
std::vector<segment> two_segments() {
  return {segment{mode::stick, 0.0, 0.25, 0.5, 1.0, 1.0, 0.0, 2.0},
          segment{mode::slip, 0.25, 1.0, 0.75, 1.0, -1.0, 2.0, 2.0}};
}

TEST(SampleTrajectory, GridInstantsPlusBothEndsOfEverySegment) {
  const auto q = sample_trajectory(two_segments(), 0.1);
  std::vector<double> times;
  for (const auto& s : q) times.push_back(s.time);
  const std::vector<double> expected{0.0, 0.1, 0.2, 0.25, 0.25, 0.3, 0.4, 0.5, 0.6,
                                     0.7, 0.8, 0.9, 1.0};
  ASSERT_EQ(times.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(times[i], expected[i], 1e-15) << i;
}

TEST(SampleTrajectory, ValuesFollowTheClosedForm) {
  for (const auto& s : sample_trajectory(two_segments(), 0.1)) {
    if (s.kind == mode::stick) {
      EXPECT_DOUBLE_EQ(s.position, 0.5 + 1.0 * s.time);
      EXPECT_DOUBLE_EQ(s.velocity, 1.0);
      EXPECT_EQ(s.belt_velocity, 1.0);
    } else {
      // x = c + (x0 - c) cos w tau + (x0'/w) sin w tau, tau = t - 0.25.
      const double tau = s.time - 0.25;
      EXPECT_NEAR(s.position, 2.0 - 1.25 * std::cos(2 * tau) + 0.5 * std::sin(2 * tau), 1e-14);
      EXPECT_NEAR(s.velocity, 1.0 * std::cos(2 * tau) + 2.0 * 1.25 * std::sin(2 * tau), 1e-14);
      EXPECT_EQ(s.belt_velocity, -1.0);
    }
  }
}

TEST(SampleTrajectory, StopsAtTEnd) {
  const auto q = sample_trajectory(two_segments(), 0.1, 0.25);
  ASSERT_FALSE(q.empty());
  EXPECT_EQ(q.back().time, 0.25);
  EXPECT_EQ(q.back().kind, mode::stick);
  for (const auto& s : q) EXPECT_LE(s.time, 0.25);
}

TEST(SampleTrajectory, Fig2UsesTheSameSampler) {
  sweep_spec spec;
  model_parameters p;
  p.switch_rate = 2.0;
  p.window = 5.0;
  segment_recorder rec;
  (void)simulate_realization(spec, p, 3, rec);
  const auto direct = sample_trajectory(rec.segments, 0.05, 4.0);
  const auto fig = study::sample_realization(spec, p, 3, 0.05, 4.0);
  ASSERT_EQ(direct.size(), fig.size());
  for (std::size_t i = 0; i < fig.size(); ++i) {
    EXPECT_EQ(fig[i].t, direct[i].time);
    EXPECT_EQ(fig[i].x, direct[i].position);
    EXPECT_EQ(fig[i].stick, direct[i].kind == mode::stick);
  }
}

}  // namespace
}  // namespace stickslip
