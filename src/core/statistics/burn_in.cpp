#include "stickslip/burn_in.hpp"

#include "stickslip/episode.hpp"
#include "stickslip/model/oscillator_model.hpp"

namespace stickslip {

burn_in_cut::burn_in_cut(const model_parameters& p, double burn_in) : from_(burn_in) {
  if (!active()) return;
  const oscillator_model m = model_of(p);
  kinetic_offset_ = m.kinetic_offset();
  omega_ = m.natural_frequency();
  decay_rate_ = m.decay_rate();
}

motion_piece burn_in_cut::after(const motion_piece& p) const noexcept {
  // A slip's centre is sigma a_k (model_engine.hpp); a stick moves with v.
  const double centre = p.kind == mode::slip ? p.sigma * kinetic_offset_ : 0.0;
  const segment s{p.kind, p.start_time, p.end_time, p.start_position, p.start_velocity,
                  p.belt_velocity, centre, omega_, decay_rate_};
  const phase_point at = evaluate(s, from_);
  motion_piece cut = p;
  cut.duration = p.end_time - from_;
  cut.start_time = from_;
  cut.start_position = at.position;
  cut.start_velocity = p.kind == mode::slip ? at.velocity : p.belt_velocity;
  return cut;
}

}  // namespace stickslip
