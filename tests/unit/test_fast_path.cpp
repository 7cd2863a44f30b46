// The fast engine (sweep_engine::fast) against the reference engine
// (poisson_switches + realization_observer + point_statistics::add): every
// statistic must agree bit for bit, for any seed, grid and block size.
#include <gtest/gtest.h>
#include <hwy/targets.h>
#include <Random123/philox.h>
#include <Random123/uniform.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include "stickslip/belt_switches.hpp"
#include "stickslip/fast_math.hpp"
#include "stickslip/random_stream.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/sweep.hpp"
#include "unit/engine_agreement.hpp"
#include "unit/same_bits.hpp"

namespace stickslip {
namespace {

using testing_support::same_bits;
using testing_support::expect_engines_agree;

sweep_spec small_study(double stiffness) {
  sweep_spec s;
  s.base.stiffness = stiffness;
  s.base.window = 20.0;
  s.realizations = 60;
  s.block_size = 16;  // last block is partial
  s.seed = 12345;
  s.axes = {{"lambda", {0.1, 0.7, 3.8, 12.0, 30.0}}, {"mu", {0.5, 3.0, 7.0}}};
  return s;
}

TEST(FastPath, DefaultEngineIsFast) { EXPECT_EQ(sweep_spec{}.engine, sweep_engine::fast); }

TEST(FastPath, BitwiseEqualToReferencePrintedStiffness) { expect_engines_agree(small_study(4.0), 2); }

TEST(FastPath, BitwiseEqualToReferenceStiffSpring) { expect_engines_agree(small_study(40.0), 2); }

TEST(FastPath, BitwiseEqualWithRecordsAndOtherSeed) {
  auto s = small_study(4.0);
  s.seed = 7;
  s.keep_records = true;
  s.block_size = 7;
  s.initial.belt_start = -1;
  expect_engines_agree(s, 3);
}

TEST(FastPath, SimulateBlockDispatchesOnEngine) {
  auto s = small_study(4.0);
  const work_unit u{7, 1};
  s.engine = sweep_engine::reference;
  const auto a = simulate_block(s, u);
  s.engine = sweep_engine::fast;
  const auto b = simulate_block(s, u);
  const auto c = simulate_block_reference(s, u);
  EXPECT_TRUE(same_bits(a.stats, b.stats));
  EXPECT_TRUE(same_bits(a.stats, c.stats));
  EXPECT_GT(a.stats.events.belt_switches, 0u);
}

// The one Poisson switch source (drawn 32 at a time with the vector log)
// against its definition written out here one draw at a time: Y_j =
// Y_{j-1} + (-log(U_j)) / lambda with U_j the u01fixedpt of the j-th word of
// the belt-switch substream and the scalar log kernel, bit for bit. (The
// lane engine refills through next_refilled_by with its target's kernel:
// FastPath* and ReproducibleBits* compare its bits.)
TEST(FastPath, PoissonSwitchesAreTheRunningSumOfExponentialWaits) {
  for (double rate : {0.1, 3.8, 30.0}) {
    poisson_switches sw(rate, 99, 1234, 5);
    random_stream rs(99, 1234, 5, substream::belt_switches);
    const double mean_wait = 1.0 / rate;
    double y = 0.0;
    for (int i = 0; i < 250; ++i) {
      const auto blk = rs.next_block();
      for (int j = 0; j < 4; ++j) {
        y += -detail::fm::log(random_stream::open_uniform(blk.v[j])) * mean_wait;
        ASSERT_TRUE(same_bits(sw.next(), y)) << rate << " " << 4 * i + j;
      }
    }
  }
}

// The vector draw kernel (fm::log_uniforms: the Philox rounds of many
// blocks on whole vectors) against Random123's own Philox4x64-10 called one
// block at a time, u01fixedpt and the scalar log kernel, bit for bit: on
// every SIMD target compiled in and run by this CPU (the vector rounds on
// AVX3 and AVX2, one block at a time below four 64-bit lanes), for whole
// and partial vectors of blocks (1 .. 17), for counters whose block index
// wraps at 2^64 inside a vector, and with the stream left where
// next_block would leave it.
TEST(FastPath, VectorPhiloxDrawsAreRandom123sWordsAndLogs) {
  const auto targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  for (const std::int64_t t : targets) {
    hwy::SetSupportedTargetsForTest(t);
    const std::string name = hwy::TargetName(t);
    for (const std::uint64_t first_block : {std::uint64_t{0}, std::uint64_t{5}, ~std::uint64_t{0} - 3}) {
      for (std::size_t blocks = 1; blocks <= 17; ++blocks) {
        random_stream rs(7, 0x9e3779b97f4a7c15ULL, 12345, substream::belt_switches);
        rs.skip_blocks(first_block);
        std::vector<double> w(4 * blocks);
        detail::fm::log_uniforms(rs, w.data(), blocks);
        const r123::Philox4x64::key_type key = {{7, 0x9e3779b97f4a7c15ULL}};
        for (std::size_t b = 0; b < blocks; ++b) {
          const r123::Philox4x64::ctr_type ctr = {{12345, 1, first_block + b, 0}};
          const auto words = r123::Philox4x64{}(ctr, key);
          for (std::size_t j = 0; j < 4; ++j) {
            const double expected = detail::fm::log(r123::u01fixedpt<double>(words.v[j]));
            ASSERT_TRUE(same_bits(w[4 * b + j], expected))
                << name << ": block " << first_block + b << " word " << j << " of " << blocks;
          }
        }
        const r123::Philox4x64::ctr_type after = {{12345, 1, first_block + blocks, 0}};
        EXPECT_EQ(rs.next_block().v[0], r123::Philox4x64{}(after, key).v[0]) << name;
      }
    }
  }
  hwy::SetSupportedTargetsForTest(0);
}

// The mirror return (integrator.hpp header): after a belt switch that ends a
// stick at x, the next stick starts at the same x after
// tau = (pi - 2 atan(w |x + s a| / V)) / w.
struct stick_log : observer_base {
  std::vector<episode> episodes;
  void on_episode(const episode& e) { episodes.push_back(e); }
};

TEST(FastPath, MirrorReturnRestartsTheStickAtTheSamePosition) {
  model_parameters p;  // a = 12.2625, w = 2
  const double a = p.band_half_width(), w = p.natural_frequency(), V = p.belt_speed;
  const initial_conditions ic{0.3, V, 1};  // sticking at x = 0.3, v = +V
  const double switches[] = {0.5, 100.0};
  given_switches sw(switches);
  stick_log log;
  simulate(p, ic, sw, log);
  ASSERT_GE(log.episodes.size(), 3u);
  const double x_switch = 0.3 + V * 0.5;
  const double tau = (std::numbers::pi - 2.0 * std::atan(w * (x_switch + a) / V)) / w;
  EXPECT_EQ(log.episodes[1].kind, mode::slip);
  EXPECT_EQ(log.episodes[2].kind, mode::stick);
  EXPECT_DOUBLE_EQ(log.episodes[2].start, 0.5 + tau);
  EXPECT_DOUBLE_EQ(log.episodes[2].position_at_start, x_switch);
}

// root_angle against the textbook form forward(atan2(w y, x'), -+acos(v/B)).
TEST(FastPath, RootAngleMatchesTextbookForm) {
  const double two_pi = 2.0 * std::numbers::pi;
  int checked = 0;
  for (double v : {1.0, -1.0})
    for (double wy = -7.0; wy <= 7.0; wy += 0.37)
      for (double z = -5.0; z <= 5.0; z += 0.29) {
        if (z == v) continue;
        const double sigma = v > z ? 1.0 : -1.0;
        const double disc = wy * wy + (z - v) * (z + v);
        if (!(disc > 0.0)) continue;
        const double B = std::sqrt(wy * wy + z * z);
        const double alpha = std::acos(v / B);
        double expected = detail::forward_angle(std::atan2(wy, z), sigma > 0 ? -alpha : alpha);
        const double region = sigma > 0 ? two_pi - 2.0 * alpha : 2.0 * alpha;
        if (expected > region) expected = 0.0;
        EXPECT_NEAR(detail::root_angle(wy, z, v, sigma, std::sqrt(disc)), expected, 1e-12)
            << "wy=" << wy << " z=" << z << " v=" << v;
        ++checked;
      }
  EXPECT_GT(checked, 1000);
}

}  // namespace
}  // namespace stickslip
