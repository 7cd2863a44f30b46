#include "stickslip/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace stickslip {

std::vector<trajectory_sample> sample_trajectory(std::span<const segment> segments, double step,
                                                 double t_end) {
  std::vector<trajectory_sample> out;
  auto sample = [&](const segment& s, double t) {
    const auto p = evaluate(s, t);
    out.push_back({t, p.position, p.velocity, s.belt_velocity, s.kind});
  };
  for (const auto& s : segments) {
    if (s.start >= t_end) break;
    const double end = std::min(s.end, t_end);
    sample(s, s.start);
    // Grid instants k * step with start < t < end (k counted, not summed,
    // so the grid does not drift).
    for (auto k = static_cast<std::uint64_t>(std::floor(s.start / step)) + 1;; ++k) {
      const double t = static_cast<double>(k) * step;
      if (t >= end) break;
      if (t > s.start) sample(s, t);
    }
    if (end > s.start) sample(s, end);
  }
  return out;
}

}  // namespace stickslip
