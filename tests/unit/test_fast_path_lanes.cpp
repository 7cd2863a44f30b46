// The lane engine (detail::simulate_block_lanes, what sweep_engine::fast
// runs: several realizations per thread in lock step, transcendentals as SIMD
// vectors) against the reference engine: every statistic and record bit for bit, for any block size (including
// blocks longer than the lane engine's reorder ring), seed, stiffness and
// thread count; the same error when a realization exceeds max_events; and the
// shared kernels (stickslip/fast_math.hpp) against libm.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>

#include "stickslip/detail/fast_block.hpp"
#include "stickslip/fast_math.hpp"
#include "stickslip/error.hpp"
#include "stickslip/sweep.hpp"
#include "unit/same_bits.hpp"

namespace stickslip {
namespace {

using testing_support::same_bits;

sweep_spec study(double stiffness, std::uint64_t realizations, std::uint64_t block) {
  sweep_spec s;
  s.base.stiffness = stiffness;
  s.base.window = 20.0;
  s.realizations = realizations;
  s.block_size = block;
  s.seed = 2024;
  s.keep_records = true;
  s.axes = {{"lambda", {0.1, 0.9, 3.8, 30.0}}, {"mu", {0.5, 2.0, 7.0}}};
  return s;
}

// Every unit of the spec, both engines, bit for bit.
void expect_units_agree(const sweep_spec& s) {
  for (std::uint64_t i = 0; i < unit_count(s); ++i) {
    const auto u = unit_at(s, i);
    const auto ref = simulate_block_reference(s, u);
    const auto lanes = detail::simulate_block_lanes(s, u);
    EXPECT_TRUE(same_bits(ref.stats, lanes.stats)) << "unit " << i;
    ASSERT_EQ(ref.records.size(), lanes.records.size());
    for (std::size_t j = 0; j < ref.records.size(); ++j)
      EXPECT_TRUE(same_bits(ref.records[j], lanes.records[j])) << "unit " << i << " record " << j;
  }
}

TEST(FastPathLanes, BitwiseEqualPrintedStiffness) { expect_units_agree(study(4.0, 45, 11)); }
TEST(FastPathLanes, BitwiseEqualStiffSpring) { expect_units_agree(study(40.0, 45, 11)); }
TEST(FastPathLanes, BlockOfOneRealization) { expect_units_agree(study(4.0, 5, 1)); }
TEST(FastPathLanes, FewerRealizationsThanLanes) { expect_units_agree(study(40.0, 3, 3)); }

TEST(FastPathLanes, BlockLongerThanTheReorderRing) {
  auto s = study(4.0, 150, 150);
  s.axes = {{"lambda", {0.2, 30.0}}, {"mu", {1.0}}};
  s.seed = 5;
  s.initial.belt_start = -1;
  expect_units_agree(s);
}

// Several consecutive blocks of a point in one lane engine (what run_units
// does with the fast engine): each block's result is the reference's.
TEST(FastPathLanes, ConsecutiveBlocksAtOnceEqualTheReferencePerBlock) {
  for (double k : {4.0, 40.0}) {
    auto s = study(k, 47, 7);  // 7 blocks, the last one partial
    for (std::size_t point : {0u, 5u, 11u}) {
      const auto all = detail::simulate_blocks_lanes(s, point, 1, 6);
      ASSERT_EQ(all.size(), 6u);
      for (std::uint64_t b = 0; b < 6; ++b) {
        const auto ref = simulate_block_reference(s, work_unit{point, 1 + b});
        EXPECT_TRUE(same_bits(ref.stats, all[b].stats)) << k << " " << point << " " << b;
        ASSERT_EQ(ref.records.size(), all[b].records.size());
        for (std::size_t j = 0; j < ref.records.size(); ++j)
          EXPECT_TRUE(same_bits(ref.records[j], all[b].records[j]));
      }
    }
  }
}

TEST(FastPathLanes, SweepIsBitIdenticalForAnyThreadCount) {
  auto s = study(40.0, 40, 9);
  s.engine = sweep_engine::reference;
  const auto ref = run_sweep(s, 1);
  s.engine = sweep_engine::fast;  // the lane engine, through simulate_block and run_units
  for (unsigned threads : {1u, 2u, 3u}) {
    const auto r = run_sweep(s, threads);
    ASSERT_EQ(ref.points.size(), r.points.size());
    for (std::size_t i = 0; i < r.points.size(); ++i) {
      EXPECT_TRUE(same_bits(ref.points[i].stats, r.points[i].stats)) << threads << " " << i;
      ASSERT_EQ(ref.points[i].stats.convergence.size(), r.points[i].stats.convergence.size());
      for (std::size_t j = 0; j < r.points[i].stats.convergence.size(); ++j)
        EXPECT_TRUE(same_bits(ref.points[i].stats.convergence[j].R_mean,
                              r.points[i].stats.convergence[j].R_mean));
    }
  }
}

// Passes of simulate()'s event loop (what max_events bounds): one segment
// each.
struct pass_counter : observer_base {
  std::int64_t passes = 0;
  void on_segment(const segment&) noexcept { ++passes; }
};

std::string error_of(const auto& run) {
  try {
    (void)run();
  } catch (const error& e) {
    return e.what();
  }
  return {};
}

// The event budget at its exact threshold: with max_events = the largest
// number of passes any realization of the unit needs, the lane engine runs
// (without handing the unit to the reference engine) and gives the
// reference's bits; one less, and it reports the reference's error. k = 40
// has many reversal slips (counted on the scalar path); 45 realizations in
// blocks of 11 leave lanes idle at the tail.
TEST(FastPathLanes, WorkBoundAtItsExactThreshold) {
  for (double mu : {2.0, 7.0}) {
    auto s = study(40.0, 45, 11);
    s.axes = {{"lambda", {30.0}}, {"mu", {mu}}};
    const auto p = point_parameters(s, 0);
    for (std::uint64_t block = 0; block < 5; ++block) {
      const work_unit u{0, block};
      std::int64_t most = 0;
      for (std::uint64_t r = block * 11; r < std::min<std::uint64_t>(45, block * 11 + 11); ++r) {
        pass_counter c;
        auto unbounded = s;
        unbounded.max_events = default_max_events;
        (void)simulate_realization(unbounded, p, r, c);
        most = std::max(most, c.passes);
      }
      s.max_events = most;
      const auto reruns = detail::lane_reference_reruns();
      const auto ref = simulate_block_reference(s, u);
      const auto lanes = detail::simulate_block_lanes(s, u);
      EXPECT_EQ(detail::lane_reference_reruns(), reruns) << "mu " << mu << " block " << block;
      EXPECT_TRUE(same_bits(ref.stats, lanes.stats)) << "mu " << mu << " block " << block;
      s.max_events = most - 1;
      const auto ref_msg = error_of([&] { return simulate_block_reference(s, u); });
      EXPECT_FALSE(ref_msg.empty());
      EXPECT_EQ(ref_msg, error_of([&] { return detail::simulate_block_lanes(s, u); }));
    }
  }
}

// Realizations that start with x' = v: inside the band (a stick), on the
// outward edge (grazing, no stick) and outside it (the slip starts at a
// reversal, the scalar path), also under a budget that ends inside that
// first reversal slip.
TEST(FastPathLanes, StartsOnTheBeltVelocity) {
  for (double where : {0.3, 1.0, 1.7, -2.5}) {
    auto s = study(40.0, 23, 23);
    s.axes = {{"lambda", {0.9, 30.0}}, {"mu", {2.0}}};
    const double a = point_parameters(s, 0).band_half_width();
    s.initial.velocity_min = s.initial.velocity_max = s.base.belt_speed;
    s.initial.belt_start = 1;
    s.initial.position_min = s.initial.position_max = where * a;
    expect_units_agree(s);
    s.max_events = 2;
    for (std::size_t point : {0u, 1u}) {
      const work_unit u{point, 0};
      EXPECT_EQ(error_of([&] { return simulate_block_reference(s, u); }),
                error_of([&] { return detail::simulate_block_lanes(s, u); }))
          << where << " " << point;
    }
  }
}

TEST(FastPathLanes, WorkBoundErrorIsTheReferenceOne) {
  auto s = study(4.0, 10, 10);
  s.max_events = 40;  // lambda = 30, t_a = 20: ~600 switches per realization
  const work_unit u{9, 0};
  std::string ref_msg, lanes_msg;
  try {
    (void)simulate_block_reference(s, u);
  } catch (const error& e) {
    ref_msg = e.what();
  }
  try {
    (void)detail::simulate_block_lanes(s, u);
  } catch (const error& e) {
    lanes_msg = e.what();
  }
  EXPECT_FALSE(ref_msg.empty());
  EXPECT_EQ(ref_msg, lanes_msg);
}

// The shared kernels agree with glibc to a few ulp (Highway's bounds; atan2
// adds one division) and are odd/even where the functions are.
TEST(FastPathLanes, KernelsMatchLibm) {
  auto ulps = [](double got, double want) {
    return std::abs(got - want) / (std::numeric_limits<double>::epsilon() *
                                   std::max(std::abs(want), std::numeric_limits<double>::min()));
  };
  double worst_log = 0, worst_atan = 0, worst_atan2 = 0, worst_sc = 0;
  for (int i = 1; i < 20000; ++i) {
    const double u = i / 20000.0;
    worst_log = std::max(worst_log, ulps(detail::fm::log(u), std::log(u)));
    const double q = std::tan(u * 0.5 * std::numbers::pi) * 0.999;
    worst_atan = std::max(worst_atan, ulps(detail::fm::atan(q), std::atan(q)));
    const double y = std::sin(i * 0.7) * 3.0, x = std::cos(i * 1.3) * 2.0;
    worst_atan2 = std::max(worst_atan2, ulps(detail::fm::atan2(y, x), std::atan2(y, x)));
    const double ph = i * 0.0157;  // up to ~314 = w t_a for k = 40, t_a = 50
    worst_sc = std::max(worst_sc, std::abs(detail::fm::sin(ph) - std::sin(ph)) / 2.2e-16);
    worst_sc = std::max(worst_sc, std::abs(detail::fm::cos(ph) - std::cos(ph)) / 2.2e-16);
  }
  EXPECT_LE(worst_log, 4.0);
  EXPECT_LE(worst_atan, 4.0);
  EXPECT_LE(worst_atan2, 6.0);
  EXPECT_LE(worst_sc, 8.0);  // absolute, in units of 2^-52
  EXPECT_EQ(detail::fm::atan2(0.0, -1.0), std::numbers::pi);
  EXPECT_EQ(detail::fm::atan2(-0.0, -1.0), -std::numbers::pi);
  EXPECT_EQ(detail::fm::atan2(1.0, 0.0), 0.5 * std::numbers::pi);
  // Phases past Highway's range are reduced exactly first.
  EXPECT_NEAR(detail::fm::sin(1e6), std::sin(1e6), 1e-9);
  EXPECT_NEAR(detail::fm::cos(-1e6), std::cos(-1e6), 1e-9);
}

}  // namespace
}  // namespace stickslip
