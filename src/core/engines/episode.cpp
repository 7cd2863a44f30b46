#include "stickslip/episode.hpp"

#include <cmath>

#include "stickslip/event_physics.hpp"
#include "stickslip/fast_math.hpp"
#include "stickslip/model/damped_slip.hpp"

namespace stickslip {

// The closed forms of the engines themselves: a stick moves at v
// (stick_position), an undamped slip rotates about its centre
// (rotated_position, rotated_velocity of event_physics.hpp) with the
// engines' own sine and cosine (fast_math.hpp), a damped one decays as
// model/damped_slip.hpp advances it. So the lane engine, which samples the
// observe times with the vector forms of the same kernels
// (evaluate_observed in fast_lanes.cpp), gets the same bits.
phase_point evaluate(const segment& s, double t) noexcept {
  namespace physics = detail::physics;
  const double dt = t - s.start;
  if (s.kind == mode::stick)
    return {physics::stick_position(s.position, s.belt_velocity, s.start, t), s.belt_velocity};
  const double y = s.position - s.center;
  if (s.decay_rate == 0.0) {
    const physics::slip_orbit<double> o{s.center, y, s.omega * y, 0.0};
    const double c = detail::fm::cos(s.omega * dt), sn = detail::fm::sin(s.omega * dt);
    return {physics::rotated_position(o, s.velocity, s.omega, c, sn),
            physics::rotated_velocity(o, s.velocity, c, sn)};
  }
  const detail::damped_state d =
      detail::damped_oscillator(s.omega, s.decay_rate).advance(y, s.velocity, dt);
  return {s.center + d.y, d.velocity};
}

}  // namespace stickslip
