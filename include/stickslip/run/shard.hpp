// --shard i/n: one process of a job array runs the units whose index
// (point-major, as unit_at numbers them) is i modulo n, and only journals
// them; `stickslip merge` combines the shards (docs/scaling.md).
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "stickslip/sweep.hpp"

namespace stickslip::run {

struct shard {
  std::uint64_t index = 0, count = 1;
  [[nodiscard]] bool owns(const sweep_spec& s, const work_unit& u) const noexcept {
    return (u.point * blocks_per_point(s) + u.block) % count == index;
  }
  // Part of the journal's segment names: "shard-3-of-16".
  [[nodiscard]] std::string tag() const;
  // The shard whose tag a journal's run id starts with ("shard-3-of-16-..."),
  // or none (a whole run's).
  [[nodiscard]] static std::optional<shard> of_run(const std::string& run_id);
};

// "i/n" with 0 <= i < n <= 2^20; empty text: no shard. Throws invalid_input.
[[nodiscard]] std::optional<shard> parse_shard(const std::string& text);

}  // namespace stickslip::run
