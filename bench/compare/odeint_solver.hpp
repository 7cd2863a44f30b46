// Boost.Odeint dopri5 with dense output; events located by bisection on the
// dense-output interpolant between the two step ends where the event
// function changes sign in the wanted direction.
// The event function is zero at the start of a segment after every event.
// The first step therefore counts as a crossing when it ends on the far side
// (dir * g > 0): after a slip reversal just outside the band the whole arc
// back to x' = v can fit in one tolerance-sized step, and a plain sign-change
// test between step ends would miss that stick onset. (CVODE does the same
// internally: it looks at g just after t0 when g(t0) = 0.)
#pragma once
#include <array>
#include <boost/numeric/odeint.hpp>
#include <cstdint>

#include "hybrid_driver.hpp"

namespace stickslip::bench {

class odeint_dopri5 {
 public:
  // max_step <= 0: no limit (step size chosen by the tolerances alone).
  odeint_dopri5(double abs_tol, double rel_tol, double max_step = 0.0) noexcept
      : abs_tol_(abs_tol), rel_tol_(rel_tol), max_step_(max_step) {}

  segment_outcome advance(const segment_problem& prob, double t0, const double y0[2],
                          double t_stop) {
    namespace odeint = boost::numeric::odeint;
    using state = std::array<double, 2>;
    auto system = [&](const state& x, state& dx, double) {
      prob.rhs(x.data(), dx.data());
      ++rhs_evaluations_;
    };
    using base = odeint::runge_kutta_dopri5<state>;
    auto dense = max_step_ > 0.0 ? odeint::make_dense_output(abs_tol_, rel_tol_, max_step_, base())
                                 : odeint::make_dense_output(abs_tol_, rel_tol_, base());
    double dt = dt_guess_;
    if (max_step_ > 0.0 && dt > max_step_) dt = max_step_;
    dense.initialize(state{y0[0], y0[1]}, t0, dt);
    const double dir = prob.direction();
    double t_prev = t0;
    double g_prev = prob.event(y0);
    segment_outcome out;
    bool first_step = true;
    while (true) {
      dense.do_step(system);
      ++steps_;
      const double t1 = dense.current_time();
      const double te = t1 < t_stop ? t1 : t_stop;
      state xe;
      if (t1 <= t_stop) {
        xe = dense.current_state();
      } else {
        dense.calc_state(te, xe);
      }
      const double ge = prob.event(xe.data());
      const bool crossed = first_step ? (dir * g_prev <= 0.0 && dir * ge > 0.0)
                                      : (dir * g_prev < 0.0 && dir * ge >= 0.0);
      first_step = false;
      if (crossed) {
        // Bisection on the interpolant: keep g(lo) on the old side.
        double lo = t_prev, hi = te;
        state xm = xe;
        while (hi - lo > event_tolerance) {
          const double mid = 0.5 * (lo + hi);
          dense.calc_state(mid, xm);
          if (dir * prob.event(xm.data()) < 0.0) lo = mid; else hi = mid;
        }
        dense.calc_state(hi, xm);
        out.t = hi;
        out.y[0] = xm[0];
        out.y[1] = xm[1];
        out.event = true;
        break;
      }
      if (t1 >= t_stop) {
        out.t = t_stop;
        out.y[0] = xe[0];
        out.y[1] = xe[1];
        break;
      }
      t_prev = t1;
      g_prev = ge;
    }
    dt_guess_ = dense.current_time_step();
    return out;
  }
  [[nodiscard]] std::uint64_t steps() const noexcept { return steps_; }
  [[nodiscard]] std::uint64_t rhs_evaluations() const noexcept { return rhs_evaluations_; }

  static constexpr double event_tolerance = 1e-13;

 private:
  double abs_tol_, rel_tol_, max_step_;
  double dt_guess_ = 1e-3;
  std::uint64_t steps_ = 0, rhs_evaluations_ = 0;
};

}  // namespace stickslip::bench
