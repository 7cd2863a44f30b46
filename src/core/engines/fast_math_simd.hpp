// Vector forms of the kernels of stickslip/fast_math.hpp, for every SIMD target.
// Include only from translation units that are compiled once per Highway
// target (hwy/foreach_target.h: engines/fast_math.cpp, engines/fast_lanes.cpp):
// like Highway's own -inl headers it is re-included for each target, and
// defines stickslip::detail::simd::HWY_NAMESPACE (N_AVX3, N_AVX2, N_SSE4, ...).
// Highway's math is lane-wise (no cross-lane step), so a lane's result does
// not depend on its neighbours or on the vector width: AVX2 and AVX3 give the
// same bits (same polynomials, same fused multiply-adds).

// Per-target include guard (Highway's pattern for -inl headers).
#if defined(STICKSLIP_DETAIL_FAST_MATH_SIMD_HPP_) == defined(HWY_TARGET_TOGGLE)
#ifdef STICKSLIP_DETAIL_FAST_MATH_SIMD_HPP_
#undef STICKSLIP_DETAIL_FAST_MATH_SIMD_HPP_
#else
#define STICKSLIP_DETAIL_FAST_MATH_SIMD_HPP_
#endif

#include <hwy/highway.h>
#include <hwy/contrib/math/math-inl.h>

#include <cstddef>
#include <cstdint>
#include <numbers>

#include "stickslip/phase_reduction.hpp"
#include "stickslip/random_stream.hpp"

