// The conventional way to simulate the stick-slip oscillator with an ODE
// solver, as a careful user of ode45, CVODE or odeint writes it. The Octave
// script bench/octave/stickslip_ode45.m does exactly the same, step by step:
//
//   slip  (friction direction sigma fixed for the segment):
//         x' = z,  z' = -(k/m) x + sigma mu g
//         event g = z - v, direction sigma (z rises to v when sigma = +1)
//   stick: x' = v,  z' = 0
//         event g = x - s a (s = sgn v: the spring force reaches mu m g),
//         direction s
//   belt switches: the segment ends at the next switch time (the times are
//         known in advance), then v = -v and slip with sigma = sgn(v - z).
//
//   At a slip event (z = v): |k x| <= mu m g starts a stick (z := v);
//   otherwise the slip goes on with sigma = sgn(x) (the spring wins, so the
//   relative velocity takes the sign of -k x). A stick that reaches the band
//   edge breaks into a slip with sigma = s.
//   Events exactly at the start of a segment are ignored (the event function
//   is zero there after every stick onset, stick break and reversal).
//
// Nothing here knows about the grazing orbit after a stick break: the orbit
// touches z = v at the band edge once per period for zero time, and whether
// the solver reports it (and then starts a spurious stick) is up to rounding.
// That is the honest behaviour of the conventional method.
#pragma once
#include <cmath>

#include "scenario.hpp"

namespace stickslip::bench {

// What a solver is asked to do for one segment.
struct segment_problem {
  bool stick = false;
  double sigma = 1.0;        // friction direction while slipping
  double belt_velocity = 1.0;
  double omega2 = 4.0;       // k/m
  double friction_accel = 0; // mu g
  double band = 0;           // a = mu m g / k
  // Right-hand side of the current mode.
  void rhs(const double y[2], double dy[2]) const noexcept {
    if (stick) {
      dy[0] = belt_velocity;
      dy[1] = 0.0;
    } else {
      dy[0] = y[1];
      dy[1] = -omega2 * y[0] + sigma * friction_accel;
    }
  }
  // The event function of the current mode and its direction.
  [[nodiscard]] double event(const double y[2]) const noexcept {
    const double s = belt_velocity > 0 ? 1.0 : -1.0;
    return stick ? y[0] - s * band : y[1] - belt_velocity;
  }
  [[nodiscard]] double direction() const noexcept {
    return stick ? (belt_velocity > 0 ? 1.0 : -1.0) : sigma;
  }
};

struct segment_outcome {
  double t = 0.0;
  double y[2] = {0.0, 0.0};
  bool event = false;  // true: the mode's event fired; false: reached t_stop
};

// Solver concept:
//   segment_outcome advance(const segment_problem&, double t0, const double y0[2], double t_stop);
//   std::uint64_t steps() const; std::uint64_t rhs_evaluations() const;
template <class Solver>
method_run run_hybrid(const scenario& sc, double window, Solver& solver) {
  const auto& p = sc.params;
  method_run out;
  segment_problem prob;
  prob.omega2 = p.stiffness / p.mass;
  prob.friction_accel = p.friction_coefficient * p.gravity;
  prob.band = p.band_half_width();
  const double V = p.belt_speed;

  double t = 0.0;
  double y[2] = {sc.initial.position, sc.initial.velocity};
  prob.belt_velocity = sc.initial.belt_direction >= 0 ? V : -V;
  std::size_t next_switch = 0;
  double stick_start = 0.0;

  auto start_stick = [&](double when) {
    prob.stick = true;
    y[1] = prob.belt_velocity;
    stick_start = when;
  };
  auto end_stick = [&](double when, bool censored) {
    out.sticks.push_back({stick_start, when, censored});
    prob.stick = false;
  };

  if (y[1] == prob.belt_velocity && std::abs(y[0]) <= prob.band) {
    start_stick(0.0);
  } else if (y[1] == prob.belt_velocity) {
    prob.sigma = y[0] > 0 ? 1.0 : -1.0;
  } else {
    prob.sigma = prob.belt_velocity > y[1] ? 1.0 : -1.0;
  }

  while (t < window) {
    const double t_switch =
        next_switch < sc.switch_times.size() ? sc.switch_times[next_switch] : window;
    const double t_stop = std::min(t_switch, window);
    const auto r = solver.advance(prob, t, y, t_stop);
    t = r.t;
    y[0] = r.y[0];
    y[1] = r.y[1];
    if (r.event) {
      if (prob.stick) {  // band edge: the stick breaks
        end_stick(t, false);
        ++out.counts.stick_breaks;
        prob.sigma = prob.belt_velocity > 0 ? 1.0 : -1.0;
        y[1] = prob.belt_velocity;
      } else if (std::abs(y[0]) <= prob.band) {  // z = v inside the band
        ++out.counts.stick_onsets;
        start_stick(t);
      } else {  // z = v outside the band: the slip reverses
        ++out.counts.slip_reversals;
        prob.sigma = y[0] > 0 ? 1.0 : -1.0;
        y[1] = prob.belt_velocity;
      }
      continue;
    }
    if (t >= window) break;
    // Belt switch at t.
    ++next_switch;
    ++out.counts.belt_switches;
    if (prob.stick) end_stick(t, false);
    prob.belt_velocity = -prob.belt_velocity;
    prob.sigma = prob.belt_velocity > y[1] ? 1.0 : -1.0;
  }
  if (prob.stick) end_stick(window, true);
  out.steps = solver.steps();
  out.rhs_evaluations = solver.rhs_evaluations();
  return out;
}

}  // namespace stickslip::bench
