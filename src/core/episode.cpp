#include "stickslip/episode.hpp"

#include <cmath>

#include "stickslip/model/damped_slip.hpp"

namespace stickslip {

phase_point evaluate(const segment& s, double t) noexcept {
  const double dt = t - s.start;
  if (s.kind == mode::stick) return {s.position + s.belt_velocity * dt, s.belt_velocity};
  const double y = s.position - s.center;
  if (s.decay_rate == 0.0) {
    const double c = std::cos(s.omega * dt), sn = std::sin(s.omega * dt);
    return {s.center + y * c + s.velocity / s.omega * sn, s.velocity * c - s.omega * y * sn};
  }
  const detail::damped_state d =
      detail::damped_oscillator(s.omega, s.decay_rate).advance(y, s.velocity, dt);
  return {s.center + d.y, d.velocity};
}

}  // namespace stickslip
