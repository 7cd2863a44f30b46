// The refinement math of `reproduce` on synthetic curves with a known
// maximum: exact recovery without noise, coverage of the bootstrap interval
// with noise, and no maximum for an upward curve. Also the study grids.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "stickslip/study/design.hpp"
#include "stickslip/study/fit.hpp"

namespace {

using stickslip::study::fit_peak;

// R(lambda) = R* - c ln(lambda/lambda*)^2, the local shape of mean R.
double curve(double lambda, double lambda_star, double R_star, double c) {
  const double u = std::log(lambda / lambda_star);
  return R_star - c * u * u;
}

TEST(ReproducePeak, RecoversAnExactQuadraticMaximum) {
  const auto lam = stickslip::study::refinement_grid(3.5, 0.4, 17);
  std::vector<double> mean, se(lam.size(), 1e-4);
  for (double l : lam) mean.push_back(curve(l, 3.71, 0.7823, 0.07));
  const auto p = fit_peak(lam, mean, se, 3.5, 1, 2);
  ASSERT_TRUE(p.valid);
  EXPECT_NEAR(p.lambda_star, 3.71, 1e-9);
  EXPECT_NEAR(p.R_star, 0.7823, 1e-12);
  EXPECT_TRUE(p.interior);
  EXPECT_NEAR(p.chi2, 0.0, 1e-12);
  EXPECT_EQ(p.dof, 14u);
  EXPECT_LE(p.lambda_lo, p.lambda_star);
  EXPECT_GE(p.lambda_hi, p.lambda_star);
  // The bootstrap interval and the delta method agree for a well-determined peak.
  EXPECT_NEAR((p.lambda_hi - p.lambda_lo) / (2 * stickslip::z95), p.lambda_se_delta,
              0.15 * p.lambda_se_delta);
  EXPECT_NEAR((p.R_hi - p.R_lo) / (2 * stickslip::z95), p.R_se_delta, 0.15 * p.R_se_delta);
}

TEST(ReproducePeak, BootstrapIntervalsCoverTheTruth) {
  // 200 noisy replications; a 95 % interval must cover the true lambda* and
  // R* in about 190 of them. Binomial(200, 0.95) has SD 3.1: accept >= 178
  // (4 SD below), so the test fails only for a real miscalibration.
  const auto lam = stickslip::study::refinement_grid(3.3, 0.4, 17);
  const double se = 0.0012;
  std::mt19937_64 gen(12345);
  std::normal_distribution<double> z;
  int cover_l = 0, cover_r = 0;
  const int reps = 200;
  for (int k = 0; k < reps; ++k) {
    std::vector<double> mean, s(lam.size(), se);
    for (double l : lam) mean.push_back(curve(l, 3.71, 0.7823, 0.07) + se * z(gen));
    const auto p = fit_peak(lam, mean, s, 3.3, 7, static_cast<std::uint64_t>(k), 1000);
    ASSERT_TRUE(p.valid);
    cover_l += p.lambda_lo <= 3.71 && 3.71 <= p.lambda_hi;
    cover_r += p.R_lo <= 0.7823 && 0.7823 <= p.R_hi;
  }
  EXPECT_GE(cover_l, 178) << "lambda* interval covered the truth in " << cover_l << "/" << reps;
  EXPECT_GE(cover_r, 178) << "R* interval covered the truth in " << cover_r << "/" << reps;
}

TEST(ReproducePeak, SameSeedSameIntervals) {
  const auto lam = stickslip::study::refinement_grid(3.0, 0.4, 9);
  std::vector<double> mean, se(lam.size(), 0.002);
  for (std::size_t i = 0; i < lam.size(); ++i)
    mean.push_back(curve(lam[i], 3.2, 0.5, 0.1) + (i % 2 ? 0.001 : -0.001));
  const auto a = fit_peak(lam, mean, se, 3.0, 99, 5);
  const auto b = fit_peak(lam, mean, se, 3.0, 99, 5);
  const auto c = fit_peak(lam, mean, se, 3.0, 99, 6);
  EXPECT_EQ(a.lambda_lo, b.lambda_lo);
  EXPECT_EQ(a.R_hi, b.R_hi);
  EXPECT_NE(a.lambda_lo, c.lambda_lo);  // another stream tag, other draws
}

TEST(ReproducePeak, NoMaximumForAnUpwardCurve) {
  const auto lam = stickslip::study::refinement_grid(1.0, 0.3, 7);
  std::vector<double> mean, se(lam.size(), 0.001);
  for (double l : lam) mean.push_back(0.2 + 0.5 * std::log(l) * std::log(l));
  const auto p = fit_peak(lam, mean, se, 1.0, 1, 1);
  EXPECT_FALSE(p.valid);
}

TEST(ReproducePeak, TooFewPointsIsNotAFit) {
  const auto p = fit_peak({1, 2}, {0.1, 0.2}, {0.01, 0.01}, 1.5, 1, 1);
  EXPECT_FALSE(p.valid);
}

TEST(ReproduceGrids, PaperGridsHaveTheDocumentedShape) {
  const auto lam = stickslip::study::paper_lambda_grid();
  ASSERT_EQ(lam.size(), 40u);
  EXPECT_TRUE(std::is_sorted(lam.begin(), lam.end()));
  EXPECT_EQ(std::adjacent_find(lam.begin(), lam.end()), lam.end());
  EXPECT_DOUBLE_EQ(lam.front(), 0.1);
  EXPECT_DOUBLE_EQ(lam.back(), 30.0);
  EXPECT_NE(std::find(lam.begin(), lam.end(), 3.5), lam.end());
  EXPECT_NE(std::find(lam.begin(), lam.end(), 3.8), lam.end());
  const auto mu = stickslip::study::paper_mu_grid();
  ASSERT_EQ(mu.size(), 8u);
  EXPECT_DOUBLE_EQ(mu.front(), 0.5);
  EXPECT_DOUBLE_EQ(mu.back(), 7.0);
  EXPECT_NE(std::find(mu.begin(), mu.end(), 5.0), mu.end());
}

TEST(ReproduceGrids, RefinementGridIsGeometricAroundTheCenter) {
  const auto g = stickslip::study::refinement_grid(3.8, 0.4, 5);
  ASSERT_EQ(g.size(), 5u);
  EXPECT_NEAR(g[2], 3.8, 1e-12);
  EXPECT_NEAR(g.front(), 3.8 * std::exp(-0.4), 1e-12);
  EXPECT_NEAR(g.back(), 3.8 * std::exp(0.4), 1e-12);
  EXPECT_NEAR(g[1] / g[0], g[4] / g[3], 1e-12);
}

TEST(ReproduceSets, ConcludedSetGivesThePrintedDmax) {
  auto p = stickslip::study::concluded_parameters().base;
  p.friction_coefficient = 5;
  EXPECT_NEAR(p.max_stick_duration(), 2.5, 0.05);  // the paper's "2.5 s"
  auto q = stickslip::study::printed_parameters().base;
  q.friction_coefficient = 5;
  EXPECT_NEAR(q.max_stick_duration(), 24.525, 1e-9);  // what the printed values give
}

}  // namespace
