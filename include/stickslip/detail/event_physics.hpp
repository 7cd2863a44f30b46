// The closed-form steps of one event, written once over the number type:
// `simulate` (integrator.hpp) calls them with double, the lane engine
// (src/core/fast_lanes.cpp) with Highway vectors of realizations, so both
// evaluate the same operations in the same order and round alike, bit for
// bit. Only + - * / appear here (Highway's vectors overload them for every
// x86 target); negation goes through Neg(), found for vectors by argument-
// dependent lookup in Highway's namespace. Derivations: integrator.hpp's
// header comment and docs/model.md. What depends on branches (the contact
// resolution, the choice of the root angle) stays written twice, as scalar
// branches and as vector masks, for speed: tests/unit/test_fast_path_episodes.cpp
// compares every episode and event field of the two.
#pragma once

namespace stickslip::detail::physics {

[[nodiscard]] inline double Neg(double x) noexcept { return -x; }

// Stick at x with belt velocity v = s V: it reaches the band edge x = s a at
// t + (a - s x) / V.
template <class Num>
[[nodiscard]] inline Num stick_edge_time(Num t, Num a, Num s, Num x, Num V) noexcept {
  return t + (a - s * x) / V;
}

// Slip with friction direction sigma about the centre c = sigma a:
// y = x - c, w y, and the discriminant B^2 - v^2 = (w y)^2 + (x' - v)(x' + v)
// of the relative-rest condition x' = v (B^2 = (w y)^2 + x'^2 is conserved).
template <class Num>
struct slip_orbit {
  Num c, y, wy, disc;
};
template <class Num>
[[nodiscard]] inline slip_orbit<Num> orbit_of(Num x, Num z, Num v, Num sigma, Num a,
                                              Num w) noexcept {
  const Num c = sigma * a;
  const Num y = x - c;
  const Num wy = w * y;
  return {c, y, wy, wy * wy + (z - v) * (z + v)};
}

// The slip after a phase run w dt (cs = cos(w dt), sn = sin(w dt)): (w y, x')
// rotates rigidly, x = c + y cos + (x'/w) sin, x' = x' cos - w y sin.
template <class Num>
[[nodiscard]] inline Num rotated_position(const slip_orbit<Num>& o, Num z, Num w, Num cs,
                                          Num sn) noexcept {
  return o.c + o.y * cs + z / w * sn;
}
template <class Num>
[[nodiscard]] inline Num rotated_velocity(const slip_orbit<Num>& o, Num z, Num cs,
                                          Num sn) noexcept {
  return z * cs - o.wy * sn;
}

// The root of the slip (x' = v): x_root = c - sigma sqrt(B^2 - v^2) / w.
template <class Num>
[[nodiscard]] inline Num root_position(const slip_orbit<Num>& o, Num sigma, Num sqrt_disc,
                                       Num w) noexcept {
  return o.c - sigma * sqrt_disc / w;
}

// The two arguments of the atan2 that gives the phase run to the root
// (integrator.hpp, root_angle): the cross and dot products of the start
// (x', w y) and the root (v, r), r = -sigma sqrt(B^2 - v^2).
template <class Num>
struct atan2_args {
  Num y, x;  // atan2(y, x)
};
template <class Num>
[[nodiscard]] inline Num root_ordinate(Num sigma, Num sqrt_disc) noexcept {
  return Neg(sigma) * sqrt_disc;
}
template <class Num>
[[nodiscard]] inline atan2_args<Num> root_angle_arguments(Num wy, Num z, Num v,
                                                          Num r) noexcept {
  return {z * r - wy * v, z * v + wy * r};
}

// Mirror return (integrator.hpp): from x' = -v back to x' = v on the orbit
// through w y; the phase run is pi - 2 atan(|w y| / |x'|).
template <class Num>
[[nodiscard]] inline Num mirror_return_from_atan(Num atan_ratio, Num pi, Num two) noexcept {
  return pi - two * atan_ratio;
}

// The time a phase run dtheta takes at angular frequency w.
template <class Num>
[[nodiscard]] inline Num time_after_phase(Num t, Num dtheta, Num w) noexcept {
  return t + dtheta / w;
}

}  // namespace stickslip::detail::physics
