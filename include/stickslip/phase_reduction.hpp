// The phase reduction before the engines' sine and cosine (fast_math.hpp and
// their vector forms, src/core/engines/fast_math_simd.hpp).
#pragma once
#include <cmath>
#include <numbers>

namespace stickslip::detail::fm {

// Highway's Sin/Cos are valid for |x| <= 39000: larger phases are reduced
// first with fmod by the double nearest 2 pi (fmod itself is exact; the
// rounding of 2 pi shifts such huge phases slightly). Both engines apply this.
inline constexpr double max_direct_phase = 39000.0;
[[nodiscard]] inline double reduce_phase(double x) noexcept {
  return std::abs(x) > max_direct_phase ? std::fmod(x, 2.0 * std::numbers::pi) : x;
}

}  // namespace stickslip::detail::fm
