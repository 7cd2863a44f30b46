// The observer contract of the lane engine: it gives an observer the same
// episodes as `simulate` (the reference engine, the oracle) with EVERY field
// (kind, start, end, position_at_start, belt_velocity, censored), the same
// events with every field (kind, time, position, velocity, belt_velocity),
// and the same event counts, all by bit pattern, realization by realization:
// k = 4 and 40, lambda 0.1 .. 30, mu 0.5 .. 7, random starts and starts on
// x' = v inside the band, on its outward and inward edges and outside it.
// (The statistics comparisons of test_fast_path*.cpp would not notice a
// field that realization_observer does not read.)
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cstdint>
#include <string>
#include <vector>

#include "stickslip/detail/fast_block.hpp"
#include "stickslip/error.hpp"
#include "stickslip/observer.hpp"
#include "stickslip/sweep.hpp"
#include "unit/engine_agreement.hpp"
#include "unit/same_bits.hpp"

namespace stickslip {
namespace {

using testing_support::same_bits;
using testing_support::recorder;
using testing_support::describe;
using testing_support::same_episode;
using testing_support::same_event;

// Realizations [first, last) of every point: the lane engine's trace against
// simulate's, field by field; `compared` counts the episodes compared.
void expect_traces_agree(const sweep_spec& s, std::uint64_t first, std::uint64_t last,
                         std::size_t& compared) {
  for (std::size_t point = 0; point < point_count(s); ++point) {
    const auto p = point_parameters(s, point);
    const auto lanes = detail::trace_realizations_lanes(s, point, first, last);
    EXPECT_EQ(lanes.size(), last - first);
    for (std::uint64_t r = first; r < last && r - first < lanes.size(); ++r) {
      recorder ref;
      const auto counts = simulate_realization(s, p, r, ref);
      const auto& got = lanes[r - first];
      const std::string where = "point " + std::to_string(point) + " realization " + std::to_string(r);
      EXPECT_TRUE(same_bits(counts, got.counts)) << where;
      ASSERT_EQ(ref.episodes.size(), got.episodes.size()) << where;
      for (std::size_t i = 0; i < ref.episodes.size(); ++i)
        ASSERT_TRUE(same_episode(ref.episodes[i], got.episodes[i]))
            << where << " episode " << i << ": " << describe(ref.episodes[i]) << " vs "
            << describe(got.episodes[i]);
      ASSERT_EQ(ref.events.size(), got.events.size()) << where;
      for (std::size_t i = 0; i < ref.events.size(); ++i)
        ASSERT_TRUE(same_event(ref.events[i], got.events[i]))
            << where << " event " << i << " (" << to_string(ref.events[i].kind) << " vs "
            << to_string(got.events[i].kind) << ")";
      compared += ref.episodes.size();
    }
  }
}
void expect_traces_agree(const sweep_spec& s, std::uint64_t first, std::uint64_t last) {
  std::size_t compared = 0;
  expect_traces_agree(s, first, last, compared);
}

sweep_spec study(double stiffness) {
  sweep_spec s;
  s.base.stiffness = stiffness;
  s.base.window = 20.0;
  s.seed = 31337;
  s.axes = {{"lambda", {0.1, 0.7, 3.8, 12.0, 30.0}}, {"mu", {0.5, 2.0, 7.0}}};
  return s;
}

TEST(FastPathEpisodes, EveryFieldEqualsSimulatePrintedStiffness) {
  std::size_t compared = 0;
  expect_traces_agree(study(4.0), 0, 40, compared);
  EXPECT_GT(compared, 10000u);
}

TEST(FastPathEpisodes, EveryFieldEqualsSimulateStiffSpring) {
  std::size_t compared = 0;
  expect_traces_agree(study(40.0), 0, 40, compared);
  EXPECT_GT(compared, 10000u);
}

// The same on every SIMD target this CPU runs (AVX3: 8 doubles per vector,
// AVX2: 4, SSE4 and SSSE3: 2, SCALAR: 1), forced one at a time: the lane
// layout differs, the episodes and events must not (within each target,
// against simulate on that target).
TEST(FastPathEpisodes, EveryFieldEqualsSimulateOnEveryTarget) {
  auto s = study(40.0);
  s.axes = {{"lambda", {0.7, 30.0}}, {"mu", {0.5, 7.0}}};
  for (const std::int64_t t : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(t);
    SCOPED_TRACE(hwy::TargetName(t));
    std::size_t compared = 0;
    expect_traces_agree(s, 3, 40, compared);
    EXPECT_GT(compared, 1000u);
  }
  hwy::SetSupportedTargetsForTest(0);
}

// More realizations than the reorder ring holds, not starting at 0, belt
// starting backwards.
TEST(FastPathEpisodes, LongRunsAndOtherStarts) {
  auto s = study(40.0);
  s.axes = {{"lambda", {0.3, 30.0}}, {"mu", {1.0, 5.0}}};
  s.initial.belt_start = -1;
  s.initial.position_min = -20.0;
  s.initial.position_max = 20.0;
  s.initial.velocity_min = -8.0;
  s.initial.velocity_max = 8.0;
  expect_traces_agree(s, 7, 160);
}

// Starts with x' = v: inside the band (a stick), on the outward edge (a
// grazing touch, no stick), on the inward edge (a stick), outside it (the
// slip starts at a reversal, the lane engine's scalar path), both belt
// directions.
TEST(FastPathEpisodes, StartsOnTheBeltVelocity) {
  for (int belt : {1, -1})
    for (double where : {0.3, 1.0, -1.0, 1.7, -2.5}) {
      for (double k : {4.0, 40.0}) {
        auto s = study(k);
        s.axes = {{"lambda", {0.1, 3.8, 30.0}}, {"mu", {0.5, 7.0}}};
        s.initial.belt_start = belt;
        s.initial.velocity_min = s.initial.velocity_max = belt * s.base.belt_speed;
        for (std::size_t point = 0; point < point_count(s); ++point) {
          auto one = s;
          const auto p = point_parameters(s, point);
          one.base = p;
          one.axes.clear();
          one.initial.position_min = one.initial.position_max = where * p.band_half_width();
          SCOPED_TRACE("k " + std::to_string(k) + " x0/a " + std::to_string(where) + " belt " +
                       std::to_string(belt) + " point " + std::to_string(point));
          expect_traces_agree(one, 0, 12);
        }
      }
    }
}

// Over max_events the lane engine's trace reports the reference's error.
TEST(FastPathEpisodes, WorkBoundGivesTheReferenceError) {
  auto s = study(4.0);
  s.axes = {{"lambda", {30.0}}, {"mu", {2.0}}};
  s.max_events = 40;  // ~600 switches per realization
  std::string ref, lanes;
  try {
    recorder r;
    (void)simulate_realization(s, point_parameters(s, 0), 0, r);
  } catch (const error& e) {
    ref = e.what();
  }
  try {
    (void)detail::trace_realizations_lanes(s, 0, 0, 5);
  } catch (const error& e) {
    lanes = e.what();
  }
  EXPECT_FALSE(ref.empty());
  EXPECT_EQ(ref, lanes);
}

// The statistics observer takes neither events nor segments, so the sweep's
// lane engine builds no events; an observer of segments is refused at
// compile time (static_assert in src/core/engines/fast_lanes.cpp).
TEST(FastPathEpisodes, ObserverTraits) {
  EXPECT_FALSE(observes_events<realization_observer>);
  EXPECT_FALSE(observes_segments<realization_observer>);
  EXPECT_TRUE(observes_events<recorder>);
  EXPECT_FALSE(observes_segments<recorder>);
}

}  // namespace
}  // namespace stickslip
