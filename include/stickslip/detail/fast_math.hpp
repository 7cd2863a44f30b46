// The transcendental kernels of the integrator and of the belt switch draws,
// shared by every engine so that they give bit-identical results.
//
// All of them are Highway's vector polynomials (hwy/contrib/math), evaluated
// with one static target (AVX2 + FMA where the build enables it, see
// src/core/CMakeLists.txt, STICKSLIP_SIMD_AVX2). The scalar functions below
// broadcast their argument to a whole vector and return lane 0; the lane
// engine (src/core/fast_lanes.cpp) evaluates the very same kernels on 4
// realizations at once. Highway's math is lane-wise (no cross-lane step), so
// a lane's result does not depend on its neighbours: the engines agree bit
// for bit. Accuracy: a few ulp (Highway's documented bounds; atan2 adds the
// rounding of one division), far below anything the statistics resolve.
//
// These functions are out of line on purpose: they are compiled in exactly
// one translation unit with the target flags, whatever the flags of the
// caller, so no caller can get a differently rounded copy.
#pragma once
#include <cmath>
#include <cstddef>
#include <numbers>

namespace stickslip::detail::fm {

[[nodiscard]] double log(double x) noexcept;             // x > 0
[[nodiscard]] double atan(double x) noexcept;
[[nodiscard]] double atan2(double y, double x) noexcept;  // not both zero
[[nodiscard]] double sin(double x) noexcept;
[[nodiscard]] double cos(double x) noexcept;
// p[i] = log(p[i]) for i < n, the same values as log() (vectorized).
void log_inplace(double* p, std::size_t n) noexcept;

// Highway's Sin/Cos are valid for |x| <= 39000: larger phases are reduced
// first with fmod by the double nearest 2 pi (fmod itself is exact; the
// rounding of 2 pi shifts such huge phases slightly). Both engines apply this.
inline constexpr double max_direct_phase = 39000.0;
[[nodiscard]] inline double reduce_phase(double x) noexcept {
  return std::abs(x) > max_direct_phase ? std::fmod(x, 2.0 * std::numbers::pi) : x;
}

// Which instruction set the kernels were compiled for: "AVX3" (AVX-512),
// "avx2+fma", or Highway's name of the baseline target. "AVX3" and
// "avx2+fma" give the same bits (tests/unit/test_reproducible_bits.cpp);
// otherwise results are reproducible between builds with the same value.
[[nodiscard]] const char* target_name() noexcept;

}  // namespace stickslip::detail::fm
