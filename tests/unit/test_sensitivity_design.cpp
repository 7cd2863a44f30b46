// The sensitivity design run through the sweep (uncertainty/sensitivity_design.hpp)
// against oracles that do not use pick-freeze:
//   - one uncertain input: the mean response depends on it alone, so its
//     first- and total-order indices are 1 exactly;
//   - the shares: Var g(theta) and E Var(Y | theta) computed independently by
//     fixed-value sweeps on a midpoint grid of the input's law (quadrature
//     of the law, the sweep's own moments at each node);
//   - bit-identical results for 1 and 2 threads, and the same design rows
//     whatever the block size splits them into.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "stickslip/sweep.hpp"
#include "stickslip/uncertainty/parameter_law.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"
#include "stickslip/uncertainty/sobol.hpp"

namespace stickslip {
namespace {

sweep_spec design(std::vector<uncertain_parameter> laws, std::uint64_t rows, std::uint64_t seed) {
  sweep_spec s;
  s.sensitivity_statistic = std::string("R");  // (assigning a literal trips GCC 12's -Wrestrict)
  s.base.stiffness = 40.0;
  s.base.window = 20.0;
  s.base.switch_rate = 3.8;
  s.uncertain = std::move(laws);
  s.family_statistics = false;
  s.realizations = rows;
  s.block_size = 64;
  s.seed = seed;
  return s;
}

uncertain_parameter mu_uniform(double lo, double hi) {
  return {"mu", parse_law(fmt::format("uniform(min={},max={})", lo, hi), "--mu")};
}

TEST(SensitivityDesign, OneInputExplainsAllOfTheMeanResponse) {
  const auto rs = run_sweep(design({mu_uniform(2.0, 7.0)}, 4000, 11), 2);
  const auto est = sobol_indices(rs.points.front().stats.sensitivity);
  ASSERT_EQ(est.first_order.size(), 1u);
  EXPECT_EQ(est.rows, 4000u);
  EXPECT_EQ(rs.points.front().stats.realizations, 4000u);  // rows; each ran 4 realizations
  for (const auto& e : {est.first_order[0], est.total_order[0]}) {
    EXPECT_LE(e.low, 1.0) << e.value;
    EXPECT_GE(e.high, 1.0) << e.value;
    EXPECT_LT(e.half_width(), 0.2);
  }
  // The response's own first-order index is the parameter share here.
  EXPECT_NEAR(est.response_first_order[0].value, est.parameter_share.value,
              4.0 * std::max(est.response_first_order[0].half_width(),
                             est.parameter_share.half_width()) / 1.96);
}

TEST(SensitivityDesign, SharesAgreeWithQuadratureOfFixedValueSweeps) {
  // Oracle: mu on a midpoint grid of uniform(2, 7); at each node a plain sweep
  // gives g(mu) = mean R and Var(R | mu); then Var g and E Var(R | mu) by the
  // midpoint rule. Its own error: sampling (the node means) plus quadrature
  // (small: g is smooth and 40 nodes).
  const int nodes = 40;
  sweep_spec grid;
  grid.base.stiffness = 40.0;
  grid.base.window = 20.0;
  grid.base.switch_rate = 3.8;
  grid.family_statistics = false;
  grid.realizations = 20000;
  grid.seed = 99;
  axis mu{"mu", {}};
  for (int i = 0; i < nodes; ++i) mu.values.push_back(2.0 + 5.0 * (i + 0.5) / nodes);
  grid.axes = {mu};
  const auto g = run_sweep(grid, 2);
  double mean = 0, second = 0, within = 0, within_var_of_mean_sum = 0;
  for (const auto& p : g.points) {
    const double m = p.stats.stick_fraction.mean(), v = p.stats.stick_fraction.variance();
    mean += m / nodes;
    second += m * m / nodes;
    within += v / nodes;
    within_var_of_mean_sum += v / static_cast<double>(p.stats.realizations);
  }
  const double var_g = second - mean * mean;
  const double oracle_share = var_g / (var_g + within);

  const auto rs = run_sweep(design({mu_uniform(2.0, 7.0)}, 20000, 5), 2);
  const auto est = sobol_indices(rs.points.front().stats.sensitivity);
  // The design's interval and the oracle's own sampling error (node means
  // enter var_g with variance ~ 4 g'^2 Var(mean)/nodes; bounded crudely by
  // the mean within-node variance of the means, relative to Var Y).
  const double oracle_se = std::sqrt(4.0 * var_g * within_var_of_mean_sum / nodes) /
                           (var_g + within);
  const double se = std::hypot(est.parameter_share.half_width() / 1.96, oracle_se);
  std::printf("parameter share: design %.4f +- %.4f, quadrature oracle %.4f (se %.4f)\n",
              est.parameter_share.value, est.parameter_share.half_width(), oracle_share, oracle_se);
  EXPECT_NEAR(est.parameter_share.value, oracle_share, 4.0 * se)
      << "design " << est.parameter_share.value << " oracle " << oracle_share;
  EXPECT_NEAR(est.intrinsic_share.value, 1.0 - oracle_share, 4.0 * se);
  EXPECT_NEAR(est.mean, mean, 4.0 * std::sqrt(est.variance / (3.0 * 20000)) + 4.0 * std::sqrt(within_var_of_mean_sum) / nodes);
}

TEST(SensitivityDesign, SameBitsForAnyThreadsAndBlockSize) {
  auto s = design({mu_uniform(2.0, 7.0), {"lambda", parse_law("loguniform(0.5,10)", "--lambda")}},
                  500, 3);
  const auto one = run_sweep(s, 1);
  const auto two = run_sweep(s, 2);
  EXPECT_EQ(one.points.front().stats.sensitivity, two.points.front().stats.sensitivity);
  // Rows are the same draws whatever the blocks: the moments agree to
  // rounding (the merge order differs, not the rows).
  s.block_size = 7;
  const auto other = run_sweep(s, 2);
  const auto a = sobol_indices(one.points.front().stats.sensitivity);
  const auto b = sobol_indices(other.points.front().stats.sensitivity);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(a.first_order[i].value, b.first_order[i].value, 1e-9);
    EXPECT_NEAR(a.total_order[i].value, b.total_order[i].value, 1e-9);
  }
}

TEST(SensitivityDesign, RefusesWhatIsNotADesign) {
  auto s = design({}, 100, 1);
  EXPECT_THROW(validate(s), error);  // no uncertain input
  s = design({mu_uniform(2, 7)}, 100, 1);
  s.axes = {{"lambda", {1.0, 2.0}}};
  EXPECT_THROW(validate(s), error);
  s = design({mu_uniform(2, 7)}, 100, 1);
  s.sensitivity_statistic = "first_stick_duration";  // not one value per realization
  EXPECT_THROW(validate(s), error);
  s.sensitivity_statistic = "no_such_statistic";
  EXPECT_THROW(validate(s), error);
}

}  // namespace
}  // namespace stickslip
