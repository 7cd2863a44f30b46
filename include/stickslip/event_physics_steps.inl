// The closed-form steps and the decisions of one event as templates over the
// number type: the body of event_physics.hpp. No include guard and no
// namespace on purpose: event_physics.hpp includes it into
// stickslip::detail::physics (doubles and bools, for `simulate` and
// `simulate_model`), and src/core/engines/fast_lanes.cpp includes it once more
// inside each SIMD target's namespace, so that the vector instantiations are
// compiled for that target (Highway's vector operators can only be inlined
// into code of their own target). One text, so one order of operations, so
// the same bits. Only + - * /, Neg() and the comparisons, mask logic and
// selections of Highway's names (double: the shims of event_physics.hpp;
// vectors: Highway's own, by argument-dependent lookup).

// Stick at x with belt velocity v = s V: it reaches the band edge x = s a at
// t + (a - s x) / V.
template <class Num>
[[nodiscard]] inline Num stick_edge_time(Num t, Num a, Num s, Num x, Num V) noexcept {
  return t + (a - s * x) / V;
}

// ---- decisions ----
// A decision is a mask: a bool for double (the shims of event_physics.hpp),
// Highway's mask for vectors, one bit per realization. Comparisons and
// selections are exact, so a decision taken lane-wise is the scalar one.
// The constants of the decisions, as numbers of the type (Set() for vectors).
template <class Num>
struct decision_constants {
  Num zero, one, minus_one, two, pi, two_pi, minus_half_pi;
  // decide_contact's bound for a stick whose break may round to its onset:
  // a gap over |v| t near (2^-49, far above half an ulp of t) cannot; below
  // t = tiny (2^-900) that bound underflows and the gap is always checked.
  Num near, tiny;
};

// Relative rest x' = v reached at time t and position x by a slip of
// direction from_sigma, with the stick band |x - b| <= a and belt velocity v:
// on the band's side (x - b >= -a for sigma = +1, x - b <= a for -1) the
// mass sticks at x clamped to the band, except where that stick would have
// no length: on the outward edge a - sgn(v) (x - b) <= 0, or so close to it
// that the stick's break time t + (a - sgn(v) (x - b)) / |v| rounds to t.
// There it only touches x' = v (`grazing`) and leaves from the edge
// (x = b + sgn(v) a, sigma = sgn v, the state the stick's break would
// leave): a touch of x' = v for no representable time is not a stick, so no
// onset, no break and no stick episode of zero length between two slips. At
// v = 0 the band has no outward edge. Beyond the band's side the slip
// reverses (sigma = -from_sigma, x unchanged).
// `at_root`: where the break time may need checking (lanes that reach a
// root this round; true for a scalar); `any(mask)`: whether some lane of
// the mask is set, so that the division runs only when some lane needs it.
template <class Num, class Bool>
struct contact_decision {
  Bool stick, grazing, reversal;  // exactly one holds
  Num x, sigma;                   // the state after the contact
};
// The band's centre b: a number, or band_at_zero for b = 0 (the paper's
// model and the undamped family), which costs no operation (x - 0 and 0 + y
// are x and y, bit for bit, for the nonzero y they are used with: -a and
// s a, nonzero since validation holds a_s >= 1e-60).
struct band_at_zero {};
template <class Num>
[[nodiscard]] inline Num minus_centre(Num x, Num b) noexcept {
  return x - b;
}
template <class Num>
[[nodiscard]] inline Num minus_centre(Num x, band_at_zero) noexcept {
  return x;
}
template <class Num>
[[nodiscard]] inline Num plus_centre(Num b, Num y) noexcept {
  return b + y;
}
template <class Num>
[[nodiscard]] inline Num plus_centre(band_at_zero, Num y) noexcept {
  return y;
}
// MayRest: whether v can be 0 (a resting belt level; false for the paper).
template <bool MayRest, class Num, class Centre, class Bool, class Any>
[[nodiscard]] inline contact_decision<Num, Bool> decide_contact(
    Num t, Num x, Num from_sigma, Num v, Num a, Centre b, Bool at_root,
    const decision_constants<Num>& k, Any any) noexcept {
  const Num u = minus_centre(x, b);
  const Num minus_a = Neg(a);
  const auto up = Gt(from_sigma, k.zero);
  const auto inside = Or(And(up, Ge(u, minus_a)), AndNot(up, Le(u, a)));
  const Num xc = Min(Max(x, plus_centre(b, minus_a)), plus_centre(b, a));
  const Num s = IfThenElse(Gt(v, k.zero), k.one, k.minus_one);
  const Num speed = Abs(v);
  const Num uc = minus_centre(xc, b);
  const Num gap = a - s * uc;
  auto no_length = Le(gap, k.zero);
  const auto near = And(at_root, Or(Le(gap, speed * (t * k.near)), Lt(t, k.tiny)));
  if (any(AndNot(no_length, near)))
    no_length = Or(no_length, And(near, Le(stick_edge_time(t, a, s, uc, speed), t)));
  if constexpr (MayRest) no_length = AndNot(Eq(v, k.zero), no_length);
  const auto grazing = And(no_length, inside);
  return {AndNot(no_length, inside), grazing, Not(inside),
          IfThenElse(inside, IfThenElse(grazing, plus_centre(b, s * a), xc), x),
          IfThenElse(inside, IfThenElse(grazing, s, from_sigma), Neg(from_sigma))};
}

// The phase run to the root from the raw atan2 of root_angle_arguments
// (integrator.hpp, detail::root_angle): put in [0, 2 pi), except that a
// small negative angle is rounding at the root itself, and means 0, where
// the run is shorter than pi: when the whole sigma region is (sigma v <= 0)
// or the start lies on the root's half of it (w y r > 0).
template <class Num>
[[nodiscard]] inline Num root_angle_from_raw(Num raw, Num wy, Num v, Num sigma, Num r,
                                             const decision_constants<Num>& k) noexcept {
  const auto rounding_at_root =
      And(Or(Le(sigma * v, k.zero), Gt(wy * r, k.zero)), Gt(raw, k.minus_half_pi));
  return IfThenElse(Ge(raw, k.zero), raw, IfThenElse(rounding_at_root, k.zero, raw + k.two_pi));
}

// The phase run of a slip that starts at a reversal (integrator.hpp,
// detail::reversal_arc_angle), from alpha = atan2(|w y|, v): the whole arc
// of the new sigma region up to its other root.
template <class Num>
[[nodiscard]] inline Num reversal_arc_from_alpha(Num alpha, Num sigma,
                                                 const decision_constants<Num>& k) noexcept {
  const Num two_alpha = k.two * alpha;
  return IfThenElse(Gt(sigma, k.zero), k.two_pi - two_alpha, two_alpha);
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
