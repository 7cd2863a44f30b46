// Sources of belt switch times. A source yields non-decreasing times through
// next(); +infinity means "no more switches". Given lists are validated to be
// strictly increasing; a Poisson sum can repeat a time only when W rounds to
// 0 against Y (probability ~1e-16 per draw). The two flips then cancel at one
// instant; no zero-length episode is reported, but a stick in progress is
// counted as two sticks that meet at that instant.
//   poisson_switches: W_j ~ Exp(lambda) i.i.d., Y_j = W_1 + ... + W_j (paper, Sec. 3).
//   given_switches:   a replayed, measured or hand-made list.
#pragma once
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>

#include "stickslip/fast_math.hpp"
#include "stickslip/random_stream.hpp"

namespace stickslip {
namespace detail {

// next_refilled_by of every switch source: the next of the chunk's
// `waits`, after refill_chunk(source) when all were handed out (it must
// call the source's refill_with, which sets `i` back to 0).
template <class Source, std::size_t Chunk, class RefillChunk>
[[gnu::always_inline]] inline double next_wait_of_chunk(Source& source, int& i,
                                                        const std::array<double, Chunk>& waits,
                                                        RefillChunk& refill_chunk) noexcept {
  if (i == static_cast<int>(Chunk)) [[unlikely]] {
    refill_chunk(source);
    assert(i == 0 && "refill_chunk must call refill_with");
  }
  return waits[static_cast<std::size_t>(i++)];
}

}  // namespace detail

// The one Poisson switch source of every engine. Inverse-transform
// exponential: W_j = -log(U_j) / lambda, U_j = u01fixedpt of the j-th 64-bit
// word of the realization's belt-switch substream (on (0, 1)), and
// Y_j = Y_{j-1} + W_j, summed in order. The waits are drawn `chunk` at a
// time, the Philox rounds and the logs on whole vectors of blocks
// (fm::log_uniforms); the values do not depend on this (every word is a
// function of its counter alone, and the log kernel is lane-wise). The sum
// is taken as the times are handed out, one addition each: the same
// additions in the same order as a sum over the chunk, without its chain
// of `chunk` dependent additions in every refill.
class poisson_switches {
 public:
  static constexpr int blocks_per_chunk = 8;        // Philox blocks per refill
  static constexpr int chunk = 4 * blocks_per_chunk;  // switch times per refill

  poisson_switches(double rate, std::uint64_t seed, std::uint64_t point,
                   std::uint64_t realization) noexcept
      : mean_wait_(1.0 / rate), rs_(seed, point, realization, substream::belt_switches) {}
  // A placeholder (rate 1, seed 0) to be assigned a real source later.
  poisson_switches() noexcept : poisson_switches(1.0, 0, 0, 0) {}

  // The next switch time, refilled with the shared draw kernel dispatched
  // to the SIMD target of the CPU (detail::fm::log_uniforms), out of line
  // once per chunk.
  [[nodiscard]] double next() noexcept {
    if (i_ == chunk) [[unlikely]] refill();
    return time_ += waits_[i_++];
  }

  // The same values again, refilled by refill_chunk(*this), which calls
  // refill_with: the lane engine passes a function compiled for its SIMD
  // target, into which the refill (the Philox rounds, the conversion to
  // doubles, the log, the waits) is inlined and compiled for that target
  // too. log_uniforms(rs, w, blocks) is fm::log_uniforms or the same kernel
  // of the caller's target.
  // refill_chunk must call refill_with exactly once; refill_with is for
  // that call only (it drops the unread waits of the chunk). The wait and
  // the sum are a product and a separate addition, never fused: the core
  // compiles with -ffp-contract=off and passes it to every target that
  // links it (src/core/CMakeLists.txt).
  template <class RefillChunk>
  [[nodiscard, gnu::always_inline]] double next_refilled_by(RefillChunk&& refill_chunk) noexcept {
    return time_ += detail::next_wait_of_chunk(*this, i_, waits_, refill_chunk);
  }
  template <class LogUniforms>
  [[gnu::always_inline]] void refill_with(LogUniforms& log_uniforms) noexcept {
    log_uniforms(rs_, waits_.data(), std::size_t{blocks_per_chunk});
    for (int j = 0; j < chunk; ++j) waits_[j] = -waits_[j] * mean_wait_;
    i_ = 0;
  }

 private:
  [[gnu::noinline]] void refill() noexcept { refill_with(detail::fm::log_uniforms); }

  double mean_wait_;
  double time_ = 0.0;  // the last time handed out
  random_stream rs_;
  int i_ = chunk;
  alignas(64) std::array<double, chunk> waits_{};  // W_j of the chunk
};

// The switch times of a two-level Markov belt, the same bits as
// markov_level_switches (model/belt_chain.hpp) with two levels: W_j =
// -log(U_j) * m_j, m_j the mean wait (1 / q_i) of the level switch j
// (counted from 0) leaves: the start level's for even j, the other level's
// for odd j, the same words of the same substream in the same order, the
// running sum in the same order. Drawn `chunk` at a time like
// poisson_switches (chunk is even, so every refill starts on the start
// level). The lane engine's source for such belts.
class two_level_switch_times {
 public:
  static constexpr int blocks_per_chunk = poisson_switches::blocks_per_chunk;
  static constexpr int chunk = poisson_switches::chunk;
  static_assert(chunk % 2 == 0);

  two_level_switch_times(double mean_wait_start, double mean_wait_other, std::uint64_t seed,
                         std::uint64_t point, std::uint64_t realization) noexcept
      : mean_wait_{mean_wait_start, mean_wait_other},
        rs_(seed, point, realization, substream::belt_switches) {}
  two_level_switch_times() noexcept : two_level_switch_times(1.0, 1.0, 0, 0, 0) {}

  // As poisson_switches::next_refilled_by and refill_with (the lane engine
  // is this source's only user).
  template <class RefillChunk>
  [[nodiscard, gnu::always_inline]] double next_refilled_by(RefillChunk&& refill_chunk) noexcept {
    return time_ += detail::next_wait_of_chunk(*this, i_, waits_, refill_chunk);
  }
  template <class LogUniforms>
  [[gnu::always_inline]] void refill_with(LogUniforms& log_uniforms) noexcept {
    log_uniforms(rs_, waits_.data(), std::size_t{blocks_per_chunk});
    const double m0 = mean_wait_[0], m1 = mean_wait_[1];
    for (int j = 0; j < chunk; j += 2) {
      waits_[j] = -waits_[j] * m0;
      waits_[j + 1] = -waits_[j + 1] * m1;
    }
    i_ = 0;
  }

 private:
  double mean_wait_[2];
  double time_ = 0.0;  // the last time handed out
  random_stream rs_;
  int i_ = chunk;
  alignas(64) std::array<double, chunk> waits_{};  // W_j of the chunk
};

class given_switches {
 public:
  // Preconditions (checked by validate_switch_times at the edge): finite,
  // >= 0, strictly increasing.
  explicit given_switches(std::span<const double> times) noexcept : times_(times) {}
  [[nodiscard]] double next() noexcept {
    return i_ < times_.size() ? times_[i_++] : std::numeric_limits<double>::infinity();
  }

 private:
  std::span<const double> times_;
  std::size_t i_ = 0;
};

// Throws stickslip::error naming the first offending entry.
void validate_switch_times(std::span<const double> times);

}  // namespace stickslip
