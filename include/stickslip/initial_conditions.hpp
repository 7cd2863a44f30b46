// Initial state of one realization, and the law it is drawn from.
// Paper defaults: x0, x'0 independent uniform on [-1, 1]; belt direction +V or
// -V with equal odds.
#pragma once
#include <cstddef>
#include <cstdint>

#include "stickslip/random_stream.hpp"

namespace stickslip {

struct initial_conditions {
  double position = 0.0;  // x0  [m]
  double velocity = 0.0;  // x'0 [m/s]
  int belt_direction = 1; // +1 or -1: v(0) = belt_direction * V
};

struct initial_condition_law {
  double position_min = -1.0, position_max = 1.0;
  double velocity_min = -1.0, velocity_max = 1.0;
  int belt_start = 0;  // +1, -1, or 0 for random with equal odds
  friend bool operator==(const initial_condition_law&, const initial_condition_law&) = default;
};

// Throws stickslip::error on non-finite bounds (or |bound| > 1e60), min > max,
// or belt_start not in {-1,0,1}.
void validate(const initial_condition_law& law);
// initial_condition_law::belt_start (or a replay's fixed start) against a
// belt of `level_count` levels: +1 / -1 on two levels, a level number 1..n
// on more, and 0 (the stationary law) when `stationary_allowed`.
void validate_belt_start(int belt_start, std::size_t level_count, bool stationary_allowed);
// Throws on non-finite or |value| > 1e60 position/velocity, or belt not +-1.
void validate(const initial_conditions& ic);

// Draw from substream::initial_conditions: one Philox block gives x0, x'0 and
// the belt direction.
[[nodiscard]] inline initial_conditions draw_initial_conditions(
    const initial_condition_law& law, std::uint64_t seed, std::uint64_t point,
    std::uint64_t realization) noexcept {
  random_stream rs(seed, point, realization, substream::initial_conditions);
  const auto w = rs.next_block();
  const double u0 = random_stream::open_uniform(w.v[0]);
  const double u1 = random_stream::open_uniform(w.v[1]);
  initial_conditions ic;
  ic.position = law.position_min + (law.position_max - law.position_min) * u0;
  ic.velocity = law.velocity_min + (law.velocity_max - law.velocity_min) * u1;
  ic.belt_direction = law.belt_start != 0 ? law.belt_start : ((w.v[2] >> 63) ? 1 : -1);
  return ic;
}

// How records and outputs write a starting level: +1 / -1 on a two-level
// belt (first / second level, the paper's direction), the level number
// 1..n on a belt of more levels.
[[nodiscard]] inline int recorded_belt_start(std::size_t level, std::size_t level_count) noexcept {
  if (level_count == 2) return level == 0 ? 1 : -1;
  return static_cast<int>(level) + 1;
}
// The inverse: a recorded or requested belt start as a level index.
[[nodiscard]] inline std::size_t level_of_belt_start(int belt_start) noexcept {
  return belt_start == -1 ? 1 : static_cast<std::size_t>(belt_start - 1);
}

}  // namespace stickslip
