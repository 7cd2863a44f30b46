// What "the exact engine agrees with the RK4 oracle" means for one model
// scenario (model_oracle.hpp, model_scenario.hpp), shared by the oracle
// tests: the episode sequences are identical (count and modes), every
// boundary within tol_t = 10 kappa E(N) + 1e-12 t_a, E(N) = t_a (2 pi / N)^4
// / 120, kappa = 1 + B / V_min (B the largest orbit speed amplitude, V_min
// the slowest moving level), and every start position within tol_t (V_max +
// B). Near-degenerate scenarios, where the oracle cannot resolve which branch
// is right, are named by near_degenerate: a stick shorter than 10 stick
// resolutions; a contact whose stick force |k x + c v| lies within 1e3 tol of
// mu_s m g; an event within 1e3 tol_t of a belt switch; a near tangency the
// oracle flags.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "reference/episode_agreement.hpp"
#include "reference/model_oracle.hpp"
#include "reference/model_scenario.hpp"

namespace stickslip::reference {

struct tolerance {
  double time, position;
};

inline double slowest_moving_level(const oscillator_model& m) {
  double v = 1e300;
  for (double u : m.belt.levels)
    if (u != 0.0) v = std::min(v, std::abs(u));
  return v;
}
inline double fastest_level(const oscillator_model& m) {
  double v = 0;
  for (double u : m.belt.levels) v = std::max(v, std::abs(u));
  return v;
}

inline tolerance tolerance_for(const model_scenario& s, const model_exact_run& r, double n) {
  double B = std::abs(s.ic.velocity);
  for (const segment& g : r.segments)
    if (g.kind == mode::slip) B = std::max(B, std::hypot(g.omega * (g.position - g.center), g.velocity));
  const double kappa = 1.0 + B / slowest_moving_level(s.model);
  const double e = s.model.window * std::pow(2.0 * std::numbers::pi / n, 4) / 120.0;
  const double t = 10.0 * kappa * e + 1e-12 * s.model.window;
  return {t, t * (fastest_level(s.model) + B)};
}

inline std::optional<std::string> near_degenerate(const model_scenario& s, const model_exact_run& r,
                                           const model_oracle_result& o, tolerance tol) {
  const double res = 10.0 * o.stick_resolution;
  for (const episode& e : r.episodes)
    if (e.kind == mode::stick && e.duration() < res) return "short exact stick";
  for (const episode& e : o.episodes)
    if (e.kind == mode::stick && e.duration() < res) return "short oracle stick";
  if (!o.near_tangencies.empty()) return "near tangency";
  const oscillator_model& m = s.model;
  const double static_force = m.static_friction * m.mass * m.gravity;
  auto near_switch = [&](double t) {
    for (const level_switch& w : s.switches)
      if (std::abs(w.time - t) < 1e3 * tol.time) return true;
    return false;
  };
  for (const event& e : r.events) {
    if (e.kind == event_kind::belt_switch) continue;
    if (near_switch(e.time)) return "event next to a belt switch";
    const double force = m.stiffness * e.position + m.damping * e.belt_velocity;
    if (e.kind != event_kind::stick_break &&
        std::abs(std::abs(force) - static_force) < 1e3 * m.stiffness * tol.position)
      return "contact at the band edge";
  }
  for (const oracle_event& e : o.events) {
    if (e.kind == event_kind::belt_switch) continue;
    if (near_switch(e.time)) return "oracle event next to a belt switch";
  }
  return std::nullopt;
}

inline std::string describe(const model_scenario& s) {
  const oscillator_model& m = s.model;
  std::string out;
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "m=%.17g k=%.17g c=%.17g (zeta %.3g) mu_s=%.17g mu_k=%.17g ta=%.17g x0=%.17g "
                "xdot0=%.17g level=%zu levels:",
                m.mass, m.stiffness, m.damping, m.damping_ratio(), m.static_friction,
                m.kinetic_friction, m.window, s.ic.position, s.ic.velocity, s.ic.level);
  out += buf;
  for (double v : m.belt.levels) {
    std::snprintf(buf, sizeof buf, " %.17g", v);
    out += buf;
  }
  out += " switches:";
  for (const level_switch& w : s.switches) {
    std::snprintf(buf, sizeof buf, " %.17g->%zu", w.time, w.level);
    out += buf;
  }
  return out;
}

inline std::string episodes_text(const std::vector<episode>& es) {
  std::string out;
  char buf[160];
  for (const episode& e : es) {
    std::snprintf(buf, sizeof buf, "  %-5s %.12f %.12f x=%.9g v=%.4g\n", to_string(e.kind), e.start,
                  e.end, e.position_at_start, e.belt_velocity);
    out += buf;
  }
  return out;
}


// One scenario through both integrators, with the tolerance and, when the
// oracle cannot decide between two branches, why.
struct scenario_run {
  model_exact_run exact;
  model_oracle_result oracle;
  tolerance tol;
  std::optional<std::string> degenerate;
};
inline scenario_run run_both(const model_scenario& s, double steps_per_period) {
  scenario_run r;
  r.exact = run_model_exact(s);
  r.oracle = integrate_model_reference(s.model, s.ic, s.switches,
                                       {.steps_per_period = steps_per_period});
  r.tol = tolerance_for(s, r.exact, steps_per_period);
  r.degenerate = near_degenerate(s, r.exact, r.oracle, r.tol);
  return r;
}

// The agreement the oracle tests require (header comment), as gtest
// failures; nullopt when the episode sequences differ.
inline std::optional<difference> expect_agreement(const model_scenario& s, const scenario_run& r) {
  const auto d = compare(r.exact.episodes, r.oracle.episodes);
  if (!d) {
    ADD_FAILURE() << "episode sequences differ for " << describe(s) << "\nexact:\n"
                  << episodes_text(r.exact.episodes) << "oracle:\n"
                  << episodes_text(r.oracle.episodes);
    return d;
  }
  EXPECT_LE(d->time, r.tol.time) << describe(s);
  EXPECT_LE(d->position, r.tol.position) << describe(s);
  return d;
}

}  // namespace stickslip::reference
