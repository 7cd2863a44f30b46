// The peak finder (include/stickslip/precision/peak_finder.hpp) against
// curves whose maximizer is known in closed form, evaluated with the sweep's
// noise model: the mean of n independent realizations of a quantity with
// standard deviation sigma(x), reported with its estimated standard error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <random>
#include <string>

#include "stickslip/error.hpp"
#include "stickslip/precision/common_peak_finder.hpp"
#include "stickslip/precision/peak_finder.hpp"
#include "unit/synthetic_curves.hpp"

namespace sp = stickslip::precision;
using namespace stickslip::testing_support;

namespace {

// The sweep's noise model: the sample mean of n realizations is normal with
// sd sigma/sqrt(n) (n >= 100 here), and its standard error is estimated from
// the sample variance, which has relative sd ~ 1/sqrt(2(n - 1)).
sp::evaluator noisy(const curve& c, std::uint64_t problem_seed) {
  return [c, problem_seed](const std::vector<double>& xs, std::uint64_t n, std::uint64_t stage) {
    std::mt19937_64 g(sp::stage_seed(problem_seed, stage));
    std::vector<sp::evaluation> out;
    for (double x : xs) {
      const double se = c.sigma(x) / std::sqrt(static_cast<double>(n));
      const double mean = c.mean(x) + se * normal(g);
      const double se_hat =
          se * std::abs(1.0 + normal(g) / std::sqrt(2.0 * static_cast<double>(n - 1)));
      out.push_back({x, mean, se_hat});
    }
    return out;
  };
}

// The noise of common random numbers: within a group of n realizations the
// points share their random numbers, so the group's error is a random curve,
// not independent per point. Modelled as a common level Z0 plus a Brownian
// motion in x (the variance of the difference of two points grows linearly
// with their distance, as measured for R(lambda): docs/precision.md) plus a
// small independent part:
//   e_g(x) = sigma(x)/sqrt(n) (Z0 + kappa B(x/x0) + 0.1 Z_x).
// Groups and stages are independent.
sp::group_evaluator crn_noisy(const curve& c, double kappa, std::uint64_t problem_seed) {
  return [c, kappa, problem_seed](const std::vector<double>& xs, std::uint64_t n,
                                  std::size_t groups, std::uint64_t stage) {
    std::mt19937_64 g(sp::stage_seed(problem_seed, stage));
    std::vector<std::vector<double>> means(groups);
    for (auto& row : means) {
      const double level = normal(g);
      const auto e = crn_errors(g, xs, c.argmax, level, kappa, 0.1);
      for (std::size_t i = 0; i < xs.size(); ++i)
        row.push_back(c.mean(xs[i]) + c.sigma(xs[i]) / std::sqrt(static_cast<double>(n)) * e[i]);
    }
    return means;
  };
}

}  // namespace

TEST(LocalFit, RecoversAnExactCubicAndItsMaximizer) {
  // p(t) = 1 + 0.5 t - 2 t^2 + 0.3 t^3: p'(t) = 0.5 - 4 t + 0.9 t^2 = 0 at
  // t = (4 - sqrt(16 - 1.8)) / 1.8.
  std::vector<sp::evaluation> pts;
  for (int i = -5; i <= 5; ++i) {
    const double t = i / 5.0;
    pts.push_back({3 + 2 * t, 1 + 0.5 * t - 2 * t * t + 0.3 * t * t * t, 0.01});
  }
  const auto f = sp::fit_polynomial(pts, 3, 3.0, 2.0);
  EXPECT_NEAR(f.coef[0], 1.0, 1e-12);
  EXPECT_NEAR(f.coef[1], 0.5, 1e-12);
  EXPECT_NEAR(f.coef[2], -2.0, 1e-12);
  EXPECT_NEAR(f.coef[3], 0.3, 1e-12);
  EXPECT_NEAR(f.chi2, 0.0, 1e-12);
  const auto m = sp::maximize(f, -1, 1);
  ASSERT_TRUE(m.interior);
  EXPECT_NEAR(m.t, (4 - std::sqrt(16 - 1.8)) / 1.8, 1e-12);
}

TEST(LocalFit, ArgmaxStandardErrorMatchesTheSpreadOverReplicates) {
  // The delta-method standard error of the quadratic's maximizer against the
  // spread of the maximizer over 2000 independent noisy replicates.
  std::mt19937_64 g(7);
  const double se = 0.02;
  double sum = 0, sum2 = 0, reported = 0;
  const int reps = 2000;
  for (int k = 0; k < reps; ++k) {
    std::vector<sp::evaluation> pts;
    for (int i = -4; i <= 4; ++i) {
      const double t = i / 4.0;
      pts.push_back({t, 1 - (t - 0.1) * (t - 0.1) + se * normal(g), se});
    }
    const auto m = sp::maximize(sp::fit_polynomial(pts, 2, 0, 1), -1, 1);
    ASSERT_TRUE(m.interior);
    sum += m.t;
    sum2 += m.t * m.t;
    reported += m.t_std_error;
  }
  const double mean = sum / reps, sd = std::sqrt(sum2 / reps - mean * mean);
  // The sd of a sample sd of 2000 is ~1.6 %; allow 4 of those.
  EXPECT_NEAR(reported / reps / sd, 1.0, 0.065);
  EXPECT_NEAR(mean, 0.1, 4 * sd / std::sqrt(reps) + 1e-3);
}

