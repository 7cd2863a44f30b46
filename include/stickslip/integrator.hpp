// Exact, event-driven integration of one realization. No time step and no
// tolerance: between events the motion has a closed form, and every event
// time is computed from it. Derivations: docs/model.md.
//
// Slip (friction direction sigma = sgn(v - x')):   x'' = -w^2 (x - sigma a)
//   Put y = x - c (c = sigma a). Then (w y, x') rotates rigidly at rate w:
//   x' = B cos(theta), w y = B sin(theta), theta = theta0 + w t,
//   B^2 = (w y)^2 + x'^2 is conserved.
//   Relative velocity zero (x' = v) at cos(theta) = v/B, i.e. theta = +-alpha,
//   alpha = acos(v/B) (computed as one atan2: detail::root_angle). It is reached iff B^2 - v^2 > 0 (B = |v| is a tangency,
//   which only happens at the outward band edge: the grazing contact, no stick).
//   sigma = +1 (x' < v) lives on theta in (alpha, 2pi - alpha) and meets -alpha;
//   sigma = -1 (x' > v) lives on (-alpha, alpha) and meets +alpha.
//   There w y = -+ sqrt(B^2 - v^2): x_root = c - sigma sqrt(B^2 - v^2)/w.
// Stick: x = x0 + v t with |x| <= a, ending at x = sgn(v) a after (a - sgn(v) x0)/V.
// At x' = v: |x| <= a starts a stick; otherwise the slip reverses (new sigma =
//   sgn(x)); consecutive roots of one orbit are mirror images x -> 2c - x.
// Mirror return: a belt switch that ends a stick at x leaves x' = -v (the old
//   belt velocity). The new orbit (about c = -s a, s = sgn(old v)) is symmetric
//   under time reversal about its turning point y' = 0, so it reaches x' = v
//   again at the SAME x after dtheta = pi - 2 atan(w |y| / |x'|) (from
//   theta0 = atan2(w y, x'), alpha = pi - |theta0|): a stick restarts at x.
//   Used by both engines (see detail::mirror_return_angle); exact, and x is
//   kept bit-for-bit instead of being recomputed from the conserved B.
// A stick that breaks at the band edge continues on the grazing orbit
//   x = sa + (V/w) sin(w t), which touches x' = v once per period for zero time
//   and never sticks again until the next belt switch (flag `grazing`).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "stickslip/event_physics.hpp"
#include "stickslip/fast_math.hpp"
#include "stickslip/engines/integration_counts.hpp"
#include "stickslip/episode.hpp"
#include "stickslip/observer.hpp"
#include "stickslip/error.hpp"
#include "stickslip/initial_conditions.hpp"
#include "stickslip/parameters.hpp"

