// The burn-in of a sweep (sweep_spec::burn_in, `sweep --burn-in T`): every
// window statistic counts only [T, t_a] (docs/outputs.md, "Burn-in"). The
// engines run the whole window [0, t_a] unchanged; the observer
// (realization_observer) and the lane engine cut what they are told at T:
//   an episode (stick or slip) or a piece of motion that ends at or before
//   T is left out; one that starts at or after T counts whole; one in
//   progress at T (start < T < end) counts from T and is left-truncated.
// This file holds the one cut of a piece of motion, shared by the scalar
// observer and the lanes, so that both give the same bits.
#pragma once
#include "stickslip/observer.hpp"
#include "stickslip/parameters.hpp"

namespace stickslip {

class burn_in_cut {
 public:
  burn_in_cut() = default;  // no burn-in
  // T = `burn_in` for the model p (its slip centre a_k, omega_0 and decay
  // rate gamma: the closed form of a piece, episode.hpp's segment).
  burn_in_cut(const model_parameters& p, double burn_in);
  [[nodiscard]] double time() const noexcept { return from_; }
  [[nodiscard]] bool active() const noexcept { return from_ > 0.0; }
  // The part of `p` after T: the state at T from the piece's closed form
  // (evaluate(segment), episode.cpp), the duration t_end - T.
  // Precondition: p.start_time < T < p.end_time.
  [[nodiscard]] motion_piece after(const motion_piece& p) const noexcept;

 private:
  double from_ = 0.0;
  double kinetic_offset_ = 0.0, omega_ = 0.0, decay_rate_ = 0.0;
};

}  // namespace stickslip
