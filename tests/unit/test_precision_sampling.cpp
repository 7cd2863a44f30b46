// Sampling tools for precision: common random numbers (sweep_spec::
// common_random_numbers), the likelihood-ratio derivative of a mean over
// lambda and the control-variate mean (accumulators/score_moments.hpp), and
// adaptive sampling to a target CI half-width (sweep_spec::target_statistic).
// Statistical checks use fixed seeds and tolerances from standard errors.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <tuple>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/precision/crn_slopes.hpp"
#include "stickslip/replay.hpp"
#include "stickslip/statistics_schema.hpp"
#include "stickslip/sweep.hpp"
#include "figure_spec.hpp"
#include "same_bits.hpp"

namespace stickslip {
namespace {
using testing_support::same_bits;

// The paper's figures (k = 40), mu = 5, lambda over `lambdas`.
sweep_spec figure_spec(std::vector<double> lambdas, std::uint64_t n, bool crn,
                       std::uint64_t seed = 13) {
  return testing_support::figure_spec(5.0, std::move(lambdas), n, crn, seed);
}

// Sample mean and variance, with the standard error of the variance from
// the fourth central moment: Var(s^2) ~ (m4 - s^4) / n.
struct moments {
  double mean = 0, var = 0, var_se = 0;
};
moments moments_of(const std::vector<double>& x) {
  const auto n = static_cast<double>(x.size());
  moments m;
  for (double v : x) m.mean += v / n;
  double m2 = 0, m4 = 0;
  for (double v : x) {
    const double d = (v - m.mean) * (v - m.mean);
    m2 += d / n;
    m4 += d * d / n;
  }
  m.var = m2 * n / (n - 1);
  m.var_se = std::sqrt(std::max(0.0, m4 - m2 * m2) / n);
  return m;
}

std::vector<double> stick_fractions(const result_set& rs, std::size_t point) {
  std::vector<double> out;
  for (const auto& r : rs.records[point]) out.push_back(r.stick_fraction);
  return out;
}

// The central difference of mean R between points 0 and 2 (x -+ h) of a
// common-random-number sweep with records, paired per realization, and its
// standard error from the spread of the per-realization differences.
struct paired_difference {
  double mean = 0, std_error = 0;
};
paired_difference central_difference(const result_set& rs, double h) {
  const auto lo = stick_fractions(rs, 0), hi = stick_fractions(rs, 2);
  std::vector<double> d(lo.size());
  for (std::size_t r = 0; r < d.size(); ++r) d[r] = (hi[r] - lo[r]) / (2 * h);
  const auto m = moments_of(d);
  return {m.mean, std::sqrt(m.var / static_cast<double>(d.size()))};
}

TEST(CommonRandomNumbers, PointsShareInitialStateAndUnitExponentials) {
  auto s = figure_spec({1.0, 2.5, 7.0}, 64, true);
  s.keep_records = true;
  const auto rs = run_sweep(s, 1);
  for (std::size_t p = 1; p < 3; ++p)
    for (std::size_t r = 0; r < 64; ++r) {
      const auto &a = rs.records[0][r], &b = rs.records[p][r];
      EXPECT_EQ(a.x0, b.x0);
      EXPECT_EQ(a.xdot0, b.xdot0);
      EXPECT_EQ(a.belt_start, b.belt_start);
    }
  // The switch times: W_j lambda = E_j at every point (up to the rounding
  // of the multiplication by 1/lambda and of the running sum).
  for (std::uint64_t r = 0; r < 4; ++r) {
    const auto p1 = point_parameters(s, 0), p2 = point_parameters(s, 2);
    poisson_switches a(p1.switch_rate, s.seed, stream_key(s, p1), r);
    poisson_switches b(p2.switch_rate, s.seed, stream_key(s, p2), r);
    double ya = 0, yb = 0;
    for (int j = 0; j < 100; ++j) {
      const double na = a.next(), nb = b.next();
      const double ea = (na - ya) * p1.switch_rate, eb = (nb - yb) * p2.switch_rate;
      EXPECT_NEAR(ea, eb, 1e-9 * (1 + ea)) << "r " << r << " j " << j;
      ya = na, yb = nb;
    }
  }
  // Without the flag, each point has its own streams.
  s.common_random_numbers = false;
  const auto ind = run_sweep(s, 1);
  EXPECT_NE(ind.records[0][0].x0, ind.records[1][0].x0);
}

TEST(CommonRandomNumbers, BothEnginesAndReplayGiveTheSameBits) {
  auto s = figure_spec({0.7, 3.8}, 150, true);
  s.keep_records = true;
  const auto fast = run_sweep(s, 2);
  s.engine = sweep_engine::reference;
  const auto ref = run_sweep(s, 1);
  for (std::size_t p = 0; p < 2; ++p) {
    EXPECT_TRUE(same_bits(fast.points[p].stats, ref.points[p].stats));
    for (std::uint64_t r : {0u, 77u, 149u}) {
      replay_request q;
      q.parameters = point_parameters(s, p);
      q.seed = s.seed;
      q.realization = r;
      q.common_random_numbers = true;
      const auto t = replay(q);
      EXPECT_EQ(t.record.stick_fraction, fast.records[p][r].stick_fraction);
      EXPECT_EQ(t.record.events.belt_switches, fast.records[p][r].events.belt_switches);
      EXPECT_EQ(t.record.x0, fast.records[p][r].x0);
      q.common_random_numbers = false;  // the point's own streams: another realization
      EXPECT_NE(replay(q).record.x0, fast.records[p][r].x0);
    }
  }
}

TEST(CommonRandomNumbers, ResultsDoNotDependOnThreads) {
  const auto s = figure_spec({0.5, 1.0, 2.0, 3.8, 8.0}, 700, true);
  const auto one = run_sweep(s, 1), two = run_sweep(s, 2);
  for (std::size_t p = 0; p < one.points.size(); ++p)
    EXPECT_TRUE(same_bits(one.points[p].stats, two.points[p].stats)) << "point " << p;
}

// The point of common random numbers: the difference of the means at two
// neighbouring lambdas has a far smaller variance than with independent
// streams. Per realization, D_r = R_r(lambda_2) - R_r(lambda_1).
TEST(CommonRandomNumbers, DifferencesBetweenNeighboursHaveMuchLowerVariance) {
  const std::uint64_t n = 4000;
  for (const auto& pair : std::vector<std::vector<double>>{{1.0, 1.1}, {3.6, 3.8}}) {
    std::vector<double> d_crn, d_ind;
    for (bool crn : {true, false}) {
      auto s = figure_spec(pair, n, crn);
      s.keep_records = true;
      const auto rs = run_sweep(s, 2);
      const auto a = stick_fractions(rs, 0), b = stick_fractions(rs, 1);
      auto& d = crn ? d_crn : d_ind;
      for (std::size_t r = 0; r < n; ++r) d.push_back(b[r] - a[r]);
    }
    const auto c = moments_of(d_crn), i = moments_of(d_ind);
    std::printf("lambda %g -> %g: Var(D) CRN %.3g +- %.2g, independent %.3g +- %.2g, ratio %.3g\n",
                pair[0], pair[1], c.var, c.var_se, i.var, i.var_se, c.var / i.var);
    // At least 10x lower, beyond 4 standard errors of both variances.
    EXPECT_LT(c.var + 4 * c.var_se, 0.1 * (i.var - 4 * i.var_se));
  }
}

// The likelihood-ratio derivative against common-random-number central
// differences (R(lambda + h) - R(lambda - h)) / 2h, at six lambdas, each
// with its standard error (the differences' from the per-realization
// differences); they must agree within 3.5 combined standard errors, and
// the test must have power (some derivatives many standard errors from 0).
TEST(ScoreDerivative, AgreesWithCommonRandomNumberDifferences) {
  const std::uint64_t n = 20000;
  int strong = 0;
  for (double lambda : {0.3, 0.8, 1.5, 3.0, 6.0, 12.0}) {
    const double h = 0.04 * lambda;
    auto s = figure_spec({lambda - h, lambda, lambda + h}, n, true, 29);
    s.keep_records = true;
    const auto rs = run_sweep(s, 2);
    const auto [fd_mean, fd_se] = central_difference(rs, h);
    const auto& mid = rs.points[1].stats;
    const auto lr = score_derivative(mid.stick_fraction_score, mid.stick_fraction, lambda);
    std::printf("lambda %5.2f: LR %.5f +- %.5f, CRN difference %.5f +- %.5f\n", lambda, lr.value,
                lr.std_error, fd_mean, fd_se);
    EXPECT_LT(std::abs(lr.value - fd_mean), 3.5 * std::hypot(lr.std_error, fd_se))
        << "lambda " << lambda;
    if (std::abs(fd_mean) > 6 * std::hypot(lr.std_error, fd_se)) ++strong;
  }
  EXPECT_GE(strong, 3);
}

// The delta-method standard error of the score derivative against the
// spread of the estimate over independent replicates.
TEST(ScoreDerivative, StandardErrorMatchesTheSpreadOverReplicates) {
  std::vector<double> values;
  double se2 = 0;
  const int m = 60;
  for (int k = 0; k < m; ++k) {
    const auto rs = run_sweep(figure_spec({1.0}, 1000, false, 1000 + k), 2);
    const auto& st = rs.points[0].stats;
    const auto e = score_derivative(st.stick_fraction_score, st.stick_fraction, 1.0);
    values.push_back(e.value);
    se2 += e.std_error * e.std_error / m;
  }
  const auto spread = moments_of(values);
  std::printf("score derivative: replicate variance %.3g +- %.2g, mean reported SE^2 %.3g\n",
              spread.var, spread.var_se, se2);
  EXPECT_NEAR(spread.var, se2, 3.5 * spread.var_se);
}

// Control variate N (known mean lambda t_a): unbiased (the mean over
// replicates of the difference to the plain mean is 0 within its standard
// error), its reported standard error matches its spread, and it reduces
// the variance by the reported factor.
TEST(ControlVariate, IsUnbiasedAndReducesTheVarianceOfTheStickRate) {
  const int m = 80;
  std::vector<double> plain, cv, diff;
  double se2 = 0, reported_gain = 0;
  for (int k = 0; k < m; ++k) {
    const auto rs = run_sweep(figure_spec({0.6}, 1000, false, 5000 + k), 2);
    const auto& st = rs.points[0].stats;
    const auto c = control_variate_mean(st.sticks_per_time_score, st.sticks_per_time);
    plain.push_back(st.sticks_per_time.mean());
    cv.push_back(c.mean.value);
    diff.push_back(c.mean.value - st.sticks_per_time.mean());
    se2 += c.mean.std_error * c.mean.std_error / m;
    reported_gain += c.variance_reduction / m;
  }
  const auto p = moments_of(plain), c = moments_of(cv), d = moments_of(diff);
  std::printf("control variate: Var plain %.3g, Var cv %.3g (+- %.2g), gain %.3g, reported %.3g, "
              "reported SE^2 %.3g, mean difference %.3g +- %.3g\n",
              p.var, c.var, c.var_se, p.var / c.var, reported_gain, se2, d.mean,
              std::sqrt(d.var / m));
  EXPECT_LT(std::abs(d.mean), 3.5 * std::sqrt(d.var / m));  // unbiased
  EXPECT_NEAR(c.var, se2, 3.5 * c.var_se);                  // its SE is honest
  EXPECT_GT(reported_gain, 2.0);
  EXPECT_LT(c.var + 3.5 * c.var_se, p.var / 2);             // it reduces the variance
}

// Adaptive sampling: every point stops at the first block after which the
// half-width meets the target (so one block less would not), the same for
// any thread count.
TEST(TargetCi, EveryPointMeetsTheTargetAtTheFirstBlockThatDoes) {
  auto s = figure_spec({0.2, 0.8, 3.8, 15.0}, 200000, false);
  s.target_statistic = "R";
  s.target_halfwidth = 0.004;
  s.min_realizations = 500;
  const auto one = run_sweep(s, 1), two = run_sweep(s, 2);
  bool differ = false;
  for (std::size_t p = 0; p < one.points.size(); ++p) {
    const auto& st = one.points[p].stats;
    EXPECT_TRUE(same_bits(st, two.points[p].stats)) << "point " << p;
    EXPECT_LE(st.stick_fraction.ci95_half_width(), s.target_halfwidth);
    EXPECT_LT(st.realizations, s.realizations);
    EXPECT_EQ(st.realizations % s.block_size, 0u);
    // One block less: the plain sweep with that many realizations misses it.
    auto fewer = s;
    fewer.target_statistic.clear();
    fewer.axes[0].values = {s.axes[0].values[p]};
    fewer.realizations = st.realizations - s.block_size;
    if (fewer.realizations >= s.min_realizations) {
      const auto f = run_sweep(fewer, 2);
      EXPECT_GT(f.points[0].stats.stick_fraction.ci95_half_width(), s.target_halfwidth);
    }
    if (st.realizations != one.points[0].stats.realizations) differ = true;
    std::printf("lambda %g: %llu realizations, half-width %.5f\n", s.axes[0].values[p],
                static_cast<unsigned long long>(st.realizations),
                st.stick_fraction.ci95_half_width());
  }
  EXPECT_TRUE(differ) << "the realizations are chosen per point";
}

// A target no point can reach is named (a new user's ended with exit 0 and
// no word): how many points stopped at the cap, the widest finite one with
// its parameters, and those with fewer than 2 values (no half-width: NaN,
// not "the widest"); nothing when every point met it.
TEST(TargetCi, AnUnmetTargetIsNamedWithItsWidestPoint) {
  auto s = figure_spec({0.5, 3.8}, 200, false);
  s.target_statistic = "R";
  s.target_halfwidth = 1e-6;
  s.min_realizations = 100;
  auto rs = run_sweep(s, 1);
  const auto* q = find_mean_statistic("R");
  const double w0 = (rs.points[0].stats.*q->moments).ci95_half_width();
  const double w1 = (rs.points[1].stats.*q->moments).ci95_half_width();
  const auto& widest = w0 > w1 ? rs.points[0] : rs.points[1];
  const std::string note = unmet_target_note(rs);
  // One text for the CLI, Python and the outputs' record.
  EXPECT_EQ(note.rfind("2 of 2 grid points did not reach the target 95 % half-width 1e-06 of the "
                       "mean of R within the cap of 200 realizations per point (the widest: ", 0),
            0u) << note;
  EXPECT_NE(note.find(fmt::format("lambda = {}", widest.parameters.switch_rate)), std::string::npos)
      << note;
  EXPECT_NE(note.find("; raise the cap, or read"), std::string::npos) << note;
  // a point without two values: counted apart, never "the widest"
  rs.points[0].stats.*q->moments = mean_variance{};
  const std::string with_nan = unmet_target_note(rs);
  EXPECT_NE(with_nan.find("; 1 of them had fewer than 2 values of R, and no half-width"),
            std::string::npos) << with_nan;
  EXPECT_EQ(with_nan.find("nan"), std::string::npos) << with_nan;
  rs.spec.target_halfwidth = 1.0;  // met where it is defined
  rs.points[0] = rs.points[1];
  EXPECT_EQ(unmet_target_note(rs), "");
}

TEST(TargetCi, BadTargetsAreRefusedByName) {
  auto s = figure_spec({1.0}, 1000, false);
  s.target_statistic = "stick_duration";  // pooled: not one value per realization
  s.target_halfwidth = 0.01;
  EXPECT_THROW(validate(s), error);
  s.target_statistic = "R";
  s.target_halfwidth = -1;
  EXPECT_THROW(validate(s), error);
  s.target_halfwidth = 0.01;
  s.min_realizations = 5000;  // above the cap
  EXPECT_THROW(validate(s), error);
  s.min_realizations = 100;
  EXPECT_NO_THROW(validate(s));
}

}  // namespace
}  // namespace stickslip

