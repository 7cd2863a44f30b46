// Two episode sequences agree when they have the same length and modes;
// then their largest boundary and start-position differences (shared by the
// paper's and the model family's oracle tests).
#pragma once
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "stickslip/episode.hpp"

namespace stickslip::reference {

struct difference {
  double time = 0, position = 0;
};
// Largest boundary and position differences, or nullopt if the sequences differ.
inline std::optional<difference> compare(const std::vector<episode>& exact,
                                         const std::vector<episode>& oracle) {
  if (exact.size() != oracle.size()) return std::nullopt;
  difference d;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    if (exact[i].kind != oracle[i].kind) return std::nullopt;
    d.time = std::max({d.time, std::abs(exact[i].start - oracle[i].start),
                       std::abs(exact[i].end - oracle[i].end)});
    d.position =
        std::max(d.position, std::abs(exact[i].position_at_start - oracle[i].position_at_start));
  }
  return d;
}

}  // namespace stickslip::reference