HWY_BEFORE_NAMESPACE();
namespace stickslip::detail::simd {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using dtag = hn::ScalableTag<double>;
using vec = hn::Vec<dtag>;

// atan2 from Highway's Atan on [0, 1]: octant by |y| <= |x|, then quadrant.
// Precondition: (x, y) != (0, 0). atan2(+-0, x < 0) = +-pi as in libm.
// Split in two so that the lane engine can share one Atan call between
// atan2 lanes and plain atan lanes: atan2 = atan2_finish(Atan(q), ...) with
// q = atan2_ratio(...).
HWY_INLINE void atan2_ratio_operands(vec y, vec x, vec& num, vec& den) {
  const vec ay = hn::Abs(y), ax = hn::Abs(x);
  const auto steep = hn::Gt(ay, ax);
  num = hn::IfThenElse(steep, ax, ay);
  den = hn::IfThenElse(steep, ay, ax);
}
HWY_INLINE vec atan2_ratio(vec y, vec x) {
  vec num, den;
  atan2_ratio_operands(y, x, num, den);
  return hn::Div(num, den);
}
HWY_INLINE vec atan2_finish(dtag d, vec atan_ratio, vec y, vec x) {
  const auto steep = hn::Gt(hn::Abs(y), hn::Abs(x));
  vec r = hn::IfThenElse(steep, hn::Sub(hn::Set(d, 0.5 * std::numbers::pi), atan_ratio), atan_ratio);
  r = hn::IfThenElse(hn::Lt(x, hn::Zero(d)), hn::Sub(hn::Set(d, std::numbers::pi), r), r);
  return hn::CopySign(r, y);
}
HWY_INLINE vec atan2(dtag d, vec y, vec x) {
  return atan2_finish(d, hn::Atan(d, atan2_ratio(y, x)), y, x);
}

HWY_INLINE vec atan(dtag d, vec x) { return hn::Atan(d, x); }
HWY_INLINE vec log(dtag d, vec x) { return hn::Log(d, x); }
HWY_INLINE vec sin(dtag d, vec x) { return hn::Sin(d, x); }
// cos(x) = 1 for |x| < 1e-8, where the correctly rounded value is 1
// (Highway's Cos reduces by pi/2 and returns 1 - 1 ulp there): a rotation by
// a zero phase (a belt switch at t = 0) must be the identity.
HWY_INLINE vec cos(dtag d, vec x) {
  return hn::IfThenElse(hn::Lt(hn::Abs(x), hn::Set(d, 1e-8)), hn::Set(d, 1.0), hn::Cos(d, x));
}

// p[i] = log(p[i]) for i < n (log_uniforms' draws on targets of fewer than
// four 64-bit lanes).
HWY_INLINE void log_inplace(double* HWY_RESTRICT p, std::size_t n) {
  const dtag d;
  const std::size_t N = hn::Lanes(d);
  std::size_t i = 0;
  for (; i + N <= n; i += N) hn::StoreU(log(d, hn::LoadU(d, p + i)), d, p + i);
  for (; i < n; ++i) p[i] = hn::GetLane(log(d, hn::Set(d, p[i])));
}

// Philox4x64-10 (Random123's philox4x64, the generator of random_stream) on
// whole vectors: lane b computes the block of counter {c0, c1, c2 + b, c3},
// so one vector holds N consecutive blocks. Integer arithmetic only: the
// same words as r123::Philox4x64 on any target. Each 64 x 64 -> 128-bit
// product is four 32 x 32 -> 64-bit ones (the vector units have no 64-bit
// high multiply): hi and lo of a * m, m = m_hi * 2^32 + m_lo.
template <class DU>
HWY_INLINE void mulhilo64(DU du, hn::Vec<DU> a, hn::Vec<DU> m_lo, hn::Vec<DU> m_hi,
                          hn::Vec<DU>& hi, hn::Vec<DU>& lo) {
  const hn::Repartition<std::uint32_t, DU> d32;
  const auto a32 = hn::BitCast(d32, a), a_hi32 = hn::BitCast(d32, hn::ShiftRight<32>(a));
  const auto ll = hn::MulEven(a32, hn::BitCast(d32, m_lo));
  const auto lh = hn::MulEven(a32, hn::BitCast(d32, m_hi));
  const auto hl = hn::MulEven(a_hi32, hn::BitCast(d32, m_lo));
  const auto hh = hn::MulEven(a_hi32, hn::BitCast(d32, m_hi));
  const auto low32 = hn::Set(du, 0xffffffffULL);
  const auto t = hn::Add(hl, hn::ShiftRight<32>(ll));  // < 2^64: no carry lost
  const auto u = hn::Add(lh, hn::And(t, low32));
  hi = hn::Add(hn::Add(hh, hn::ShiftRight<32>(t)), hn::ShiftRight<32>(u));
  lo = hn::OrAnd(hn::ShiftLeft<32>(u), ll, low32);
}

// w[0 .. 4 * blocks) = log(random_stream::open_uniform(word)) of the words
// of the next `blocks` blocks of rs, in order (block by block, word by
// word), and rs advanced past them: the same bits as rs.next_block(),
// open_uniform and log() of each word (log is lane-wise; u01fixedpt is
// exact: an odd integer below 2^53 times 2^-53). The belt switch draws,
// vectorized whole: one block at a time, a block's ten rounds are one
// dependency chain (4.3 - 5.3 ns a word on an AVX-512 Xeon, against 2.4 ns
// for 8 blocks on one vector; docs/performance.md). Targets of fewer than
// four 64-bit lanes, and a count of blocks that is not a whole number of
// vectors, draw blocks one at a time, as 0.1.0.
HWY_INLINE void log_uniforms(random_stream& rs, double* HWY_RESTRICT w, std::size_t blocks) {
  const dtag d;
  const hn::RebindToUnsigned<dtag> du;
  constexpr std::size_t N = hn::MaxLanes(dtag());
  if constexpr (N >= 4) {
    if (blocks % N == 0) {
      using philox = random_stream::philox;
      const auto& key = rs.key();
      const auto& ctr = rs.counter();
      const auto m0_lo = hn::Set(du, PHILOX_M4x64_0 & 0xffffffffULL);
      const auto m0_hi = hn::Set(du, PHILOX_M4x64_0 >> 32);
      const auto m1_lo = hn::Set(du, PHILOX_M4x64_1 & 0xffffffffULL);
      const auto m1_hi = hn::Set(du, PHILOX_M4x64_1 >> 32);
      const auto one = hn::Set(du, 1);
      // random_stream::open_uniform (r123::u01fixedpt<double>) on whole
      // vectors: (1 | w >> 11) * 2^-53, exact (FastPath.VectorPhilox...).
      const auto ulp53 = hn::Set(d, 0x1p-53);
      const auto uniform = [&](hn::Vec<decltype(du)> x) {
        return log(d, hn::Mul(hn::ConvertTo(d, hn::Or(one, hn::ShiftRight<11>(x))), ulp53));
      };
      static_assert(philox::rounds == 10);
      for (std::size_t b = 0; b < blocks; b += N) {
        auto x0 = hn::Set(du, ctr.v[0]), x1 = hn::Set(du, ctr.v[1]);
        auto x2 = hn::Iota(du, ctr.v[2] + b), x3 = hn::Set(du, ctr.v[3]);
        std::uint64_t k0 = key.v[0], k1 = key.v[1];
        for (int round = 0; round < 10; ++round) {
          if (round > 0) {
            k0 += PHILOX_W64_0;
            k1 += PHILOX_W64_1;
          }
          hn::Vec<decltype(du)> hi0, lo0, hi1, lo1;
          mulhilo64(du, x0, m0_lo, m0_hi, hi0, lo0);
          mulhilo64(du, x2, m1_lo, m1_hi, hi1, lo1);
          x0 = hn::Xor3(hi1, x1, hn::Set(du, k0));
          x1 = lo1;
          x2 = hn::Xor3(hi0, x3, hn::Set(du, k1));
          x3 = lo0;
        }
        hn::StoreInterleaved4(uniform(x0), uniform(x1), uniform(x2), uniform(x3), d, w + 4 * b);
      }
      rs.skip_blocks(blocks);
      return;
    }
  }
  for (std::size_t b = 0; b < blocks; ++b) {
    const auto block = rs.next_block();
    for (int j = 0; j < 4; ++j) w[4 * b + j] = random_stream::open_uniform(block.v[j]);
  }
  log_inplace(w, 4 * blocks);
}

// The scalar kernels of this target: the vector kernel on a broadcast
// argument, lane 0. fm::log etc. (fast_math.cpp) dispatch to these; the lane
// engine calls them directly, inside the same target.
HWY_INLINE double log1(double x) {
  const dtag d;
  return hn::GetLane(log(d, hn::Set(d, x)));
}
HWY_INLINE double atan1(double x) {
  const dtag d;
  return hn::GetLane(atan(d, hn::Set(d, x)));
}
HWY_INLINE double atan21(double y, double x) {
  const dtag d;
  return hn::GetLane(atan2(d, hn::Set(d, y), hn::Set(d, x)));
}
HWY_INLINE double sin1(double x) {
  const dtag d;
  return hn::GetLane(sin(d, hn::Set(d, fm::reduce_phase(x))));
}
HWY_INLINE double cos1(double x) {
  const dtag d;
  return hn::GetLane(cos(d, hn::Set(d, fm::reduce_phase(x))));
}

}  // namespace HWY_NAMESPACE
}  // namespace stickslip::detail::simd
HWY_AFTER_NAMESPACE();

#endif  // per-target include guard
