// Regression: a damped slip that leaves x' = v with almost no relative
// acceleration "returned" at once, and the mass was put back on the edge.
//
// Found by fuzz_model_family: k = 80.3, m = 1, c = 0.0179, mu_s a few ulps
// above mu_k, v = 9.84. A stick breaks at the outward edge; the slip starts
// at x' = v with x'' = (mu_k - mu_s) g ~ -5e-17. Its relative velocity then
// grows like omega_0^2 v t^2 / 2, below ulp(v) = 1.8e-15 for the first few
// nanoseconds, so x'(t) computes as v exactly. The root search took g = 0
// at the end of a short piece (the next switch 3.7e-10 s on) for a return,
// the contact clamped x back to the edge, and the mass stayed there while
// the belt moved on, in ever shorter pieces up to the work bound.
// A first fix (g == 0 at the end is no return) still took the horizons where
// the rounding gives x' one ulp beyond v for a return.
// Oracles: the Taylor expansion of x' about the start (x' - v below half
// an ulp of v over the short horizon, so no return can be resolved there),
// the motion to the horizon at the belt's speed, and, over a long horizon,
// no return at all (x' sampled densely stays below v).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "stickslip/model/damped_slip.hpp"
#include "stickslip/model/oscillator_model.hpp"

namespace stickslip {
namespace {

struct edge_departure {
  oscillator_model m;
  double v = 9.8420975012632717, sigma = 1.0, y0 = 0.0, a0 = 0.0;
  edge_departure() {
    m.mass = 1.0;
    m.stiffness = 80.312603254298963;
    m.gravity = 0.49737180543531906;
    m.damping = 0.017923459850631405;
    m.static_friction = 0.77697566538918639;
    m.kinetic_friction = 0.77697566538918628;
    const double as = m.static_friction * m.mass * m.gravity / m.stiffness;
    const double b = -m.damping / m.stiffness * v;
    y0 = (b + as) - sigma * m.kinetic_offset();  // x on the outward edge
    a0 = sigma * (m.kinetic_friction - m.static_friction) * m.gravity;  // exact, as the engine
  }
};

TEST(DampedDepartureBelowResolution, NoReturnBeforeTheVelocityLeavesTheBelt) {
  const edge_departure e;
  const detail::damped_oscillator o(e.m.natural_frequency(), e.m.decay_rate());
  ASSERT_EQ(o.regime(), detail::damping_regime::under);
  ASSERT_LT(e.a0, 0.0);
  const double horizon = 3.7430050802823338e-10;
  // Taylor about t = 0: x' - v = a0 t + x'''(0) t^2 / 2 + O(t^3), x'''(0) =
  // -omega_0^2 v - 2 gamma a0: below half an ulp of v on the whole horizon
  const double jerk = -o.omega_squared() * e.v - 2.0 * o.gamma() * e.a0;
  const double departure = std::abs(e.a0 * horizon + 0.5 * jerk * horizon * horizon);
  ASSERT_LT(departure, 0.5 * (std::nextafter(e.v, 2.0 * e.v) - e.v));
  detail::damped_state root{}, at_horizon{};
  at_horizon.velocity = std::nan("");
  const double tau = o.first_rest(e.y0, e.v, e.a0, e.v, e.sigma, horizon, root, &at_horizon);
  EXPECT_EQ(tau, std::numeric_limits<double>::infinity()) << "a return at " << tau;
  // the mass went with the belt: x moved v horizon
  ASSERT_FALSE(std::isnan(at_horizon.velocity));
  EXPECT_NEAR(at_horizon.y - e.y0, e.v * horizon, 1e-15 * e.v * horizon + 1e-18);
}

// Any short horizon: the computed x' at its end is v, or one or two ulps
// either side of it (the basis terms nearly cancel), while the Taylor bound
// keeps the true departure below a quarter ulp. No horizon gives a return.
TEST(DampedDepartureBelowResolution, NoReturnWhateverTheRoundingAtTheHorizon) {
  const edge_departure e;
  const detail::damped_oscillator o(e.m.natural_frequency(), e.m.decay_rate());
  const double jerk = -o.omega_squared() * e.v - 2.0 * o.gamma() * e.a0;
  const double quarter_ulp = 0.25 * (std::nextafter(e.v, 2.0 * e.v) - e.v);
  int below = 0, above = 0, equal = 0;
  for (int i = 0; i <= 2000; ++i) {
    const double horizon = 1e-10 + 1e-9 * i / 2000.0;
    if (std::abs(e.a0 * horizon + 0.5 * jerk * horizon * horizon) >= quarter_ulp) continue;
    const double x_dot = o.advance(e.y0, e.v, horizon).velocity;
    (x_dot < e.v ? below : x_dot > e.v ? above : equal) += 1;
    detail::damped_state root{};
    const double tau = o.first_rest(e.y0, e.v, e.a0, e.v, e.sigma, horizon, root);
    EXPECT_EQ(tau, std::numeric_limits<double>::infinity())
        << "horizon " << horizon << ": a return at " << tau;
  }
  // the rounding takes every sign in this range (the case g_hi < 0, i.e. x'
  // above v for sigma = 1, is the one a sign test alone gets wrong)
  EXPECT_GT(above, 0);
  EXPECT_GT(equal, 0);
  EXPECT_GT(below + above + equal, 500);
  // the reviewer's horizon, where the rounding gives g < 0
  detail::damped_state root{};
  EXPECT_EQ(o.first_rest(e.y0, e.v, e.a0, e.v, e.sigma, 1.002e-10, root),
            std::numeric_limits<double>::infinity());
}

// Over a long horizon the slip never comes back to v: damping shrinks every
// later extremum of x' (docs/model.md, as for mu_s = mu_k). The root search
// agrees with x' sampled densely, and with the start at a0 = 0 exactly.
TEST(DampedDepartureBelowResolution, NoReturnOnALongHorizonEither) {
  const edge_departure e;
  const detail::damped_oscillator o(e.m.natural_frequency(), e.m.decay_rate());
  detail::damped_state root{};
  EXPECT_EQ(o.first_rest(e.y0, e.v, e.a0, e.v, e.sigma, 10.0, root),
            std::numeric_limits<double>::infinity());
  EXPECT_EQ(o.first_rest(e.y0, e.v, 0.0, e.v, e.sigma, 10.0, root),
            std::numeric_limits<double>::infinity());
  for (int i = 1; i <= 10000; ++i) {
    const double t = 10.0 * i / 10000.0;
    ASSERT_GT(e.sigma * (e.v - o.advance(e.y0, e.v, t).velocity), 0.0) << "t = " << t;
  }
}

}  // namespace
}  // namespace stickslip
