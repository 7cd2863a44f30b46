// The transcendental kernels of the integrator and of the belt switch draws,
// shared by every engine so that they give bit-identical results.
//
// All of them are Highway's vector polynomials (hwy/contrib/math,
// src/core/engines/fast_math_simd.hpp), compiled once per SIMD target (AVX3 = AVX-512,
// AVX2, SSE4, SSSE3 and Highway's one-lane SCALAR baseline) with Highway's
// foreach_target.h, and chosen at run time (HWY_DYNAMIC_DISPATCH) for the
// CPU the program runs on: one binary runs on any x86-64 CPU. The scalar
// functions below broadcast their argument to a whole vector of the chosen
// target and return lane 0; the lane engine
// (src/core/engines/fast_lanes.cpp) is dispatched the same way and evaluates the very
// same kernels on whole vectors of realizations. Every dispatch in the
// process reads Highway's one chosen target, so the scalar integrator and the
// lane engine always run the same target, and Highway's math is lane-wise:
// the engines agree bit for bit.
//
// Targets with FMA (AVX3, AVX2) give the same bits (same polynomials, same
// fused multiply-adds); targets without it (SSE4, SSSE3, SCALAR) evaluate
// the same polynomials with separately rounded multiplies and adds, and give
// other (equally valid) bits, identical among themselves.
// tests/unit/test_reproducible_bits.cpp pins one digest per family and runs
// every compiled target. Accuracy: a few ulp (Highway's documented bounds;
// atan2 adds the rounding of one division), far below anything the
// statistics resolve.
//
// These functions are out of line on purpose: they are compiled in exactly
// one translation unit, whatever the flags of the caller, so no caller can
// get a differently rounded copy.
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>

#include "stickslip/phase_reduction.hpp"  // reduce_phase

namespace stickslip {
class random_stream;
}

namespace stickslip::detail::fm {

[[nodiscard]] double log(double x) noexcept;             // x > 0
[[nodiscard]] double atan(double x) noexcept;
[[nodiscard]] double atan2(double y, double x) noexcept;  // not both zero
[[nodiscard]] double sin(double x) noexcept;
[[nodiscard]] double cos(double x) noexcept;
// w[0 .. 4 * blocks) = log(random_stream::open_uniform(word)) of the words of
// the next `blocks` Philox blocks of rs, in order, and rs advanced past them:
// the belt's exponential waits, the same values as next_block, open_uniform
// and log() of each word (the Philox rounds vectorized across blocks).
void log_uniforms(random_stream& rs, double* w, std::size_t blocks) noexcept;

// The SIMD target the kernels and the lane engine run on now, as Highway's
// bit (HWY_AVX3, HWY_AVX2, ...) and name ("AVX3", "AVX2", "SSE4", "SSSE3",
// "SCALAR"). The journal fingerprint records the name. Tests may switch it
// with hwy::SetSupportedTargetsForTest.
[[nodiscard]] std::int64_t target() noexcept;
[[nodiscard]] const char* target_name() noexcept;
// Whether the target has fused multiply-adds (AVX3, AVX2): the family whose
// bits tests/unit/test_reproducible_bits.cpp pins as the paper's.
[[nodiscard]] bool target_fuses_multiply_add() noexcept;

}  // namespace stickslip::detail::fm
