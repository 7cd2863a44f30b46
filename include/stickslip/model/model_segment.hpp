// One closed-form piece of motion of the model family between two events,
// as reported to observers by simulate_model (model_engine.hpp).
// Stick:  x(t) = x0 + v (t - t0), x' = v.
// Slip:   y = x - center (center = sigma a_k) obeys
//         y'' + 2 gamma y' + omega_0^2 y = 0 from (x0 - center, x0');
//         gamma = 0 is the paper's harmonic slip (episode.hpp, segment).
// Observers of the family take on_segment(const model_segment&);
// model_observer_base gives no-op defaults.
#pragma once
#include "stickslip/episode.hpp"

namespace stickslip {

struct model_segment {
  mode kind;
  double start, end;
  double position, velocity;  // x, x' at start
  double belt_velocity;       // v during the segment
  double center;              // sigma a_k while slipping (0 while sticking)
  double omega;               // omega_0 = sqrt(k/m)
  double decay_rate;          // gamma = c / 2m
};

// x, x' at time t (start <= t), from the closed form of docs/model.md.
[[nodiscard]] phase_point evaluate(const model_segment& s, double t) noexcept;

struct model_observer_base {
  void on_event(const event&) noexcept {}
  void on_segment(const model_segment&) noexcept {}
  void on_episode(const episode&) noexcept {}
};

}  // namespace stickslip