namespace stickslip {

// The default bound on events per realization. Hitting it is reported as an
// error, never silently truncated.
inline constexpr std::int64_t default_max_events = 100'000'000;

namespace detail {

inline constexpr double two_pi = 2.0 * std::numbers::pi;

// Phase distance from `from` forward to `to`, reduced to [0, 2 pi).
[[nodiscard]] inline double forward_angle(double from, double to) noexcept {
  double d = std::fmod(to - from, two_pi);
  return d < 0.0 ? d + two_pi : d;
}

// Phase run from the point (x', w y) of the slip orbit forward to its root
// (v, r), r = -sigma sqrt(B^2 - v^2) = w (x_root - c) (header comment): one
// atan2 of the cross and dot products of the two points, put in [0, 2 pi).
// Precondition: the start is strictly inside the sigma region, sgn(v - x') =
// sigma. The run is shorter than pi when the whole region is (sigma v < 0:
// alpha >= pi/2 for sigma = +1, <= pi/2 for -1) or when the start lies on the
// root's half of the region (w y r > 0); there a small negative atan2 can only
// be rounding at the root itself and means 0. (It replaces acos(v/B) and
// atan2(w y, x') with fmod, and is better conditioned near grazing, B ~ |v|.)
// The two halves of root_angle: the lane engine evaluates the atan2 of
// several realizations in one vector call between the same two halves,
// instantiated for vectors (event_physics_steps.inl).
struct root_angle_args {
  double y, x;  // atan2(y, x)
};
[[nodiscard]] inline root_angle_args root_angle_arguments(double wy, double z, double v,
                                                          double sigma, double sqrt_disc) noexcept {
  const auto q = physics::root_angle_arguments(wy, z, v, physics::root_ordinate(sigma, sqrt_disc));
  return {q.y, q.x};
}
[[nodiscard]] inline double root_angle_from_raw(double raw, double wy, double v, double sigma,
                                                double sqrt_disc) noexcept {
  return physics::root_angle_from_raw(raw, wy, v, sigma, physics::root_ordinate(sigma, sqrt_disc),
                                      physics::scalar_constants);
}
[[nodiscard]] inline double root_angle(double wy, double z, double v, double sigma,
                                       double sqrt_disc) noexcept {
  const auto q = root_angle_arguments(wy, z, v, sigma, sqrt_disc);
  return root_angle_from_raw(fm::atan2(q.y, q.x), wy, v, sigma, sqrt_disc);
}

// Phase run of the mirror return (header comment): from x' = -v back to
// x' = v on the orbit through w y. Precondition: wy != 0, z = -v != 0.
[[nodiscard]] inline double mirror_return_ratio(double wy, double z) noexcept {
  return std::abs(wy) / std::abs(z);
}
[[nodiscard]] inline double mirror_return_from_atan(double atan_ratio) noexcept {
  return physics::mirror_return_from_atan(atan_ratio, std::numbers::pi, 2.0);
}
[[nodiscard]] inline double mirror_return_angle(double wy, double z) noexcept {
  return mirror_return_from_atan(fm::atan(mirror_return_ratio(wy, z)));
}

// Phase run of a slip that starts at a reversal (x' = v outside the band):
// the whole arc of the new sigma region up to its other root. With x' = v,
// B^2 = (w y)^2 + v^2, so the root half-angle alpha = acos(v / B) is
// atan2(|w y|, v): the same angle without the cancellation of acos near 1
// (reversals just outside the band edge) and with the shared kernel, not
// libm. Precondition: wy != 0 (B^2 - v^2 = (w y)^2 > 0).
// Split in two, like the mirror return: the lane engine takes the atan2 with
// its own target's kernel and the same second half, for vectors (the same
// bits).
[[nodiscard]] inline double reversal_arc_from_alpha(double alpha, double sigma) noexcept {
  return physics::reversal_arc_from_alpha(alpha, sigma, physics::scalar_constants);
}
[[nodiscard]] inline double reversal_arc_angle(double wy, double v, double sigma) noexcept {
  return reversal_arc_from_alpha(fm::atan2(std::abs(wy), v), sigma);
}

}  // namespace detail

template <class Switches, class Observer>
event_counts simulate(const model_parameters& p, const initial_conditions& ic,
                      Switches& switches, Observer& obs,
                      std::int64_t max_events = default_max_events) {
  detail::count_integration(integrator::paper);
  using detail::two_pi;
  const double a = p.band_half_width();
  const double w = p.natural_frequency();
  const double V = p.belt_speed;
  const double ta = p.window;
  constexpr double inf = std::numeric_limits<double>::infinity();

  event_counts counts;
  double t = 0.0, x = ic.position, z = ic.velocity;
  double v = ic.belt_direction >= 0 ? V : -V;
  double t_switch = switches.next();

  // The mode at t = 0, and how the slip started (integrator.hpp header).
  const auto start = detail::physics::mode_at_start(x, z, v, a);
  mode m = start.kind;
  double sigma = start.sigma;  // friction direction while slipping
  // on the grazing orbit: physics::leave_edge with mu_s = mu_k, the paper's
  bool grazing = start.on_outward_edge;
  bool after_reversal = start.after_reversal;
  bool mirror = false;       // slip started by a belt switch that ended a stick

  // Relative velocity zero (x' == v) reached by a slip of direction
  // from_sigma: a stick (reported), a grazing touch of the outward edge, or
  // a reversal (reported when count_reversal; a belt switch that lands
  // exactly on x' = v reverses without a slip reversal event).
  auto contact_at = [&](double from_sigma, bool count_reversal) {
    const auto c = detail::physics::resolve_contact(t, x, from_sigma, v, a);
    x = c.x;
    sigma = c.sigma;
    switch (c.outcome) {
      case detail::physics::contact_outcome::stick:
        m = mode::stick;
        return true;
      case detail::physics::contact_outcome::grazing:  // a zero-length stick
        m = mode::slip;
        grazing = true;
        return false;
      case detail::physics::contact_outcome::reversal:
        m = mode::slip;
        after_reversal = true;
        if (count_reversal) {
          ++counts.slip_reversals;
          obs.on_event(event{event_kind::slip_reversal, t, x, z, v});
        }
        return false;
    }
    return false;
  };

  // A piece of motion from the current state (observer.hpp): level 0 is +V.
  // `t_end`: where it ends (its duration t_end - t).
  auto piece = [&](mode kind, double t_end, double x0, double x1, double z0, double z1,
                   double sig) {
    if constexpr (takes_pieces<Observer>)
      obs.on_piece(motion_piece{kind, v > 0 ? std::size_t{0} : std::size_t{1}, t_end - t, x0, x1,
                                z0, z1, v, sig, t, t_end});
  };

  episode ep{m, 0.0, 0.0, x, v, false};
  // Zero-length episodes (only possible at t = 0: a belt switch at t = 0) are
  // no interval of either mode and are not reported.
  auto close_episode = [&](double when, mode next_mode) {
    ep.end = when;
    if (ep.end > ep.start) obs.on_episode(ep);
    ep = episode{next_mode, when, 0.0, x, v, false, static_cast<double>(counts.belt_switches)};
  };

  std::int64_t steps = 0;
  while (true) {
    if (++steps > max_events) throw work_bound_exceeded(steps, t, ta);

    if (m == mode::stick) {
      const double s = v > 0 ? 1.0 : -1.0;
      const double t_edge = detail::physics::stick_edge_time(t, a, s, x, V);
      const double t_next = std::min(t_edge, t_switch);
      obs.on_segment(segment{mode::stick, t, std::min(t_next, ta), x, v, v, 0.0, w});
      if (t_next >= ta) {
        const double x_end = detail::physics::stick_position(x, v, t, ta);
        piece(mode::stick, ta, x, x_end, v, v, 0.0);
        x = x_end;
        t = ta;
        break;
      }
      if (t_switch <= t_edge) {  // belt switch ends the stick
        const double x_end = std::clamp(detail::physics::stick_position(x, v, t, t_switch), -a, a);
        piece(mode::stick, t_switch, x, x_end, v, v, 0.0);
        x = x_end;
        z = v;
        t = t_switch;
        v = -v;
        sigma = -s;  // the belt now runs away from the mass: x' = old v, v = -old v
        m = mode::slip;
        grazing = after_reversal = false;
        mirror = true;
        ++counts.belt_switches;
        counts.switch_time_sum += t;
        obs.on_event(event{event_kind::belt_switch, t, x, z, v});
        close_episode(t, mode::slip);
        t_switch = switches.next();
      } else {  // stick breaks at the band edge; exact state, then grazing orbit
        piece(mode::stick, t_edge, x, s * a, v, v, 0.0);
        x = s * a;
        z = v;
        t = t_edge;
        sigma = s;
        m = mode::slip;
        grazing = true;
        after_reversal = mirror = false;
        ++counts.stick_breaks;
        obs.on_event(event{event_kind::stick_break, t, x, z, v});
        close_episode(t, mode::slip);
      }
      continue;
    }

    // --- slip ---
    const auto o = detail::physics::orbit_of(x, z, v, sigma, a, w);
    const double c = o.c, wy = o.wy, disc = o.disc;  // disc = B^2 - v^2
    double t_root = inf;
    if (!grazing && disc > 0.0) {
      // Arc of the current sigma region still to run before the root.
      double dtheta;
      if (mirror) {
        dtheta = detail::mirror_return_angle(wy, z);  // z == -v exactly here
      } else if (after_reversal) {  // we start on the region's first root: all of it
        dtheta = detail::reversal_arc_angle(wy, v, sigma);  // z == v exactly here
      } else {
        dtheta = detail::root_angle(wy, z, v, sigma, std::sqrt(disc));
      }
      t_root = detail::physics::time_after_phase(t, dtheta, w);
    }
    const double t_next = std::min(t_root, t_switch);
    obs.on_segment(segment{mode::slip, t, std::min(t_next, ta), x, z, v, c, w});
    if (t_next >= ta || t_switch <= t_root) {  // the slip runs to t_a or to a belt switch
      const double t_end = std::min(t_switch, ta);
      const double cs = detail::fm::cos(w * (t_end - t)), sn = detail::fm::sin(w * (t_end - t));
      const double x_end = detail::physics::rotated_position(o, z, w, cs, sn);
      const double z_end = detail::physics::rotated_velocity(o, z, cs, sn);
      piece(mode::slip, t_end, x, x_end, z, z_end, sigma);
      x = x_end;
      z = z_end;
      t = t_end;
      if (t_next >= ta) break;
      v = -v;  // belt switch during a slip
      grazing = after_reversal = mirror = false;
      ++counts.belt_switches;
      counts.switch_time_sum += t;
      obs.on_event(event{event_kind::belt_switch, t, x, z, v});
      t_switch = switches.next();
      if (z == v) {  // measure zero: landed exactly on relative rest
        if (contact_at(x > 0 ? -1.0 : 1.0, false)) {
          ++counts.stick_onsets;
          obs.on_event(event{event_kind::stick_onset, t, x, z, v});
          close_episode(t, mode::stick);
        }
      } else {
        sigma = v > z ? 1.0 : -1.0;
      }
      continue;
    }
    // Relative velocity reaches zero: x' = v, x from the conserved B (on a
    // mirror return x is where the stick ended, exactly).
    const double x_root = mirror ? x : detail::physics::root_position(o, sigma, std::sqrt(disc), w);
    piece(mode::slip, t_root, x, x_root, z, v, sigma);
    x = x_root;
    z = v;
    t = t_root;
    after_reversal = mirror = false;
    if (contact_at(sigma, true)) {
      ++counts.stick_onsets;
      obs.on_event(event{event_kind::stick_onset, t, x, z, v});
      close_episode(t, mode::stick);
    }
  }
  ep.end = ta;
  ep.censored = true;
  obs.on_episode(ep);
  return counts;
}

}  // namespace stickslip
