// Per-realization energy balance of the model family engine: over [0, t_a],
//   E(t_a) - E(0) = W_friction + W_damping,   E = m x'^2 / 2 + k x^2 / 2,
// where, piece by piece (segment),
//   slip:  W_friction = sigma mu_k m g (x_end - x_start)   (f constant),
//          W_damping  = -c int x'^2 dt                     (Gauss-Legendre),
//   stick: W_friction = int (k x + c v) v dt = v (k (x0 d + v d^2 / 2) + c v d)
//          (the work the belt does through the stick), W_damping = -c v^2 d.
// The quadrature is exact to rounding (5 nodes on sub-intervals of at most
// 1/64 of the period of the fastest mode: error ~ (omega h)^10), so the balance must close
// to rounding. It fails if any state handed from one piece to the next, or
// any closed form, breaks the equation of motion.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "reference/model_scenario.hpp"

namespace stickslip {
namespace {

double energy(const oscillator_model& m, double x, double z) {
  return 0.5 * m.mass * z * z + 0.5 * m.stiffness * x * x;
}

// int_{start}^{end} x'(t)^2 dt on the segment's closed form.
double squared_velocity_integral(const segment& s, double period) {
  constexpr double nodes[] = {0.0, 0.5384693101056831, -0.5384693101056831, 0.9061798459386640,
                              -0.9061798459386640};
  constexpr double weights[] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                0.2369268850561891, 0.2369268850561891};
  const double length = s.end - s.start;
  if (!(length > 0)) return 0.0;
  const int pieces = static_cast<int>(std::ceil(64.0 * length / period));
  const double h = length / pieces;
  double sum = 0.0;
  for (int p = 0; p < pieces; ++p) {
    const double mid = s.start + (p + 0.5) * h;
    for (int j = 0; j < 5; ++j) {
      const double z = evaluate(s, mid + 0.5 * h * nodes[j]).velocity;
      sum += weights[j] * 0.5 * h * z * z;
    }
  }
  return sum;
}

TEST(ModelEnergy, BalanceClosesPerRealizationAcrossTheFamily) {
  std::mt19937_64 rng(0xe4e26ULL);
  double worst = 0;
  int damped = 0;
  for (int n = 0; n < 400; ++n) {
    const reference::model_scenario s = reference::draw_model_scenario(rng);
    const reference::model_exact_run r = reference::run_model_exact(s);
    const oscillator_model& m = s.model;
    // The shortest time scale of a slip: omega_0, or the fast over-damped mode.
    const double w0 = m.natural_frequency(), gamma = m.decay_rate();
    const double fastest = std::max(w0, gamma + std::sqrt(std::abs(gamma * gamma - w0 * w0)));
    const double period = 2.0 * std::numbers::pi / fastest;
    double friction = 0, damping = 0, scale = 0;
    for (const segment& g : r.segments) {
      const double d = g.end - g.start;
      if (g.kind == mode::stick) {
        const double v = g.belt_velocity;
        const double wf = v * (m.stiffness * (g.position * d + 0.5 * v * d * d) + m.damping * v * d);
        friction += wf;
        damping -= m.damping * v * v * d;
        scale += std::abs(wf) + m.damping * v * v * d;
      } else {
        const double sigma = g.center > 0 ? 1.0 : -1.0;
        const double x_end = evaluate(g, g.end).position;
        const double wf = sigma * m.kinetic_friction * m.mass * m.gravity * (x_end - g.position);
        const double wd = -m.damping * squared_velocity_integral(g, period);
        friction += wf;
        damping += wd;
        scale += std::abs(wf) + std::abs(wd) + energy(m, g.position, g.velocity);
      }
    }
    const phase_point end = evaluate(r.segments.back(), m.window);
    const double e0 = energy(m, s.ic.position, s.ic.velocity), e1 = energy(m, end.position, end.velocity);
    const double imbalance = std::abs((e1 - e0) - (friction + damping));
    scale += e0 + e1;
    worst = std::max(worst, imbalance / scale);
    EXPECT_LE(imbalance, 2e-12 * scale) << "scenario " << n << ": dE " << e1 - e0 << " W_f "
                                         << friction << " W_c " << damping;
    damped += m.damping > 0;
  }
  std::printf("energy balance: worst imbalance %.3g of the energy turnover (%d damped)\n", worst, damped);
  EXPECT_GT(damped, 200);
}

}  // namespace
}  // namespace stickslip
