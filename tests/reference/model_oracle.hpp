// An independent reference integrator for the model family
// (stickslip/model/oscillator_model.hpp), used only by the tests to check the
// exact engine simulate_model (model_engine.hpp). Like oracle.hpp it shares no
// algorithm with the closed forms: it integrates the equation of motion
//   m x'' + c x' + k x = f,
//   slip:  f = mu_k m g sigma,  sigma = sgn(v - x') held fixed,
//          classical fixed-step RK4 on (x, x');
//   stick: x' = v while |k x + c v| <= mu_s m g (x += v tau; at v = 0 x stays),
// with every event found by bisection inside one RK4 step:
//   - the relative velocity reaching zero during a slip (g = sigma (v - x') > 0
//     while slipping; a hidden double crossing inside one step is found by
//     bisecting g' = -sigma x'' to the step's minimum of g first; a slip that
//     leaves g = 0 at a reversal and returns within its first step is found
//     after the step's maximum of g);
//   - the band edge |k x + c v| = mu_s m g during a stick at v != 0;
//   - the belt switches (given (t, level) pairs), hit exactly.
// At a contact the mass sticks if |k x + c v| <= mu_s m g, else it slips on
// with sigma = sgn(k x + c v). A stick that breaks leaves with sigma = sgn(v)
// (beyond the edge k x + c v has the sign of v). Sticks shorter than
// `stick_resolution` are zero-time touches (grazing) and are merged into the
// slip, as in oracle.hpp.
//
// Step: h = 2 pi / (N Omega) with Omega = max(omega_0, gamma + |gamma^2 -
// omega_0^2|^(1/2)), the fastest rate of the slip (the fast over-damped mode
// included), so every mode gets N steps per radian-period and RK4's error is
// about t_a (2 pi / N)^4 / 120 in time, as in oracle.hpp.
//
// Near tangency: a minimum of g inside a step that stays above zero but below
// `tangency_band` times the speed scale is reported in `near_tangencies`
// (outside the grazing orbits after an equal-friction break): there, whether
// the orbit touches x' = v is below the oracle's resolution.
#pragma once
#include <span>
#include <vector>

#include "reference/oracle.hpp"
#include "stickslip/model/belt_chain.hpp"
#include "stickslip/model/oscillator_model.hpp"

namespace stickslip::reference {

// Energy bookkeeping, integrated along the RK4 path (Simpson's rule on each
// accepted step, the midpoint from the same RK4 map): never the closed forms
// nor the engine's per-piece formulas.
//   friction_dissipation  int over slips of mu_k m g |v - x'| dt
//   damping_dissipation   int of c x'^2 dt (a stick: c v^2 dt)
//   belt_work             int of f v dt, f the friction force on the mass
//                         (slip: sigma mu_k m g; stick: k x + c v)
// and the mechanical energy m x'^2 / 2 + k x^2 / 2 at 0 and t_a:
//   belt_work = friction + damping dissipation + final - initial energy.
struct model_oracle_result {
  double friction_dissipation = 0, damping_dissipation = 0, belt_work = 0;
  double initial_energy = 0, final_energy = 0;
  std::vector<episode> episodes;
  std::vector<oracle_event> events;
  std::vector<double> dropped_stick_durations;
  std::vector<double> near_tangencies;  // times
  std::vector<oracle_sample> samples;   // at sample_times (oracle.hpp), in order
  std::int64_t rk4_steps = 0;
  double step = 0;
  double stick_resolution = 0;
};

[[nodiscard]] model_oracle_result integrate_model_reference(
    const oscillator_model& model, const model_initial_state& ic,
    std::span<const level_switch> switches, const oracle_options& options = {},
    double tangency_band = 1e-7, std::span<const double> sample_times = {});

}  // namespace stickslip::reference
