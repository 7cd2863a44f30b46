// Regression: a damped slip's return to x' = v was missed when the horizon
// (the next switch, or t_a) was long, so results depended on t_a.
//
// Found by fuzz_model_family: at damping ratio 1 + 2e-16 (over-damped,
// beta ~ 4e-7) the slip from x' = -2.55 reaches the belt's -0.775 at
// t = 0.0898 and x' then creeps to 0. The root solver started from the
// secant point of [0, horizon], deep in the tail where x'' ~ 1e-200: each
// Halley step moved t by about 2 / |r1| ~ 0.1 while g did not change, and
// after 200 steps it returned the bracket's far end as the root (6.62 for
// t_a = 40, 2.99 for t_a = 69.36; 0.0898 for t_a = 5, 20, 60). Oracles: the
// root found on a short horizon, where the solver converges at once, and
// the sign of g itself on both sides of it.
#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <string>
#include <vector>

#include "regression/recorded.hpp"
#include "stickslip/model/belt_chain.hpp"
#include "stickslip/model/damped_slip.hpp"
#include "stickslip/model/model_engine.hpp"

namespace stickslip {
namespace {

using regression::recorded;

oscillator_model fuzzer_model(double window) {
  oscillator_model m;
  m.mass = 0.014136174049814295;
  m.stiffness = 5.0075599112268341;
  m.gravity = 100.0;
  m.static_friction = 0.24626730192993604;
  m.kinetic_friction = 0.21771751613265194;
  m.damping = 0.53211930417896014;
  m.belt = markov_belt{{-0.7753435232831275, 0.042191324880705948}, {-1.0, 1.0, 1.0, -1.0}};
  m.window = window;
  return m;
}

TEST(DampedRootOnALongHorizon, TheFirstReturnDoesNotDependOnTheHorizon) {
  const oscillator_model m = fuzzer_model(5.0);
  const detail::damped_oscillator o(m.natural_frequency(), m.decay_rate());
  ASSERT_EQ(o.regime(), detail::damping_regime::over);
  const double v = m.belt.levels[0], z0 = -2.5516592618846694;
  const double sigma = 1.0, y0 = 0.24893057637147883 - sigma * m.kinetic_offset();
  const double a0 = -o.omega_squared() * y0 - 2.0 * o.gamma() * z0;
  detail::damped_state root{};
  const double short_horizon = o.first_rest(y0, z0, a0, v, sigma, 0.5, root);
  ASSERT_GT(short_horizon, 0.08);
  ASSERT_LT(short_horizon, 0.1);
  // g = sigma (v - x') changes sign there
  EXPECT_GT(sigma * (v - o.advance(y0, z0, short_horizon * (1 - 1e-9)).velocity), 0.0);
  EXPECT_LE(sigma * (v - o.advance(y0, z0, short_horizon * (1 + 1e-9)).velocity), 0.0);
  for (double horizon : {5.0, 20.0, 40.0, 60.0, 69.36, 1000.0, 1e6}) {
    const double tau = o.first_rest(y0, z0, a0, v, sigma, horizon, root);
    EXPECT_NEAR(tau, short_horizon, 1e-15) << "horizon " << horizon;
    EXPECT_NEAR(root.velocity, v, 1e-12) << "horizon " << horizon;
  }
}

TEST(DampedRootOnALongHorizon, EpisodesUpToAStickDoNotDependOnTheWindow) {
  std::vector<double> first_stick;
  for (double window : {5.0, 20.0, 40.0, 60.0, 69.36}) {
    const std::vector<level_switch> none;
    given_level_switches sw(none);
    recorded r;
    (void)simulate_model(fuzzer_model(window),
                         model_initial_state{0.24893057637147883, -2.5516592618846694, 0}, sw, r);
    ASSERT_GE(r.episodes.size(), 2u) << "window " << window;
    EXPECT_EQ(r.episodes[0].kind, mode::slip);
    EXPECT_EQ(r.episodes[1].kind, mode::stick) << "window " << window;
    first_stick.push_back(r.episodes[1].start);
  }
  for (double t : first_stick) EXPECT_NEAR(t, first_stick.front(), 1e-15);
}

// The damped engine visits every half-period of a slip: a window of more
// than 1e6 radians of the natural frequency is refused by name instead of
// hanging (fuzz_model_family found k ~ 4e49, m = 50, c = 19: ~1e21
// half-periods in 5 ms).
TEST(DampedRootOnALongHorizon, AWindowOfTooManyPeriodsIsRefusedByName) {
  oscillator_model m = fuzzer_model(0.3);
  m.mass = 50.0;
  m.stiffness = 3.98e49;
  m.damping = 19.0;
  try {
    validate(m);
    ADD_FAILURE() << "accepted";
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::invalid_input);
    EXPECT_NE(std::string(e.what()).find("k (stiffness)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("sqrt(k/m) t_a <= 1e6"), std::string::npos) << e.what();
  }
  m.damping = 0.0;  // undamped slips have closed-form roots: accepted
  EXPECT_NO_THROW(validate(m));
  m = fuzzer_model(1e4);
  m.mass = 1.0;
  m.stiffness = 80.0;  // the users' largest scale
  EXPECT_NO_THROW(validate(m));
}

}  // namespace
}  // namespace stickslip