namespace stickslip {
namespace {

// The schema row of R.
const quantity_info& stick_fraction_row() {
  return quantities()[quantity_row("stick_fraction")];
}

// The model family (Markov belts, damping) draws with the common key too;
// the score estimators apply only where the belt switches at rate lambda.
TEST(CommonRandomNumbers, FamilyPointsShareTheirRandomNumbersToo) {
  sweep_spec s = figure_spec({1.0}, 40, true);
  s.axes = {{"c", {0.1, 0.5}}, {"r1", {1.0, 2.0}}};
  s.keep_records = true;
  const auto rs = run_sweep(s, 2);
  ASSERT_FALSE(point_parameters(s, 0).is_paper_model());
  for (std::size_t p = 1; p < rs.points.size(); ++p)
    for (std::size_t r = 0; r < 40; ++r) {
      EXPECT_EQ(rs.records[p][r].x0, rs.records[0][r].x0);
      EXPECT_EQ(rs.records[p][r].xdot0, rs.records[0][r].xdot0);
    }
  s.common_random_numbers = false;
  EXPECT_NE(run_sweep(s, 2).records[1][0].x0, rs.records[1][0].x0);
  model_parameters q;
  EXPECT_TRUE(has_poisson_switching(q));
  q.belt_rates = {1.0, 2.0};
  EXPECT_FALSE(has_poisson_switching(q));
}

// The likelihood-ratio derivative over the rates of a Markov belt.
// Independent oracle: common-random-number central differences in r_j
// (the same realizations at r_j - h and r_j + h, paired per realization),
// on a two-level belt with unequal levels and rates, stationary start.
TEST(BeltRateScore, AgreesWithCommonRandomNumberDifferences) {
  const std::uint64_t n = 12000;
  int strong = 0, compared = 0;
  // (r1, r2, t_a): with t_a = 1.5 the start level, drawn from the stationary
  // law that depends on the rates, matters, and so does its score term.
  for (const auto& [r1, r2, window] : {std::tuple{0.8, 2.0, 50.0}, std::tuple{3.0, 1.5, 50.0},
                                       std::tuple{2.5, 6.0, 50.0}, std::tuple{0.5, 1.5, 1.5}}) {
    for (std::size_t j = 0; j < 2; ++j) {
      const double rj = j == 0 ? r1 : r2, h = 0.05 * rj;
      sweep_spec s = figure_spec({1.0}, n, true, 41);
      s.base.window = window;
      s.base.belt_levels = {1.0, -0.5};
      s.base.belt_rates = {r1, r2};
      s.axes = {{j == 0 ? "r1" : "r2", {rj - h, rj, rj + h}}};
      s.keep_records = true;
      const auto rs = run_sweep(s, 2);
      const auto [fd_mean, fd_se] = central_difference(rs, h);
      const auto lr = belt_rate_derivative(rs.points[1].stats, stick_fraction_row(), j);
      std::printf("r = (%.2f, %.2f), d/dr%zu: LR %.5f +- %.5f, CRN difference %.5f +- %.5f\n", r1,
                  r2, j + 1, lr.value, lr.std_error, fd_mean, fd_se);
      ASSERT_TRUE(std::isfinite(lr.value));
      EXPECT_LT(std::abs(lr.value - fd_mean), 3.5 * std::hypot(lr.std_error, fd_se))
          << "r = (" << r1 << ", " << r2 << "), j = " << j;
      ++compared;
      if (std::abs(fd_mean) > 6 * std::hypot(lr.std_error, fd_se)) ++strong;
    }
  }
  EXPECT_EQ(compared, 8);
  EXPECT_GE(strong, 3);
}

// At r1 = r2 = lambda the two rate scores add up to the Poisson score
// (d/dlambda = d/dr1 + d/dr2): with common random numbers both points draw
// the same realizations, so the derivatives agree to rounding. Also: no
// rate derivative where the belt has no rates of its own, and none without
// the family statistics.
TEST(BeltRateScore, RatesEqualToLambdaAddUpToTheLambdaDerivative) {
  const double lambda = 2.0;
  sweep_spec paper = figure_spec({lambda}, 4000, true, 43);
  paper.base.belt_levels = {1.0, -0.5};  // not the paper's model, which (r, r) would resolve to
  sweep_spec rates = paper;
  rates.axes.clear();
  rates.base.belt_rates = {lambda, lambda};
  const auto a = run_sweep(paper, 2), b = run_sweep(rates, 2);
  for (const auto& q : quantities()) {
    if (!q.rate_score) continue;
    const auto d = score_derivative(a.points[0].stats.*q.score, a.points[0].stats.*q.moments, lambda);
    const auto d1 = belt_rate_derivative(b.points[0].stats, q, 0);
    const auto d2 = belt_rate_derivative(b.points[0].stats, q, 1);
    EXPECT_NEAR(d1.value + d2.value, d.value, 1e-9 * (1 + std::abs(d.value))) << q.name;
    EXPECT_TRUE(std::isnan(belt_rate_derivative(a.points[0].stats, q, 0).value)) << q.name;
  }
  rates.family_statistics = false;
  const auto c = run_sweep(rates, 2);
  EXPECT_TRUE(std::isnan(belt_rate_derivative(c.points[0].stats, stick_fraction_row(), 0).value));
}

// The scores are centred: K_j has mean 0 over realizations (within 4 SE),
// from either start level and from the stationary law.
TEST(BeltRateScore, ScoresHaveMeanZero) {
  for (int start : {0, 1, -1}) {
    sweep_spec s = figure_spec({1.0}, 20000, false, 47);
    s.base.belt_levels = {1.0, 0.0};
    s.base.belt_rates = {0.7, 3.0};
    s.axes.clear();
    s.initial.belt_start = start;
    const auto rs = run_sweep(s, 2);
    const auto& m = rs.points[0].stats.stick_fraction_rate_score;
    for (std::size_t j = 0; j < 2; ++j) {
      const double n = static_cast<double>(m[j].count());
      const double mean = m[j].sum(0) / n, var = m[j].sum(1) / n - mean * mean;
      EXPECT_LT(std::abs(mean), 4 * std::sqrt(var / n)) << "start " << start << " j " << j;
      EXPECT_GT(var, 0.0);
    }
  }
}

// Common-random-number finite differences for every parameter
// (precision/crn_slopes.hpp). Independent oracle: the likelihood-ratio
// derivatives (over lambda, and over a Markov belt's rate r1), which use
// one point and no differencing; a narrow central difference must agree
// within 3.5 combined standard errors.
TEST(CrnSlopes, AgreeWithTheLikelihoodRatioDerivatives) {
  const std::uint64_t n = 12000;
  int strong = 0;
  for (double lambda : {0.8, 3.0, 8.0}) {
    const double h = 0.04 * lambda;
    auto s = figure_spec({lambda + h, lambda, lambda - h}, n, true, 53);  // not sorted
    s.keep_records = true;
    const auto rs = run_sweep(s, 2);
    const auto slopes = precision::crn_slopes(rs);
    ASSERT_EQ(slopes.size(), 3u);
    const auto& c = slopes[1].front();  // the middle point; R is the first row
    EXPECT_EQ(c.quantity->summary_name, std::string("R"));
    EXPECT_EQ(c.from, 2u);
    EXPECT_EQ(c.to, 0u);
    EXPECT_EQ(c.pairs, n);
    const auto& mid = rs.points[1].stats;
    const auto lr = score_derivative(mid.stick_fraction_score, mid.stick_fraction, lambda);
    std::printf("lambda %.2f: CRN slope %.5f +- %.5f, LR %.5f +- %.5f\n", lambda, c.slope.value,
                c.slope.std_error, lr.value, lr.std_error);
    EXPECT_LT(std::abs(c.slope.value - lr.value), 3.5 * std::hypot(c.slope.std_error, lr.std_error));
    if (std::abs(lr.value) > 6 * std::hypot(c.slope.std_error, lr.std_error)) ++strong;
    // The end points difference one-sidedly with their only neighbour.
    EXPECT_EQ(slopes[0].front().from, 1u);
    EXPECT_EQ(slopes[0].front().to, 0u);
    EXPECT_EQ(slopes[2].front().from, 2u);
    EXPECT_EQ(slopes[2].front().to, 1u);
  }
  EXPECT_GE(strong, 2);
  // Over a belt rate, on a two-axis grid (the rate axis first).
  sweep_spec s = figure_spec({1.0}, n, true, 59);
  s.base.belt_levels = {1.0, -0.5};
  s.base.belt_rates = {1.0, 2.0};
  s.axes = {{"r1", {0.95, 1.0, 1.05}}, {"mu", {3.0, 5.0}}};
  s.keep_records = true;
  const auto rs = run_sweep(s, 2);
  const auto slopes = precision::crn_slopes(rs);
  for (std::size_t p : {2u, 3u}) {  // r1 = 1.0, mu = 3 and 5
    const auto& c = slopes[p].front();
    EXPECT_EQ(c.axis, 0u);
    const auto lr = belt_rate_derivative(rs.points[p].stats, stick_fraction_row(), 0);
    EXPECT_LT(std::abs(c.slope.value - lr.value), 3.5 * std::hypot(c.slope.std_error, lr.std_error))
        << "point " << p << ": CRN " << c.slope.value << " LR " << lr.value;
  }
}

TEST(CrnSlopes, OnlyWithCommonRandomNumbersAndRecords) {
  auto s = figure_spec({1.0, 2.0}, 50, false);
  s.keep_records = true;
  EXPECT_TRUE(precision::crn_slopes(run_sweep(s, 1)).empty());  // independent points
  s.common_random_numbers = true;
  s.keep_records = false;
  EXPECT_TRUE(precision::crn_slopes(run_sweep(s, 1)).empty());  // no records
  s.keep_records = true;
  EXPECT_EQ(precision::crn_slopes(run_sweep(s, 1)).size(), 2u);
}

// sweep_spec::means_only (the peak finder's sweeps): the moments of every
// per-realization quantity keep their bits, on every engine that can run
// the point (the paper's and a mu_s > mu_k model in the lanes, a damped and
// a three-level model on the scalar engine, and the reference engine); the
// pooled statistics and histograms stay empty.
TEST(MeansOnly, KeepsTheMeansBitsOnEveryEngine) {
  std::vector<sweep_spec> specs(4, figure_spec({0.7, 3.8}, 300, false, 73));
  specs[1].base.static_friction = 7.0;
  specs[2].base.damping = 0.6;
  specs[3].base.belt_levels = {1.0, 0.0, -0.5};
  specs[3].base.belt_generator = {-2, 1, 1, 0.5, -1, 0.5, 1, 1, -2};
  specs[3].axes = {{"mu", {2.0, 5.0}}};
  for (bool family : {false, true})
    for (auto engine : {sweep_engine::fast, sweep_engine::reference})
      for (const auto& base : specs) {
        sweep_spec full = base;
        full.family_statistics = family;
        full.engine = engine;
        sweep_spec lean = full;
        lean.means_only = true;
        const auto a = run_sweep(full, 2), b = run_sweep(lean, 2);
        for (std::size_t p = 0; p < a.points.size(); ++p) {
          const auto &x = a.points[p].stats, &y = b.points[p].stats;
          for (const auto& q : quantities()) {
            if (per_realization(q.sampled)) {
              EXPECT_TRUE(same_bits(x.*q.moments, y.*q.moments)) << q.name << " point " << p;
              if (q.score) {
                EXPECT_TRUE(same_bits(x.*q.score, y.*q.score)) << q.name;
              }
            } else {
              EXPECT_EQ((y.*q.moments).count(), 0u) << q.name;
            }
            if (q.density) {
              EXPECT_EQ((y.*q.density).total(), 0u) << q.name;
            }
          }
          EXPECT_GT(x.stick_duration.count(), 0u);
        }
      }
}

}  // namespace
}  // namespace stickslip
