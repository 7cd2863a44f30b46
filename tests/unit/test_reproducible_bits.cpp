// The same seed gives the same bits on every SIMD target with fused
// multiply-adds (AVX3 = AVX-512, AVX2): Highway's math is the same polynomial
// with the same fused multiply-adds on both, and everything else is IEEE
// arithmetic in a fixed order (no libm call remains in the simulation:
// std::sqrt and std::fmod are exact). This test runs every target compiled
// into the binary that this CPU runs (hwy::SupportedAndGeneratedTargets,
// forced one at a time with hwy::SetSupportedTargetsForTest) and pins a
// digest of a small sweep (every accumulator, histogram and event count, by
// bit pattern, both engines) per family of targets:
//   - FMA targets (AVX3, AVX2): the paper's bits, recorded with 0.1.0 (then a
//     build for one static target, checked with AVX2 and with AVX-512 on a
//     Zen 5 machine) and unchanged by the run-time dispatch;
//   - targets without FMA (SSE4, SSSE3, SCALAR): the same polynomials with
//     separately rounded multiplies and adds, identical among themselves,
//     recorded when the dispatch was introduced (one digest per stiffness).
// A change of a digest means that results of earlier runs can no longer be
// reproduced bit for bit: only a deliberate change of the integrator or of
// the statistics may do that, and then the constant is updated in the same
// commit, saying why.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <hwy/targets.h>

#include "stickslip/fast_math.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip {
namespace {

struct digest {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a, 64 bit
  void add(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) {
      h ^= (v >> (8 * i)) & 0xffu;
      h *= 0x100000001b3ULL;
    }
  }
  void add(double x) { add(std::bit_cast<std::uint64_t>(x)); }
  void add(const mean_variance& m) {
    add(m.count());
    add(m.mean());
    add(m.sum_sq_dev());
  }
  void add(const histogram& hist) {
    for (auto c : hist.counts()) add(c);
    add(hist.underflow());
    add(hist.overflow());
  }
  void add(const point_statistics& p) {
    for (const auto* m : {&p.stick_fraction, &p.sticks_per_time, &p.slips_per_time,
                          &p.stick_duration, &p.first_stick_duration, &p.slip_duration})
      add(*m);
    for (const auto* hist : {&p.stick_fraction_hist, &p.stick_duration_hist,
                             &p.first_stick_duration_hist, &p.slip_duration_hist})
      add(*hist);
    add(p.no_stick);
    add(p.first_stick_censored);
    add(p.events.belt_switches);
    add(p.events.stick_onsets);
    add(p.events.stick_breaks);
    add(p.events.slip_reversals);
  }
};

sweep_spec small_study(double stiffness, sweep_engine engine) {
  sweep_spec s;
  s.base.stiffness = stiffness;
  s.base.window = 20.0;
  s.realizations = 120;
  s.seed = 20261121;
  s.engine = engine;
  s.axes = {{"lambda", {0.3, 3.8, 30.0}}, {"mu", {0.5, 5.0}}};
  return s;
}

std::uint64_t sweep_digest(double stiffness, sweep_engine engine) {
  const auto r = run_sweep(small_study(stiffness, engine), 2);
  digest d;
  for (const auto& p : r.points) d.add(p.stats);
  return d.h;
}

// Recorded from the targets named above; see the header comment before changing.
constexpr std::uint64_t expected_k4 = 0x831e2bb5fc2bcd6dULL;
constexpr std::uint64_t expected_k40 = 0xea85df5a9496a0b6ULL;
constexpr std::uint64_t expected_k4_no_fma = 0xb36c684f76def94dULL;
constexpr std::uint64_t expected_k40_no_fma = 0xc6f8802915f833e1ULL;

// Forces one SIMD target for its lifetime (every HWY_DYNAMIC_DISPATCH of the
// process: the scalar kernels and the lane engine alike).
struct forced_target {
  explicit forced_target(std::int64_t t) { hwy::SetSupportedTargetsForTest(t); }
  ~forced_target() { hwy::SetSupportedTargetsForTest(0); }
  forced_target(const forced_target&) = delete;
  forced_target& operator=(const forced_target&) = delete;
};

TEST(ReproducibleBits, EveryCompiledTargetGivesTheDigestOfItsFamily) {
  const auto targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  bool fma_seen = false;
  for (const std::int64_t t : targets) {
    forced_target force(t);
    const std::string name = hwy::TargetName(t);
    ASSERT_EQ(detail::fm::target(), t) << name;
    EXPECT_EQ(std::string(detail::fm::target_name()), name);
    const bool fma = detail::fm::target_fuses_multiply_add();
    EXPECT_EQ(fma, t == HWY_AVX2 || t == HWY_AVX3 || t == HWY_AVX3_DL) << name;
    fma_seen = fma_seen || fma;
    for (auto engine : {sweep_engine::fast, sweep_engine::reference}) {
      const auto k4 = sweep_digest(4.0, engine), k40 = sweep_digest(40.0, engine);
      EXPECT_EQ(k4, fma ? expected_k4 : expected_k4_no_fma)
          << name << " " << to_string(engine) << " k=4: " << std::hex << k4;
      EXPECT_EQ(k40, fma ? expected_k40 : expected_k40_no_fma)
          << name << " " << to_string(engine) << " k=40: " << std::hex << k40;
    }
  }
  // x86-64 CPUs of the last decade have AVX2: the paper's bits are checked.
  if (hwy::SupportedTargets() & HWY_AVX2) {
    EXPECT_TRUE(fma_seen);
  }
}

// Without a forced target, the dispatch picks the best compiled target the
// CPU runs, and every kernel and the lane engine report that one.
TEST(ReproducibleBits, DispatchPicksTheBestTargetOfTheCpu) {
  const auto targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  EXPECT_EQ(detail::fm::target(), targets.front()) << detail::fm::target_name();
}

// The journal fingerprint records the target actually used: units computed
// on targets of different families never mix in one journal.
TEST(ReproducibleBits, FingerprintNamesTheTargetInUse) {
  const auto targets = hwy::SupportedAndGeneratedTargets();
  const auto spec = small_study(4.0, sweep_engine::fast);
  std::vector<std::uint64_t> prints;
  for (const std::int64_t t : targets) {
    forced_target force(t);
    prints.push_back(fingerprint(spec));
  }
  for (std::size_t i = 0; i < prints.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_NE(prints[i], prints[j]) << hwy::TargetName(targets[i]) << " vs "
                                      << hwy::TargetName(targets[j]);
    }
  }
  EXPECT_EQ(fingerprint(spec), prints.front());
}

}  // namespace
}  // namespace stickslip
