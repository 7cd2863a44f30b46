// Statistical checks of the sweep against closed-form expectations,
// with tolerances from standard errors (fixed seeds).
#include <gtest/gtest.h>

#include <cmath>

#include "stickslip/sweep.hpp"

using namespace stickslip;

// When lambda t_a is large and the band is wide, almost every belt switch
// starts a stick: a switch interrupting a stick at x starts the mirror-return
// slip of duration tau(x) = (pi - 2 atan(w y / V)) / w, y = |x + s a| >= a/2
// for |x| <= a/2, and pi - 2 atan(u) <= 2/u gives tau <= 4V/(w^2 a) = 4V/(mu g).
// The stick is lost only if the next switch comes within tau: probability
// <= lambda tau. Sticks cannot outnumber switches + 1 (docs/model.md). So
//   lambda t_a + 1 - lambda t_a * lambda * 4V/(mu g)  <=  E[S_T]  <=  lambda t_a + 1,
// with E[number of switches] = lambda t_a exactly (Poisson).
TEST(SweepStatistics, StickCountMatchesBeltSwitchCountAtLargeLambdaTa) {
  sweep_spec s;
  s.base.friction_coefficient = 50.0;  // a = 122.6 m: |x| stays far inside a/2
  s.base.switch_rate = 1.0;
  s.base.window = 100.0;                // lambda t_a = 100
  s.realizations = 2000;
  s.seed = 77;
  s.keep_records = true;
  const auto rs = run_sweep(s, 2);
  const auto& st = rs.points.at(0).stats;
  const auto& p = rs.points.at(0).parameters;
  const double lta = p.switch_rate * p.window;
  double switches = 0;
  for (const auto& r : rs.records.at(0)) {
    EXPECT_LE(r.sticks, r.events.belt_switches + 1) << "realization " << r.realization;
    switches += static_cast<double>(r.events.belt_switches);
  }
  switches /= static_cast<double>(s.realizations);
  const double sticks = st.sticks_per_time.mean() * p.window;
  const double se = st.sticks_per_time.std_error() * p.window;
  const double lost_bound = lta * p.switch_rate * 4 * p.belt_speed /
                            (p.friction_coefficient * p.gravity);
  EXPECT_LE(sticks, lta + 1 + 4 * se);
  EXPECT_GE(sticks, lta + 1 - lost_bound - 4 * se);
  // The switch count itself is Poisson(lambda t_a): mean within 4 SE.
  EXPECT_NEAR(switches, lta, 4 * std::sqrt(lta / static_cast<double>(s.realizations)));
}

// Where the slip after a switch is negligible against 1/lambda, a stick that
// starts at x0 lasts D = min(W, d(x0)) with d(x0) = (a - sgn(v) x0)/V, so
// E[D | x0] = (1 - exp(-lambda d)) / lambda. With a band much wider than the
// sticks' wander, d >> 1/lambda and E[D] -> 1/lambda (up to the mirror-return
// slips, which shorten nothing but delay the next stick).
TEST(SweepStatistics, StickDurationMeanIsOneOverLambdaForAWideBand) {
  for (double lambda : {0.5, 2.0, 8.0}) {
    sweep_spec s;
    s.base.friction_coefficient = 50.0;
    s.base.switch_rate = lambda;
    s.base.window = 50.0;
    s.realizations = 1000;
    s.seed = 11;
    const auto rs = run_sweep(s, 2);
    const auto& d = rs.points.at(0).stats.stick_duration;
    // Sticks cut by t_a are clipped (one per realization at most): their
    // share biases the mean down by at most (1/lambda) / (lambda t_a + 1).
    const double clip_bias = (1.0 / lambda) / (lambda * s.base.window + 1.0);
    // Pooled sticks within a realization are independent here (memoryless W).
    EXPECT_NEAR(d.mean(), 1.0 / lambda, 4 * d.std_error() + clip_bias) << "lambda " << lambda;
  }
}
