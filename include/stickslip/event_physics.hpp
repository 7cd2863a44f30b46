// The closed-form steps of one event, written once over the number type
// (event_physics_steps.inl): `simulate` (integrator.hpp) calls them
// with double, the lane engine (src/core/engines/fast_lanes.cpp) with Highway vectors
// of realizations, so both evaluate the same operations in the same order and
// round alike, bit for bit. Only + - * / appear in them (Highway's vectors
// overload them for every x86 target); negation goes through Neg(), found for
// vectors by argument-dependent lookup in Highway's namespace. Derivations:
// integrator.hpp's header comment and docs/model.md. The decisions (the mode at the start,
// the contact resolution at x' = v) are written once for scalars, used by
// `simulate` and by the lane engine's scalar paths; the lane engine's vector
// step repeats the contact resolution and the choice of the root angle as
// masks and blends, for speed (branch-free lanes):
// tests/unit/test_fast_path_episodes.cpp compares every episode and event
// field of the two engines, by bit pattern.
#pragma once
#include <algorithm>
#include <cmath>

#include "stickslip/motion_mode.hpp"

namespace stickslip::detail::physics {

[[nodiscard]] inline double Neg(double x) noexcept { return -x; }

#include "stickslip/event_physics_steps.inl"

// ---- decisions, scalar ----

// The mode at t = 0 (integrator.hpp header): x' = v inside the band starts a
// stick, except on the outward edge (a grazing touch, no stick); x' = v
// outside the band starts a slip at a reversal (sigma = sgn x); otherwise a
// slip with sigma = sgn(v - x').
struct start_mode {
  mode kind;
  double sigma;
  bool grazing, after_reversal;
};
// always_inline (also below): compiled into the lane engine with its target.
[[nodiscard, gnu::always_inline]] inline start_mode mode_at_start(double x, double z, double v,
                                                                 double a) noexcept {
  const bool on_outward_edge = a - (v > 0 ? x : -x) <= 0.0;
  if (z == v && std::abs(x) <= a && !on_outward_edge) return {mode::stick, 1.0, false, false};
  if (z == v && std::abs(x) <= a) return {mode::slip, v > 0 ? 1.0 : -1.0, true, false};
  if (z == v) return {mode::slip, x > 0 ? 1.0 : -1.0, false, true};
  return {mode::slip, v > z ? 1.0 : -1.0, false, false};
}

// Relative rest x' = v reached at time t and position x by a slip of
// direction from_sigma: on the band's side (x >= -a for sigma = +1, x <= a
// for -1) the mass sticks at x clamped to the band, except where that stick
// would have no length: on the outward edge a - sgn(v) x <= 0, or so close to
// it that the stick's break time t + (a - sgn(v) x) / |v| rounds to t. There
// it only grazes (sigma = sgn v, x = sgn(v) a, the state the stick's break
// would leave): a touch of x' = v for no representable time is not a stick,
// so no onset, no break and no stick episode of zero length between two
// slips. Beyond the band's side the slip reverses (sigma = -from_sigma,
// x unchanged).
enum class contact_outcome : unsigned char { stick, grazing, reversal };
struct contact {
  contact_outcome outcome;
  double x, sigma;
};
[[nodiscard, gnu::always_inline]] inline contact resolve_contact(double t, double x,
                                                                 double from_sigma, double v,
                                                                 double a) noexcept {
  const bool inside = from_sigma > 0 ? x >= -a : x <= a;
  if (!inside) return {contact_outcome::reversal, x, -from_sigma};
  const double xc = std::clamp(x, -a, a);
  const double s = v > 0 ? 1.0 : -1.0;
  if (a - s * xc <= 0.0 || stick_edge_time(t, a, s, xc, std::abs(v)) <= t)
    return {contact_outcome::grazing, s * a, s};
  return {contact_outcome::stick, xc, from_sigma};
}

}  // namespace stickslip::detail::physics
