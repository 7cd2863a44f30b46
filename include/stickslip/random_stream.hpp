// Counter-based random streams (Random123 Philox4x64-10). Every draw is a pure
// function of (seed, grid point, realization, substream, draw index):
//   key     = { seed, point_key(parameters) }
//   counter = { realization, substream, draw_index / 4, 0 }
// so a realization can be replayed alone, and no result depends on threads,
// ranks, scheduling or on which other realizations were drawn.
#pragma once
#include <Random123/philox.h>
#include <Random123/uniform.hpp>

#include <cmath>
#include <cstdint>

#include "stickslip/parameters.hpp"

namespace stickslip {

// Every substream in one place, so that no two uses can collide; the
// numbers are part of every result's bits and never change.
enum class substream : std::uint64_t {
  initial_conditions = 0,
  belt_switches = 1,
  belt_levels = 2,           // the Markov belt's next-level draws (model/belt_chain.hpp)
  uncertain_parameters = 3   // uncertain parameters' uniforms (uncertainty/uncertain_draws.hpp)
};

// A 64-bit identity of a grid point: a hash of the bit patterns of its model
// parameters, so the same physical point gets the same streams in any sweep
// and in `simulate`.
[[nodiscard]] std::uint64_t point_key(const model_parameters& p) noexcept;

// The key every grid point uses instead of point_key with common random
// numbers (sweep_spec::common_random_numbers, `--common-random-numbers`):
// realization r of every point then draws the same initial conditions and the
// same unit-rate exponentials E_j = -log(U_j) (switch times Y_j = sum E_i /
// lambda), so differences between points have low variance while each point
// stays exact and unbiased. The constant is "CRN" in ASCII, fixed forever:
// changing it changes every common-random-number result.
inline constexpr std::uint64_t common_stream_key = 0x43524EULL;

class random_stream {
 public:
  using philox = r123::Philox4x64;
  random_stream(std::uint64_t seed, std::uint64_t point, std::uint64_t realization,
                substream s) noexcept
      : key_{{seed, point}}, ctr_{{realization, static_cast<std::uint64_t>(s), 0, 0}} {}

  // Four fresh 64-bit words; advances the block counter. always_inline: the
  // SIMD lane engine (compiled per target) gets it inlined with its target.
  [[nodiscard, gnu::always_inline]] philox::ctr_type next_block() noexcept {
    auto r = philox{}(ctr_, key_);
    ++ctr_.v[2];
    return r;
  }
  // The key and the next block's counter, and a skip past `blocks` blocks:
  // for the vector Philox rounds of the switch draws (fm::log_uniforms),
  // which compute next_block's words for many counters at once.
  [[nodiscard]] const philox::key_type& key() const noexcept { return key_; }
  [[nodiscard]] const philox::ctr_type& counter() const noexcept { return ctr_; }
  void skip_blocks(std::uint64_t blocks) noexcept { ctr_.v[2] += blocks; }
  // Uniform on (0, 1): never 0 or 1, safe for log (see ECOSYSTEM.md).
  [[nodiscard]] static double open_uniform(std::uint64_t w) noexcept {
    return r123::u01fixedpt<double>(w);
  }

 private:
  philox::key_type key_;
  philox::ctr_type ctr_;
};

}  // namespace stickslip
