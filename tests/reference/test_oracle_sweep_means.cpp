// The sweep's per-point means agree with means computed by the
// independent RK4 oracle (oracle.hpp) on the same realizations: the oracle
// is fed the initial conditions and belt switch times that the sweep's
// Philox streams produce for (seed, point, realization), and never sees the
// closed form. Counts must agree exactly; means of durations within the
// oracle's documented boundary error.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "reference/oracle.hpp"
#include "stickslip/belt_switches.hpp"
#include "stickslip/sweep.hpp"

using namespace stickslip;

namespace {

struct oracle_means {
  double R = 0, sticks = 0, slips = 0, stick_duration = 0;
  std::uint64_t stick_count = 0;
};

// At the oracle's default 800 steps per period (h = 1.2 ms at k = 40) this
// comparison found realizations where the oracle misses a stick: a slip
// reversal just outside the band (x = -0.12302, a = 0.122625; mu = 0.5,
// lambda = 0.5, seed 2024, realization 3) is followed by a 0.8 ms excursion
// with relative velocity <= 3e-6 m/s back to the mirror point x = -0.12223,
// inside the band, where a 0.245 s stick starts. The exact integrator finds
// it (docs/model.md: consecutive roots are mirror images); a step longer than
// the excursion cannot. 40000 steps per period (h = 25 us) resolves it.
constexpr reference::oracle_options fine{40000, 0, 2'000'000'000};

oracle_means run_oracle(const sweep_spec& s, const model_parameters& p) {
  oracle_means m;
  double d_sum = 0;
  const auto key = point_key(p);
  for (std::uint64_t r = 0; r < s.realizations; ++r) {
    const auto ic = draw_initial_conditions(s.initial, s.seed, key, r);
    poisson_switches sw(p.switch_rate, s.seed, key, r);
    std::vector<double> times;
    for (double t = sw.next(); t < p.window; t = sw.next()) times.push_back(t);
    const auto res = reference::integrate_reference(p, ic, times, fine);
    double stick_time = 0;
    std::uint64_t st = 0, sl = 0;
    for (const auto& e : res.episodes) {
      if (e.kind == mode::stick && e.duration() > 0) {
        ++st;
        stick_time += e.duration();
        d_sum += e.duration();
      } else if (e.kind == mode::slip && st > 0) {
        ++sl;
      }
    }
    m.R += stick_time / p.window;
    m.sticks += st / p.window;
    m.slips += sl / p.window;
    m.stick_count += st;
  }
  const double n = static_cast<double>(s.realizations);
  m.R /= n;
  m.sticks /= n;
  m.slips /= n;
  m.stick_duration = d_sum / static_cast<double>(m.stick_count);
  return m;
}

}  // namespace

TEST(OracleSweepMeans, AgreeOnSeveralGridPoints) {
  sweep_spec s;
  s.base.stiffness = 40.0;
  s.base.window = 5.0;
  s.realizations = 150;
  s.seed = 2024;
  s.axes = {{"lambda", {0.5, 3.8}}, {"mu", {0.5, 5.0}}};
  const auto rs = run_sweep(s, 2);
  for (const auto& pt : rs.points) {
    const auto o = run_oracle(s, pt.parameters);
    const auto& st = pt.stats;
    SCOPED_TRACE(testing::Message() << "lambda " << pt.parameters.switch_rate << " mu "
                                    << pt.parameters.friction_coefficient);
    // Every realization's stick count is an integer: the sums must be equal.
    EXPECT_EQ(st.stick_duration.count(), o.stick_count);
    EXPECT_DOUBLE_EQ(st.sticks_per_time.mean(), o.sticks);
    EXPECT_DOUBLE_EQ(st.slips_per_time.mean(), o.slips);
    // Durations: each boundary carries the oracle's error, ~1e-9 s here
    // (test_oracle_agreement.cpp measures 2e-10 at this step size); a
    // realization's stick time has at most 2 S_T boundaries.
    const double boundary = 1e-8;
    EXPECT_NEAR(st.stick_fraction.mean(), o.R, 2 * boundary * o.sticks);
    EXPECT_NEAR(st.stick_duration.mean(), o.stick_duration, 2 * boundary);
    // And both are far from trivial, so the comparison means something.
    EXPECT_GT(o.R, 0.02);
  }
}
