// Exact, event-driven integration of one realization of the model family
// (oscillator_model.hpp; derivations in docs/model.md, "The model family"):
//
//   m x'' + c x' + k x = f,  slip: f = mu_k m g sgn(v - x'),
//   stick: x' = v while |k x + c v| <= mu_s m g,  v(t) a Markov chain.
//
// The same events, episodes and observer calls as simulate() (integrator.hpp),
// with segment for the pieces of motion. Write F = k x + c v (the force
// a stick needs) and b = -c v / k, so the stick band is |x - b| <= a_s.
//
// Stick at v != 0: x = x0 + v t until x - b = sgn(v) a_s (a break), or a belt
//   switch. At v = 0: until the next belt switch. A switch ends every stick:
//   the mass keeps x' = old v and slips against the new level.
// Slip with sigma = sgn(v - x'): harmonic about sigma a_k when c = 0 (the
//   paper's rotation, the same code and the same bits as simulate()), damped
//   otherwise (damped_slip.hpp: closed forms and certified root isolation).
// At x' = v: a stick if |F| <= mu_s m g, except where the stick would last
//   zero time: at the outward band edge (sgn(v) (x - b) = a_s, v != 0) or so
//   near it that its break time rounds to t; there the mass leaves from the
//   edge with sigma = sgn(v), like after a break. Otherwise the slip
//   reverses: sigma = sgn(F) (a slip_reversal).
// After a break (or an outward-edge touch) the relative acceleration is
//   x'' = sgn(v) (mu_k - mu_s) g. With mu_s = mu_k it is 0: the orbit only
//   grazes x' = v (undamped, docs/model.md) or never returns (damped: every
//   later extremum of x' is smaller in size), so no contact is sought until
//   the next switch (`grazing`). With mu_s > mu_k the slip leaves at once and
//   its return is found like any other.
// These decisions (the mode at t = 0, the contact at x' = v, the departure
// from the edge) are event_physics.hpp's, with the band centre b: the same
// code as simulate() and the lane engine.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "stickslip/engines/integration_counts.hpp"
#include "stickslip/episode.hpp"
#include "stickslip/error.hpp"
#include "stickslip/event_physics.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/model/belt_chain.hpp"
#include "stickslip/model/damped_slip.hpp"
#include "stickslip/model/oscillator_model.hpp"
#include "stickslip/observer.hpp"

