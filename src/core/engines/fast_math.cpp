// Scalar entry points of the shared kernels, dispatched at run time to the
// SIMD target of the CPU: see stickslip/fast_math.hpp. This file is compiled
// once per Highway target (foreach_target.h re-includes it).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engines/fast_math.cpp"  // src/core is on the core's include path
#include <hwy/foreach_target.h>  // must come before highway.h

#include <hwy/highway.h>

#include "stickslip/fast_math.hpp"
#include "engines/fast_math_simd.hpp"

HWY_BEFORE_NAMESPACE();
namespace stickslip::detail::fm {
namespace HWY_NAMESPACE {
namespace sk = simd::HWY_NAMESPACE;

double Log(double x) { return sk::log1(x); }
double Atan(double x) { return sk::atan1(x); }
double Atan2(double y, double x) { return sk::atan21(y, x); }
double Sin(double x) { return sk::sin1(x); }
double Cos(double x) { return sk::cos1(x); }
void LogUniforms(random_stream& rs, double* w, std::size_t blocks) { sk::log_uniforms(rs, w, blocks); }
std::int64_t Target() { return HWY_TARGET; }

}  // namespace HWY_NAMESPACE
}  // namespace stickslip::detail::fm
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stickslip::detail::fm {

HWY_EXPORT(Log);
HWY_EXPORT(Atan);
HWY_EXPORT(Atan2);
HWY_EXPORT(Sin);
HWY_EXPORT(Cos);
HWY_EXPORT(LogUniforms);
HWY_EXPORT(Target);

double log(double x) noexcept { return HWY_DYNAMIC_DISPATCH(Log)(x); }
double atan(double x) noexcept { return HWY_DYNAMIC_DISPATCH(Atan)(x); }
double atan2(double y, double x) noexcept { return HWY_DYNAMIC_DISPATCH(Atan2)(y, x); }
double sin(double x) noexcept { return HWY_DYNAMIC_DISPATCH(Sin)(x); }
double cos(double x) noexcept { return HWY_DYNAMIC_DISPATCH(Cos)(x); }
void log_uniforms(random_stream& rs, double* w, std::size_t blocks) noexcept {
  HWY_DYNAMIC_DISPATCH(LogUniforms)(rs, w, blocks);
}

std::int64_t target() noexcept { return HWY_DYNAMIC_DISPATCH(Target)(); }
const char* target_name() noexcept { return hwy::TargetName(target()); }
bool target_fuses_multiply_add() noexcept {
  const std::int64_t t = target();
  return t == HWY_AVX2 || t == HWY_AVX3 || t == HWY_AVX3_DL;
}

}  // namespace stickslip::detail::fm
#endif  // HWY_ONCE
