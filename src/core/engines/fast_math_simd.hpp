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

#include <numbers>

#include "stickslip/phase_reduction.hpp"

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

// p[i] = log(p[i]) for i < n (the batched draw of belt switch waits).
HWY_INLINE void log_inplace(double* HWY_RESTRICT p, std::size_t n) {
  const dtag d;
  const std::size_t N = hn::Lanes(d);
  std::size_t i = 0;
  for (; i + N <= n; i += N) hn::StoreU(log(d, hn::LoadU(d, p + i)), d, p + i);
  for (; i < n; ++i) p[i] = hn::GetLane(log(d, hn::Set(d, p[i])));
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