TEST(PeakFinder, IntervalCoversTheKnownMaximizerOnSyntheticProblems) {
  // The 240 problems of synthetic_curves.hpp, with independent points.
  coverage_tally tally;
  for (int i = 0; i < 240; ++i) {
    const auto p = problem(i);
    tally.add(p, sp::find_peak(noisy(p.c, 1000 + static_cast<std::uint64_t>(i)), p.base));
  }
  tally.print("");
  EXPECT_GE(tally.coverage(), 0.93);
  EXPECT_EQ(tally.met, tally.total);
  EXPECT_GE(tally.max_coverage(), 0.93);
}

TEST(PeakFinder, RefusesAMaximumAtTheEndOfTheRange) {
  const curve c = gamma_shape(10.0, 2.0, 0.4, 0.2);
  sp::peak_options o;
  o.lo = 0.5;
  o.hi = 3.0;  // the curve still rises at 3
  o.log_scan = true;
  try {
    (void)sp::find_peak(noisy(c, 1), o);
    FAIL() << "no error";
  } catch (const stickslip::error& e) {
    EXPECT_EQ(e.code(), stickslip::exit_code::invalid_input);
    EXPECT_NE(std::string(e.what()).find("upper end"), std::string::npos) << e.what();
  }
}

TEST(PeakFinder, SameEvaluationsGiveTheSameResult) {
  const curve c = skewed_quartic(2.0, 0.5, 0.05);
  sp::peak_options o;
  o.lo = 0.5;
  o.hi = 6.0;
  o.target_halfwidth = 0.02;
  const auto a = sp::find_peak(noisy(c, 5), o), b = sp::find_peak(noisy(c, 5), o);
  EXPECT_EQ(a.argmax, b.argmax);
  EXPECT_EQ(a.argmax_lo, b.argmax_lo);
  EXPECT_EQ(a.realizations, b.realizations);
}

TEST(PeakFinder, ReportsAnUnmetTargetWhenTheBudgetRunsOut) {
  const curve c = gamma_shape(3.0, 2.5, 0.4, 0.2);
  sp::peak_options o;
  o.lo = 0.3;
  o.hi = 30.0;
  o.log_scan = true;
  o.target_halfwidth = 1e-4;
  o.max_total_realizations = 200'000;
  const auto r = sp::find_peak(noisy(c, 11), o);
  EXPECT_FALSE(r.target_met);
  EXPECT_LE(r.realizations, o.max_total_realizations);
  EXPECT_GT(r.halfwidth(), o.target_halfwidth);
  EXPECT_LE(r.argmax_lo, r.argmax);
  EXPECT_LE(r.argmax, r.argmax_hi);
}

TEST(PeakFinder, StageSeedsDifferFromEachOtherAndFromTheSeed) {
  EXPECT_NE(sp::stage_seed(1, 0), sp::stage_seed(1, 1));
  EXPECT_NE(sp::stage_seed(1, 1), sp::stage_seed(2, 0));
  EXPECT_NE(sp::stage_seed(1, 0), 1u);
  EXPECT_EQ(sp::stage_seed(7, 3), sp::stage_seed(7, 3));
}

TEST(StudentT, QuantilesMatchTables) {
  // Two-sided 95 %: t_{0.975} for 4, 9, 19, 49 degrees of freedom.
  EXPECT_NEAR(sp::student_t95(4), 2.7764, 8e-3);
  EXPECT_NEAR(sp::student_t95(9), 2.2622, 5e-4);
  EXPECT_NEAR(sp::student_t95(19), 2.0930, 2e-4);
  EXPECT_NEAR(sp::student_t95(49), 2.0096, 1e-4);
}

// find_peak_common (common random numbers, batch-means intervals) on the
// same 240 problems as find_peak, with the common-random-number noise model.
// Four seed sets of the 240 problems (960 runs): one set alone gives between
// 92.5 % and 95.8 %, so the 93 % floor is checked on all of them together.
TEST(CommonPeakFinder, IntervalCoversTheKnownMaximizerOnSyntheticProblems) {
  coverage_tally tally;
  for_each_synthetic_run([&](const synthetic_problem& p, std::uint64_t seed) {
    sp::common_peak_options o;
    o.base = p.base;
    tally.add(p, sp::find_peak_common(crn_noisy(p.c, p.kappa, seed), o));
  });
  tally.print("common: ");
  EXPECT_GE(tally.coverage(), 0.93);
  EXPECT_EQ(tally.met, tally.total);
  EXPECT_GE(tally.max_coverage(), 0.93);
}
