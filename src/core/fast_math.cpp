// Scalar entry points of the shared kernels: see detail/fast_math.hpp.
#include "stickslip/detail/fast_math.hpp"

#include "stickslip/detail/fast_math_simd.hpp"

namespace stickslip::detail::fm {
namespace {
namespace hn = hwy::HWY_NAMESPACE;
using simd::dtag;
}  // namespace

double log(double x) noexcept {
  const dtag d;
  return hn::GetLane(simd::log(d, hn::Set(d, x)));
}
double atan(double x) noexcept {
  const dtag d;
  return hn::GetLane(simd::atan(d, hn::Set(d, x)));
}
double atan2(double y, double x) noexcept {
  const dtag d;
  return hn::GetLane(simd::atan2(d, hn::Set(d, y), hn::Set(d, x)));
}
double sin(double x) noexcept {
  const dtag d;
  return hn::GetLane(simd::sin(d, hn::Set(d, reduce_phase(x))));
}
double cos(double x) noexcept {
  const dtag d;
  return hn::GetLane(simd::cos(d, hn::Set(d, reduce_phase(x))));
}

void log_inplace(double* p, std::size_t n) noexcept {
  const dtag d;
  const std::size_t N = hn::Lanes(d);
  std::size_t i = 0;
  for (; i + N <= n; i += N) hn::StoreU(simd::log(d, hn::LoadU(d, p + i)), d, p + i);
  for (; i < n; ++i) p[i] = log(p[i]);
}

const char* target_name() noexcept {
#if HWY_TARGET == HWY_AVX2
  return "avx2+fma";
#else
  return hwy::TargetName(HWY_TARGET);
#endif
}

}  // namespace stickslip::detail::fm
