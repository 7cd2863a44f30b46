// The closed-form steps and the decisions of one event, written once over
// the number type (event_physics_steps.inl): `simulate` (integrator.hpp)
// and the reference engine of the family (`simulate_model`,
// model/model_engine.hpp) call them with double, the lane engine
// (src/core/engines/fast_lanes.cpp) with Highway vectors of realizations,
// so all three evaluate the same operations in the same order and round
// alike, bit for bit, and decide alike: the contact at x' = v
// (decide_contact: stick, grazing touch or reversal), the phase run to the
// root (root_angle_from_raw, reversal_arc_from_alpha). Derivations:
// integrator.hpp's header comment and docs/model.md. The mode at the start
// and the departure from the outward edge are scalar only (the lanes start
// a realization one lane at a time) and are written once below.
// tests/unit/test_fast_path_episodes.cpp and test_fast_path_family.cpp
// compare every episode and event field of the engines, by bit pattern.
#pragma once
#include <algorithm>
#include <cmath>
#include <numbers>

#include "stickslip/motion_mode.hpp"

namespace stickslip::detail::physics {

// The scalar forms of the vector operations the templates use: a decision
// is a bool, a selection the conditional operator. (Min and Max differ from
// Highway's on x86 only for a NaN operand, which validated inputs never
// give.)
[[nodiscard]] inline double Neg(double x) noexcept { return -x; }
[[nodiscard]] inline double Abs(double x) noexcept { return std::abs(x); }
[[nodiscard]] inline double Min(double x, double y) noexcept { return std::min(x, y); }
[[nodiscard]] inline double Max(double x, double y) noexcept { return std::max(x, y); }
[[nodiscard]] inline bool Gt(double x, double y) noexcept { return x > y; }
[[nodiscard]] inline bool Ge(double x, double y) noexcept { return x >= y; }
[[nodiscard]] inline bool Lt(double x, double y) noexcept { return x < y; }
[[nodiscard]] inline bool Le(double x, double y) noexcept { return x <= y; }
[[nodiscard]] inline bool Eq(double x, double y) noexcept { return x == y; }
[[nodiscard]] inline bool And(bool p, bool q) noexcept { return p && q; }
[[nodiscard]] inline bool Or(bool p, bool q) noexcept { return p || q; }
[[nodiscard]] inline bool AndNot(bool not_p, bool q) noexcept { return !not_p && q; }
[[nodiscard]] inline bool Not(bool p) noexcept { return !p; }
[[nodiscard]] inline double IfThenElse(bool p, double yes, double no) noexcept {
  return p ? yes : no;
}

#include "stickslip/event_physics_steps.inl"

inline constexpr decision_constants<double> scalar_constants{
    0.0, 1.0, -1.0, 2.0, std::numbers::pi, 2.0 * std::numbers::pi, -0.5 * std::numbers::pi,
    0x1p-49, 0x1p-900};

// ---- decisions, scalar ----

// The mode at t = 0 with the stick band |x - b| <= a (integrator.hpp
// header): x' = v inside the band starts a stick, except on the outward
// edge a - sgn(v) (x - b) <= 0 (v != 0: at rest the band has none), where
// the mass touches x' = v for no time and leaves the edge (edge_departure);
// x' = v outside the band starts a slip at a reversal (sigma = sgn(x - b));
// otherwise a slip with sigma = sgn(v - x').
struct start_mode {
  mode kind;
  double sigma;
  bool on_outward_edge, after_reversal;
};
// always_inline (also below): compiled into the lane engine with its target.
[[nodiscard, gnu::always_inline]] inline start_mode mode_at_start(double x, double z, double v,
                                                                 double a,
                                                                 double b = 0.0) noexcept {
  const double u = x - b;
  const bool on_outward_edge = v != 0.0 && a - (v > 0 ? u : -u) <= 0.0;
  if (z == v && std::abs(u) <= a && !on_outward_edge) return {mode::stick, 1.0, false, false};
  if (z == v && std::abs(u) <= a) return {mode::slip, v > 0 ? 1.0 : -1.0, true, false};
  if (z == v) return {mode::slip, u > 0 ? 1.0 : -1.0, false, true};
  return {mode::slip, v > z ? 1.0 : -1.0, false, false};
}

// A slip that leaves the outward band edge at x' = v (after a stick's
// break, or a touch of the edge) has sigma = sgn(v) and the relative
// acceleration sgn(v) (mu_k - mu_s) g. With mu_s = mu_k (the paper's model)
// that is 0: the orbit only grazes x' = v (undamped) or never returns
// (damped), so no contact is sought until the next belt switch (`grazing`).
// With mu_s > mu_k it leaves at once, and returns like a slip that starts at
// a reversal (`after_reversal`).
struct edge_departure {
  double sigma;
  bool grazing, after_reversal;
};
[[nodiscard, gnu::always_inline]] inline edge_departure leave_edge(double v,
                                                                  bool equal_friction) noexcept {
  return {v > 0 ? 1.0 : -1.0, equal_friction, !equal_friction};
}

// decide_contact for one realization (event_physics_steps.inl).
enum class contact_outcome : unsigned char { stick, grazing, reversal };
struct contact {
  contact_outcome outcome;
  double x, sigma;
};
[[nodiscard, gnu::always_inline]] inline contact resolve_contact(double t, double x,
                                                                 double from_sigma, double v,
                                                                 double a,
                                                                 double b = 0.0) noexcept {
  const auto c = decide_contact<true>(t, x, from_sigma, v, a, b, true, scalar_constants,
                                      [](bool p) { return p; });
  return {c.stick ? contact_outcome::stick
                  : c.grazing ? contact_outcome::grazing : contact_outcome::reversal,
          c.x, c.sigma};
}

}  // namespace stickslip::detail::physics
