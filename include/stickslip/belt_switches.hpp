// Sources of belt switch times. A source yields non-decreasing times through
// next(); +infinity means "no more switches". Given lists are validated to be
// strictly increasing; a Poisson sum can repeat a time only when W rounds to
// 0 against Y (probability ~1e-16 per draw). The two flips then cancel at one
// instant; no zero-length episode is reported, but a stick in progress is
// counted as two sticks that meet at that instant.
//   poisson_switches: W_j ~ Exp(lambda) i.i.d., Y_j = W_1 + ... + W_j (paper, Sec. 3).
//   given_switches:   a replayed, measured or hand-made list.
#pragma once
#include <cmath>
#include <limits>
#include <span>

#include "stickslip/detail/fast_math.hpp"
#include "stickslip/random_stream.hpp"

namespace stickslip {

class poisson_switches {
 public:
  poisson_switches(double rate, std::uint64_t seed, std::uint64_t point,
                   std::uint64_t realization) noexcept
      : mean_wait_(1.0 / rate), rs_(seed, point, realization, substream::belt_switches) {}

  // Inverse-transform exponential: W = -log(U)/lambda with U on (0,1).
  [[nodiscard]] double next() noexcept {
    if (left_ == 0) {
      block_ = rs_.next_block();
      left_ = 4;
    }
    const double u = random_stream::open_uniform(block_.v[4 - left_--]);
    time_ += -detail::fm::log(u) * mean_wait_;  // the shared kernel (fast_math.hpp)
    return time_;
  }

 private:
  double mean_wait_;
  double time_ = 0.0;
  random_stream rs_;
  random_stream::philox::ctr_type block_{};
  int left_ = 0;
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
