// An independent reference integrator for the stick-slip oscillator, used only
// by the tests to check the exact closed-form integrator (integrator.hpp).
//
// It shares no algorithm with the closed form. It integrates the equation of
// motion of the paper, m x'' + k x = f, directly:
//   slip:   x'' = -(k/m) x + mu g sigma,  sigma = sgn(v - x') held fixed,
//           classical fixed-step RK4 (step h = period / steps_per_period);
//   stick:  x' = v while k |x| <= mu m g (RK4 on x' = v, i.e. x += v tau);
// and finds every event by bisection on a sign change inside one RK4 step
// (each trial point is a single RK4 sub-step from the start of that step):
//   - the relative velocity u = x' - v reaching zero during a slip
//     (g = sigma (v - x') > 0 while slipping; also a hidden double crossing
//     inside one step, found by first bisecting on g' = -sigma x'' to the
//     minimum of g and testing g there);
//   - the stick band edge k |x| = mu m g during a stick;
//   - the belt switches, which are hit exactly (steps are cut at them).
// At a contact (u = 0) the mass sticks if k |x| <= mu m g, otherwise the slip
// reverses (the spring force beats friction: sigma = sgn(x)). A stick that
// breaks at the edge leaves with sigma = sgn(v).
//
// Grazing: after a stick breaks at the band edge the orbit touches u = 0 at
// the outward edge once per period, for zero time. Numerically such a touch
// shows up (or not) as a contact whose stick ends at once, at the edge. The
// oracle runs every stick it finds, but reports only sticks that last at
// least `stick_resolution` (default 1e-6 natural periods); shorter ones are
// merged into the surrounding slip and listed in `dropped_stick_durations`.
// A genuine stick that short is a near-degenerate scenario the oracle cannot
// resolve; the tests detect and regenerate those explicitly. (RK4's amplitude
// error on the harmonic slip is dissipative, |R(i w h)| < 1, so the numerical
// grazing orbit mostly stays just short of u = 0 and the touch is not even
// seen; a start exactly on the outward edge at belt velocity exercises the
// dropped-contact path.)
//
// Error: RK4 on the harmonic slip has phase error (w h)^5 / 120 per step, so
// event times carry a global error of about t_a (2 pi / N)^4 / 120 for N steps
// per period (t_a = 5 s, N = 800: 2e-10 s), amplified by 1/|u'| at nearly
// tangent contacts. test_oracle_agreement checks the fourth order by halving h.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "stickslip/episode.hpp"
#include "stickslip/initial_conditions.hpp"
#include "stickslip/parameters.hpp"

namespace stickslip::reference {

struct oracle_options {
  double steps_per_period = 800;  // N: RK4 steps per natural period 2 pi sqrt(m/k)
  double stick_resolution = 0;    // shortest reported stick [s]; 0 = 1e-6 periods
  std::int64_t max_steps = 200'000'000;  // guard against runaway loops (throws)
};

// The oracle's state at a requested time (sample_times below): the RK4 path
// is cut at each sample time, as at a belt switch, and the state read there,
// after any event at that instant has acted (a stick that starts at t is
// sticking at t); a time equal to t_a gives the state at t_a.
struct oracle_sample {
  double time;
  double position;       // x
  double velocity;       // x' (= v while sticking)
  double belt_velocity;  // v
  std::size_t level;     // belt level index (paper: 0 = +V, 1 = -V)
  bool sticking;
};

// A contact (u = 0) or other instant the oracle resolved, for diagnostics.
struct oracle_event {
  event_kind kind;
  double time;
  double position;       // x at the event
  double belt_velocity;  // v after the event
};

struct oracle_result {
  std::vector<episode> episodes;           // tiles [0, t_a], like the integrator's
  std::vector<oracle_event> events;        // every event, including dropped sticks
  std::vector<double> dropped_stick_durations;
  std::vector<oracle_sample> samples;      // one per sample time, in order
  std::int64_t rk4_steps = 0;              // accepted steps (bisection trials not counted)
  double step = 0;                         // h [s]
  double stick_resolution = 0;             // [s]
};

// Integrates one scenario on [0, p.window]. `switch_times` must be sorted;
// times >= p.window are ignored. `sample_times`: sorted, within [0, t_a]; the
// state at each is in oracle_result::samples (the path is cut there, so the
// steps differ from a run without them). Throws std::runtime_error if
// max_steps is hit.
[[nodiscard]] oracle_result integrate_reference(const model_parameters& p,
                                                const initial_conditions& ic,
                                                std::span<const double> switch_times,
                                                const oracle_options& options = {},
                                                std::span<const double> sample_times = {});

}  // namespace stickslip::reference
