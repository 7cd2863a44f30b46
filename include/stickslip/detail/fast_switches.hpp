// Belt switch times drawn in batches: the same values, bit for bit, as
// poisson_switches (same Philox blocks, same u01fixedpt, same log, same
// running sum), but produced CHUNK at a time so that the Philox rounds and the
// logs of a chunk overlap in the pipeline instead of waiting on the integrator.
#pragma once
#include <array>
#include <cmath>
#include <cstdint>

#include "stickslip/detail/fast_math.hpp"
#include "stickslip/random_stream.hpp"

namespace stickslip::detail {

class batched_poisson_switches {
 public:
  static constexpr int blocks_per_chunk = 8;  // 32 switch times per refill
  static constexpr int chunk = 4 * blocks_per_chunk;

  batched_poisson_switches(double rate, std::uint64_t seed, std::uint64_t point,
                           std::uint64_t realization) noexcept
      : mean_wait_(1.0 / rate), rs_(seed, point, realization, substream::belt_switches) {}

  [[nodiscard]] double next() noexcept {
    if (i_ == chunk) refill();
    return times_[i_++];
  }

 private:
  void refill() noexcept {
    std::array<double, chunk> w;
    for (int b = 0; b < blocks_per_chunk; ++b) {
      const auto blk = rs_.next_block();
      for (int j = 0; j < 4; ++j) w[4 * b + j] = random_stream::open_uniform(blk.v[j]);
    }
    fm::log_inplace(w.data(), chunk);  // the same kernel as poisson_switches
    for (int j = 0; j < chunk; ++j) w[j] = -w[j] * mean_wait_;
    for (int j = 0; j < chunk; ++j) times_[j] = time_ += w[j];  // same order as poisson_switches
    i_ = 0;
  }

  double mean_wait_;
  double time_ = 0.0;
  random_stream rs_;
  std::array<double, chunk> times_{};
  int i_ = chunk;
};

}  // namespace stickslip::detail
