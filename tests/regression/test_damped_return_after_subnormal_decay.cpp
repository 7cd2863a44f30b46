// Regression: on a resting belt level (v = 0), a damped slip's return to
// x' = 0 was missed when the window was long enough for e^{-gamma t} to be
// subnormal at its end (gamma t_a = 735: e^{-735} ~ 1e-319). The products
// e S and e C lost their digits, the state at the horizon came out with
// either sign, and near critical damping (a single piece up to the horizon)
// that sign decided that the slip never returned: the mass then crept on to
// its centre against its friction. Found by fuzz_model_family at m = 0.0106,
// k = 3.82, c = 0.40 (damping ratio 1 + 4e-15), t_a = 38.6; ordinary
// initial conditions show it too.
// Oracle: the critically damped closed form written here, x'(t) = e^{-gamma t}
// (z0 - gamma (z0 + gamma y0) t), whose zero is t* = z0 / (gamma (z0 + gamma
// y0)) (the model is under-damped by omega_d^2 = 1.35e-13: the two agree to
// far below the tolerance), and the sign of x' on either side of it.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "regression/recorded.hpp"
#include "stickslip/model/belt_chain.hpp"
#include "stickslip/model/damped_slip.hpp"
#include "stickslip/model/model_engine.hpp"

namespace stickslip {
namespace {

using regression::recorded;

oscillator_model fuzzer_model() {
  oscillator_model m;
  m.mass = 0.010554504700218273;
  m.stiffness = 3.8192588631139799;
  m.gravity = 0.1240941848313941;
  m.damping = 0.40154892913360773;
  m.static_friction = m.kinetic_friction = 0.050174123841581798;
  m.belt = markov_belt{{0.0, 0.01}, {-1.0, 1.0, 1.0, -1.0}};
  m.window = 38.636636617597013;
  return m;
}

struct start {
  double x0, z0;
};

TEST(DampedReturnAfterSubnormalDecay, TheReturnOnARestingLevelIsFound) {
  const oscillator_model m = fuzzer_model();
  const detail::damped_oscillator o(m.natural_frequency(), m.decay_rate());
  ASSERT_LT(std::exp(-m.decay_rate() * m.window), 1e-300);  // the case
  const double gamma = o.gamma();
  for (const start s : {start{1.0, 1.0}, start{0.5, 3.0}, start{212718724.4999713, 2261634.5098039214}}) {
    const double sigma = -1.0;  // x' > v = 0
    const double y0 = s.x0 - sigma * m.kinetic_offset();
    const double expected = s.z0 / (gamma * (s.z0 + gamma * y0));
    const auto velocity = [&](double t) {
      return std::exp(-gamma * t) * (s.z0 - gamma * (s.z0 + gamma * y0) * t);
    };
    ASSERT_GT(velocity(0.99 * expected), 0.0);
    ASSERT_LT(velocity(1.01 * expected), 0.0);
    const double a0 = -o.omega_squared() * y0 - 2.0 * gamma * s.z0;
    detail::damped_state root{};
    const double tau = o.first_rest(y0, s.z0, a0, 0.0, sigma, m.window, root);
    EXPECT_NEAR(tau, expected, 1e-9 * expected) << "x0 " << s.x0 << " z0 " << s.z0;
  }
}

TEST(DampedReturnAfterSubnormalDecay, NoReturnWhereTheClosedFormHasNone) {
  // From x0 = 1 at rest, and from x0 = -1 moving away from the centre, x'
  // keeps its sign for ever: no return, and the state at t_a keeps that sign.
  const oscillator_model m = fuzzer_model();
  const detail::damped_oscillator o(m.natural_frequency(), m.decay_rate());
  for (const auto& [s, sigma] : {std::pair{start{1.0, 0.0}, 1.0}, std::pair{start{-1.0, 0.2}, -1.0}}) {
    const double y0 = s.x0 - sigma * m.kinetic_offset();
    const double a0 = -o.omega_squared() * y0 - 2.0 * o.gamma() * s.z0;
    detail::damped_state root{}, at_horizon{};
    const double tau = o.first_rest(y0, s.z0, a0, 0.0, sigma, m.window, root, &at_horizon);
    EXPECT_EQ(tau, std::numeric_limits<double>::infinity()) << "x0 " << s.x0;
    EXPECT_LT(sigma * at_horizon.velocity, 0.0) << "x0 " << s.x0;  // sigma (v - x') > 0
  }
}

TEST(DampedReturnAfterSubnormalDecay, TheEngineReversesTheSlipThere) {
  const std::vector<level_switch> none;
  given_level_switches sw(none);
  recorded r;
  (void)simulate_model(fuzzer_model(), model_initial_state{1.0, 1.0, 0}, sw, r);
  ASSERT_GE(r.episodes.size(), 1u);
  // x' returns to 0 at t* = 0.00263 outside the band: a reversal, so the
  // first slip event is there, not at t_a.
  ASSERT_FALSE(r.events.empty());
  EXPECT_NEAR(r.events.front().time, 0.0026254339971094861, 1e-9);
}

}  // namespace
}  // namespace stickslip
