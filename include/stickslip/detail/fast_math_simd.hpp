// Vector forms of the kernels of detail/fast_math.hpp. Include only from the
// translation units compiled with the SIMD target flags (fast_math.cpp,
// fast_lanes.cpp): both must see the same static Highway target.
#pragma once
#include <hwy/highway.h>
#include <hwy/contrib/math/math-inl.h>

#include <numbers>

namespace stickslip::detail::simd {
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

}  // namespace stickslip::detail::simd
