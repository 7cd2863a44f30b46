// One realization's motion as samples for plotting: the closed-form segments
// (episode.hpp) evaluated on the grid t = k * step and at both ends of every
// segment, so every event instant (jumps of v, corners of x') is drawn
// exactly. The one trajectory sampler: `simulate --trajectory` and Fig. 2 of
// the paper study both use it.
#pragma once
#include <limits>
#include <span>
#include <vector>

#include "stickslip/episode.hpp"
#include "stickslip/observer.hpp"

namespace stickslip {

struct trajectory_sample {
  double time;
  double position;       // x
  double velocity;       // x'
  double belt_velocity;  // v
  mode kind;             // stick or slip during the segment sampled
};

// Keeps every closed-form segment the integrator reports.
struct segment_recorder : observer_base {
  std::vector<segment> segments;
  void on_segment(const segment& s) { segments.push_back(s); }
};

// Samples of `segments` (in time order, tiling [0, t_a]) up to `t_end`:
// for each segment its start, every k * step strictly inside it, and its end
// (when the segment has positive length). Precondition: step > 0.
[[nodiscard]] std::vector<trajectory_sample> sample_trajectory(
    std::span<const segment> segments, double step,
    double t_end = std::numeric_limits<double>::infinity());

}  // namespace stickslip
