// The closed-form steps of one event as templates over the number type: the
// body of event_physics.hpp. No include guard and no namespace on
// purpose: event_physics.hpp includes it into stickslip::detail::physics
// (doubles, for `simulate`), and src/core/engines/fast_lanes.cpp includes it once more
// inside each SIMD target's namespace, so that the vector instantiations are
// compiled for that target (Highway's vector operators can only be inlined
// into code of their own target). One text, so one order of operations, so
// the same bits. Only + - * / and Neg() (double: physics::Neg; vectors:
// Highway's Neg by argument-dependent lookup).

// Stick at x with belt velocity v = s V: it reaches the band edge x = s a at
// t + (a - s x) / V.
template <class Num>
[[nodiscard]] inline Num stick_edge_time(Num t, Num a, Num s, Num x, Num V) noexcept {
  return t + (a - s * x) / V;
}

// Stick: x after sticking from t to t_end at belt velocity v.
template <class Num>
[[nodiscard]] inline Num stick_position(Num x, Num v, Num t, Num t_end) noexcept {
  return x + v * (t_end - t);
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
