// Sweeps over points with uncertain parameters (sweep_spec::uncertain).
// Oracles independent of the code under test:
//   - the mixture: E[R] over mu ~ uniform(a, b) equals the average of E[R | mu]
//     over a fine midpoint grid of fixed-mu sweeps (the lane engine, other
//     streams), within 4 combined standard errors;
//   - replay: realization r drawn and run alone through the sensitivity
//     design's entry points (uncertain_block.hpp) gives the sweep's record r
//     to the bit, for the paper engine and the family engine;
//   - invariants of the streams: 1 and 2 threads, the fast and reference
//     engine settings, other points, other realization counts and block
//     sizes leave every record the same bits; common random numbers make
//     every point draw the same values.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "same_bits.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/uncertainty/uncertain_block.hpp"

namespace stickslip {
namespace {

using testing_support::same_bits;

uncertain_parameter law_of(const char* symbol, const char* text) {
  return {symbol, parse_law(text, symbol)};
}

// The paper model at k = 40 with mu ~ gamma, swept over lambda.
sweep_spec gamma_mu_sweep() {
  sweep_spec s;
  s.base.stiffness = 40.0;
  s.base.window = 20.0;
  s.axes = {{"lambda", {1.0, 3.8}}};
  s.uncertain = {law_of("mu", "gamma(mean=5,cv=0.2)")};
  s.realizations = 300;
  s.block_size = 40;
  s.seed = 2026;
  s.keep_records = true;
  return s;
}

void expect_same_records(const std::vector<realization_record>& a,
                         const std::vector<realization_record>& b, std::size_t n) {
  ASSERT_GE(a.size(), n);
  ASSERT_GE(b.size(), n);
  for (std::size_t r = 0; r < n; ++r) {
    EXPECT_TRUE(same_bits(a[r], b[r])) << "record " << r;
    ASSERT_EQ(a[r].drawn_values.size(), b[r].drawn_values.size());
    for (std::size_t i = 0; i < a[r].drawn_values.size(); ++i)
      EXPECT_TRUE(same_bits(a[r].drawn_values[i], b[r].drawn_values[i])) << "record " << r;
  }
}

TEST(UncertainMixture, OneAndTwoThreadsGiveTheSameBits) {
  const sweep_spec s = gamma_mu_sweep();
  const result_set one = run_sweep(s, 1), two = run_sweep(s, 2);
  ASSERT_EQ(one.points.size(), 2u);
  for (std::size_t i = 0; i < one.points.size(); ++i) {
    EXPECT_TRUE(same_bits(one.points[i].stats, two.points[i].stats)) << "point " << i;
    expect_same_records(one.records[i], two.records[i], s.realizations);
  }
}

TEST(UncertainMixture, EngineSettingDoesNotChangeTheBits) {
  sweep_spec s = gamma_mu_sweep();
  s.realizations = 120;
  const result_set fast = run_sweep(s, 1);
  s.engine = sweep_engine::reference;
  const result_set reference = run_sweep(s, 1);
  for (std::size_t i = 0; i < fast.points.size(); ++i) {
    EXPECT_TRUE(same_bits(fast.points[i].stats, reference.points[i].stats)) << "point " << i;
    expect_same_records(fast.records[i], reference.records[i], s.realizations);
  }
}

// Each record holds the values its realization drew, and they vary: the
// realizations do not all run at the median.
TEST(UncertainMixture, RecordsCarryTheirOwnDraws) {
  const sweep_spec s = gamma_mu_sweep();
  const result_set rs = run_sweep(s, 1);
  for (const auto& records : rs.records) {
    ASSERT_EQ(records.size(), s.realizations);
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& r : records) {
      ASSERT_EQ(r.drawn_values.size(), 1u);
      lo = std::min(lo, r.drawn_values[0]);
      hi = std::max(hi, r.drawn_values[0]);
    }
    // 300 draws of gamma(5, cv 0.2): the range spans several sd (sd = 1).
    EXPECT_LT(lo, 4.0);
    EXPECT_GT(hi, 6.0);
  }
  // The point stands for the law's median (point_parameters).
  EXPECT_EQ(rs.points[0].parameters.friction_coefficient, quantile(s.uncertain[0].law, 0.5));
}

// Realization r replayed alone: its key (from the point with its base value
// of mu, which the key ignores), its draws, its run.
void expect_replays(const sweep_spec& s) {
  const result_set rs = run_sweep(s, 1);
  for (std::size_t i = 0; i < point_count(s); ++i) {
    model_parameters point = s.base;
    const auto idx = point_index(s, i);
    for (std::size_t k = 0; k < s.axes.size(); ++k)
      set_parameter(point, s.axes[k].name, s.axes[k].values[idx[k]]);
    const std::uint64_t key = uncertain_stream_key(s, point);
    EXPECT_EQ(key, uncertain_stream_key(s, point_parameters(s, i)));
    for (std::uint64_t r : {std::uint64_t{0}, std::uint64_t{7}, s.realizations - 1}) {
      const std::vector<double> values = draw_values(s.uncertain, s.seed, key, r);
      const model_parameters drawn = with_values(point, s.uncertain, values);
      const uncertain_run run = simulate_uncertain_realization(s, drawn, key, r);
      const realization_record& swept = rs.records[i][r];
      EXPECT_TRUE(same_bits(run.record, swept)) << "point " << i << " realization " << r;
      ASSERT_EQ(swept.drawn_values.size(), values.size());
      for (std::size_t d = 0; d < values.size(); ++d)
        EXPECT_TRUE(same_bits(swept.drawn_values[d], values[d]));
    }
  }
}

TEST(UncertainMixture, RealizationReplaysAloneOnThePaperEngine) { expect_replays(gamma_mu_sweep()); }

TEST(UncertainMixture, RealizationReplaysAloneOnTheFamilyEngine) {
  sweep_spec s = gamma_mu_sweep();
  s.base.damping = 0.5;  // damped: the family engine
  s.uncertain.push_back(law_of("k", "lognormal(mean=40,cv=0.1)"));
  s.realizations = 60;
  expect_replays(s);
}

// A point's draws and runs depend on (seed, its key, r) only: not on the
// other points, the realization count or the block size.
TEST(UncertainMixture, DrawsDependOnNothingElse) {
  const sweep_spec s = gamma_mu_sweep();
  const result_set both = run_sweep(s, 1);
  sweep_spec alone = s;
  alone.axes = {{"lambda", {3.8}}};
  alone.realizations = 150;
  alone.block_size = 17;
  const result_set one = run_sweep(alone, 1);
  expect_same_records(both.records[1], one.records[0], alone.realizations);
}

// Common random numbers: realization r of every point draws the same
// values; without, the points' draws differ.
TEST(UncertainMixture, CommonRandomNumbersShareTheDraws) {
  sweep_spec s = gamma_mu_sweep();
  s.realizations = 50;
  const result_set own = run_sweep(s, 1);
  s.common_random_numbers = true;
  const result_set common = run_sweep(s, 1);
  std::size_t equal_own = 0;
  for (std::uint64_t r = 0; r < s.realizations; ++r) {
    EXPECT_TRUE(same_bits(common.records[0][r].drawn_values[0],
                          common.records[1][r].drawn_values[0]));
    equal_own += own.records[0][r].drawn_values[0] == own.records[1][r].drawn_values[0];
  }
  EXPECT_EQ(equal_own, 0u);
}

// Changing a law changes the streams and the results' identity.
TEST(UncertainMixture, LawsArePartOfTheIdentity) {
  const sweep_spec s = gamma_mu_sweep();
  sweep_spec other = s;
  other.uncertain[0] = law_of("mu", "gamma(mean=5,cv=0.25)");
  EXPECT_NE(uncertain_stream_key(s, s.base), uncertain_stream_key(other, other.base));
  EXPECT_FALSE(same_results(s, other));
  EXPECT_NE(fingerprint(s), fingerprint(other));
  EXPECT_NE(first_difference(s, other).find("uncertain"), std::string::npos)
      << first_difference(s, other);
  EXPECT_EQ(deserialize_sweep_spec(serialize(s)), s);
  // The base value of an uncertain symbol changes nothing.
  sweep_spec moved = s;
  moved.base.friction_coefficient = 3.0;
  EXPECT_EQ(uncertain_stream_key(s, s.base), uncertain_stream_key(moved, moved.base));
}

// The mixture oracle. With mu ~ uniform(a, b), E[R] = (1/(b-a)) int E[R|mu] dmu,
// which the midpoint rule over G fixed-mu points approximates (error
// O(h^2 max|E[R|mu]''|), far below the noise here). The fixed-mu sweep runs
// the lane engine on the points' own streams, independent of the mixture's,
// so the difference has variance SE_mix^2 + SE_grid^2 with
// SE_grid^2 = sum_g SE_g^2 / G^2.
TEST(UncertainMixture, MixtureMeanIsTheAverageOverTheLaw) {
  const double a = 2.0, b = 7.0;
  const std::size_t grid = 20;
  sweep_spec mixture;
  mixture.base.stiffness = 40.0;
  mixture.base.window = 20.0;
  mixture.uncertain = {law_of("mu", "uniform(2,7)")};
  mixture.realizations = 8000;
  mixture.seed = 11;
  const result_set mixed = run_sweep(mixture, 2);
  const mean_variance& m = mixed.points[0].stats.stick_fraction;

  sweep_spec fixed = mixture;
  fixed.uncertain.clear();
  fixed.realizations = 1000;
  axis mu{"mu", {}};
  for (std::size_t g = 0; g < grid; ++g)
    mu.values.push_back(a + (b - a) * (static_cast<double>(g) + 0.5) / grid);
  fixed.axes = {mu};
  const result_set points = run_sweep(fixed, 2);
  double average = 0.0, grid_var = 0.0;
  for (const auto& p : points.points) {
    average += p.stats.stick_fraction.mean() / grid;
    grid_var += std::pow(p.stats.stick_fraction.std_error(), 2) / (grid * grid);
  }
  const double se = std::sqrt(std::pow(m.std_error(), 2) + grid_var);
  EXPECT_LT(std::abs(m.mean() - average), 4.0 * se)
      << "mixture " << m.mean() << " +- " << m.std_error() << ", grid " << average << " +- "
      << std::sqrt(grid_var);
  // The oracle has teeth: E[R | mu] varies over the law's range by more than
  // 20 standard errors of the difference, so a law drawn over another range
  // (or not drawn at all, every realization at the base mu = 5) shows.
  const double spread = points.points.front().stats.stick_fraction.mean() -
                        points.points.back().stats.stick_fraction.mean();
  EXPECT_GT(std::abs(spread), 20.0 * se);
  // Every realization at mu = 5 (grid points 4.875 and 5.125 around it)
  // would be off by more than 4 standard errors.
  const double at_base = 0.5 * (points.points[11].stats.stick_fraction.mean() +
                                points.points[12].stats.stick_fraction.mean());
  EXPECT_GT(std::abs(m.mean() - at_base), 4.0 * se) << "E[R | mu = 5] ~ " << at_base;
}

}  // namespace
}  // namespace stickslip