namespace stickslip {

// Preconditions: validate(model) passed; ic.level < level count; the switch
// source yields level_switch values with existing levels, times non-decreasing.
template <class LevelSwitches, class Observer>
event_counts simulate_model(const oscillator_model& model, const model_initial_state& ic,
                            LevelSwitches& switches, Observer& obs,
                            std::int64_t max_events = default_max_events) {
  detail::count_integration(integrator::model);
  const double as = model.static_band_half_width();
  const double ak = model.kinetic_offset();
  const double w = model.natural_frequency();
  const double w2 = w * w;
  const double gamma = model.decay_rate();
  const bool damped = gamma > 0.0;
  const bool equal_friction = model.static_friction == model.kinetic_friction;
  const double edge_acceleration_size = (model.kinetic_friction - model.static_friction) * model.gravity;
  const double c_over_k = model.damping / model.stiffness;
  const double ta = model.window;
  const double* levels = model.belt.levels.data();
  const detail::damped_oscillator oscillator(w, damped ? gamma : 0.0);
  constexpr double inf = std::numeric_limits<double>::infinity();

  event_counts counts;
  double t = 0.0, x = ic.position, z = ic.velocity;
  std::size_t level = ic.level;
  double v = levels[level];
  double b = -c_over_k * v;  // centre of the stick band
  level_switch next_switch = switches.next();

  mode m;
  double sigma = 1.0;         // friction direction while slipping
  bool grazing = false;       // no return to x' = v before the next switch
  bool after_reversal = false;
  bool mirror = false;        // undamped slip from a stick inside the kinetic band, v -> -v
  double acceleration = 0.0;           // x'' at the start of a damped slip
  double acceleration_rounding = 0.0;  // a bound on its rounding (0: exact)

  // x'' from the state, and a bound on the rounding of its terms (y = x -
  // sigma a_k cancels: its error is that of x and a_k, not of y).
  auto set_generic_acceleration = [&] {
    acceleration = -w2 * (x - sigma * ak) - 2.0 * gamma * z;
    acceleration_rounding = 8.0 * std::numeric_limits<double>::epsilon() *
                            (w2 * (std::abs(x) + ak) + 2.0 * gamma * std::abs(z));
  };
  auto sign_of = [](double u) { return u > 0 ? 1.0 : -1.0; };
  // Slip away from the outward band edge at x' = v (after a break, or a
  // touch of the edge): physics::leave_edge, with x'' = sgn(v) (mu_k - mu_s) g
  // exactly.
  auto leave_edge = [&] {
    const auto departure = detail::physics::leave_edge(v, equal_friction);
    m = mode::slip;
    sigma = departure.sigma;
    grazing = departure.grazing;
    after_reversal = departure.after_reversal;
    mirror = false;
    acceleration = sigma * edge_acceleration_size;
    acceleration_rounding = 0.0;
  };
  // Relative rest x' = v reached by a slip of direction from_sigma
  // (physics::resolve_contact, the decision of the paper's engines and the
  // lanes): a stick, a touch of the outward edge that leaves it, or a
  // reversal (sigma = -from_sigma).
  using detail::physics::contact_outcome;
  auto contact_at = [&](double from_sigma) {
    const auto c = detail::physics::resolve_contact(t, x, from_sigma, v, as, b);
    x = c.x;
    switch (c.outcome) {
      case contact_outcome::stick:
        m = mode::stick;
        break;
      case contact_outcome::grazing:
        leave_edge();
        break;
      case contact_outcome::reversal:
        m = mode::slip;
        sigma = c.sigma;
        after_reversal = true;
        set_generic_acceleration();
        break;
    }
    return c.outcome;
  };

  const auto start = detail::physics::mode_at_start(x, z, v, as, b);
  if (start.kind == mode::stick) {
    m = mode::stick;
  } else if (start.on_outward_edge) {
    leave_edge();
  } else {
    m = mode::slip;
    sigma = start.sigma;
    after_reversal = start.after_reversal;
    set_generic_acceleration();
  }

  episode ep{m, 0.0, 0.0, x, v, false};
  auto close_episode = [&](double when, mode next_mode) {
    ep.end = when;
    if (ep.end > ep.start) obs.on_episode(ep);
    ep = episode{next_mode, when, 0.0, x, v, false, static_cast<double>(counts.belt_switches)};
  };
  // A piece of motion from the current state (observer.hpp).
  // `t_end`: where it ends (its duration t_end - t).
  auto piece = [&](mode kind, double t_end, double x1, double z1) {
    if constexpr (takes_pieces<Observer>)
      obs.on_piece(motion_piece{kind, level, t_end - t, x, x1, z, z1, v,
                                kind == mode::slip ? sigma : 0.0, t, t_end});
  };
  auto take_switch = [&] {
    level = next_switch.level;
    v = levels[level];
    b = -c_over_k * v;
    ++counts.belt_switches;
    counts.switch_time_sum += t;
    obs.on_event(event{event_kind::belt_switch, t, x, z, v});
    next_switch = switches.next();
  };

  std::int64_t steps = 0;
  while (true) {
    if (++steps > max_events) throw work_bound_exceeded(steps, t, ta);
    const double t_switch = next_switch.time;

    if (m == mode::stick) {
      const double s = sign_of(v);
      const double t_edge = v != 0.0 ? t + (as - s * (x - b)) / std::abs(v) : inf;
      const double t_next = std::min(t_edge, t_switch);
      obs.on_segment(segment{mode::stick, t, std::min(t_next, ta), x, v, v, 0.0, w, gamma});
      if (t_next >= ta) {
        piece(mode::stick, ta, x + v * (ta - t), v);
        x += v * (ta - t);
        t = ta;
        break;
      }
      if (t_switch <= t_edge) {  // a belt switch ends the stick: x' = old v
        const double x_end = std::clamp(x + v * (t_switch - t), b - as, b + as);
        piece(mode::stick, t_switch, x_end, v);
        x = x_end;
        z = v;
        t = t_switch;
        const double old_v = v;
        take_switch();
        m = mode::slip;
        sigma = v > z ? 1.0 : -1.0;
        grazing = after_reversal = false;
        // The undamped orbit about c = sigma a_k starts at (w y, x') = (w y, -v).
        // From the inner side (sigma y < 0: |x| inside the kinetic band) its
        // first return to x' = v is the mirror point, the same x. From the
        // outer side (sigma y > 0: a stick between a_k and a_s, mu_s > mu_k)
        // it first turns through the far side and returns after half a
        // period at x = 2c - x: the general root (root_angle gives pi).
        mirror = !damped && v == -old_v && sigma * (x - sigma * ak) < 0.0;
        set_generic_acceleration();
        close_episode(t, mode::slip);
      } else {  // the stick breaks at the band edge; exact state
        piece(mode::stick, t_edge, b + s * as, v);
        x = b + s * as;
        z = v;
        t = t_edge;
        leave_edge();
        ++counts.stick_breaks;
        obs.on_event(event{event_kind::stick_break, t, x, z, v});
        close_episode(t, mode::slip);
      }
      continue;
    }

    // --- slip ---
    const double center = sigma * ak;
    const double y = x - center;
    double t_root = inf;
    double x_root = 0.0;
    if (!damped) {
      const double wy = w * y;
      const double disc = wy * wy + (z - v) * (z + v);  // B^2 - v^2
      if (!grazing && disc > 0.0) {
        double dtheta;
        if (mirror) {
          dtheta = detail::mirror_return_angle(wy, z);  // z == -v exactly here
        } else if (after_reversal) {
          dtheta = detail::reversal_arc_angle(wy, v, sigma);  // z == v exactly here
        } else {
          dtheta = detail::root_angle(wy, z, v, sigma, std::sqrt(disc));
        }
        t_root = t + dtheta / w;
        x_root = mirror ? x : center - sigma * std::sqrt(disc) / w;
      }
    }
    // Damped: the state at the horizon when first_rest computed it (no root
    // before it), for advance_to (the same dt, so the same bits).
    detail::damped_state at_horizon{};
    bool have_horizon_state = false;
    if (damped && !grazing) {
      detail::damped_state at_root{};
      at_horizon.velocity = std::numeric_limits<double>::quiet_NaN();
      const double tau =
          oscillator.first_rest(y, z, acceleration, v, sigma, std::min(t_switch, ta) - t, at_root,
                                &at_horizon, acceleration_rounding);
      if (tau < inf) {
        t_root = t + tau;
        x_root = center + at_root.y;
      } else {
        have_horizon_state = !std::isnan(at_horizon.velocity);
      }
    }
    const double t_next = std::min(t_root, t_switch);
    obs.on_segment(segment{mode::slip, t, std::min(t_next, ta), x, z, v, center, w, gamma});
    auto advance_to = [&](double when) {
      const double dt = when - t;
      double x_end, z_end;
      if (!damped) {
        const double cs = detail::fm::cos(w * dt), sn = detail::fm::sin(w * dt);
        x_end = center + y * cs + z / w * sn;
        z_end = z * cs - w * y * sn;
      } else {
        const detail::damped_state s =
            have_horizon_state && dt == std::min(t_switch, ta) - t ? at_horizon
                                                                 : oscillator.advance(y, z, dt);
        x_end = center + s.y;
        z_end = s.velocity;
      }
      piece(mode::slip, when, x_end, z_end);
      x = x_end;
      z = z_end;
      t = when;
    };
    if (t_next >= ta) {
      advance_to(ta);
      break;
    }
    if (t_switch <= t_root) {  // a belt switch during a slip: x, x' continuous
      advance_to(t_switch);
      take_switch();
      grazing = after_reversal = mirror = false;
      if (z == v) {  // measure zero: landed exactly on relative rest
        if (contact_at(x - b > 0 ? -1.0 : 1.0) == contact_outcome::stick) {
          ++counts.stick_onsets;
          obs.on_event(event{event_kind::stick_onset, t, x, z, v});
          close_episode(t, mode::stick);
        }
      } else {
        sigma = v > z ? 1.0 : -1.0;
        set_generic_acceleration();
      }
      continue;
    }
    // Relative rest x' = v.
    piece(mode::slip, t_root, x_root, v);
    x = x_root;
    z = v;
    t = t_root;
    after_reversal = mirror = false;
    const contact_outcome outcome = contact_at(sigma);
    if (outcome == contact_outcome::stick) {
      ++counts.stick_onsets;
      obs.on_event(event{event_kind::stick_onset, t, x, z, v});
      close_episode(t, mode::stick);
    } else if (outcome == contact_outcome::reversal) {
      ++counts.slip_reversals;
      obs.on_event(event{event_kind::slip_reversal, t, x, z, v});
    }
  }
  ep.end = ta;
  ep.censored = true;
  obs.on_episode(ep);
  return counts;
}

}  // namespace stickslip
