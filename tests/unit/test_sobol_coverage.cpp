// The Sobol' estimators (uncertainty/sobol.hpp) against closed forms: the
// 95 % intervals must cover the true indices of the Ishigami function and
// the Sobol' g-function in >= 93 % of seeded replications, also with
// additive output noise (a stochastic simulator); plus the accumulator's
// algebra (merge == fill all, offset data, empty and degenerate inputs).
//
// Why >= 93 % is a fair bar: with R replications and a true coverage of
// 95 %, the observed coverage has standard error sqrt(0.95 * 0.05 / R)
// (0.0049 for R = 2000), so 93 % is 4 standard errors below 95 %; an
// interval with half its width covers about 2 Phi(0.98) - 1 = 67 %.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/uncertainty/sobol.hpp"

using stickslip::first_order_form;
using stickslip::interval_estimate;
using stickslip::sobol_estimates;
using stickslip::sobol_indices;
using stickslip::sobol_moments;

namespace {

constexpr double pi = std::numbers::pi;

// A test function with independent inputs and closed-form indices.
struct test_function {
  std::string name;
  std::size_t inputs = 0;
  std::function<double(const std::vector<double>&)> f;
  std::function<double(std::mt19937_64&)> draw;  // one input (all inputs share the law)
  double variance = 0.0;                          // Var f
  std::vector<double> first, total;               // V_i, VT_i (not normalized)
};

// Ishigami and Homma (1990), x_i ~ U(-pi, pi): with V_1 = (1 + b pi^4/5)^2 / 2,
// V_2 = a^2 / 8, V_3 = 0, V_13 = 8 b^2 pi^8 / 225 and Var f = V_1 + V_2 + V_13
// (Sobol' and Levitan 1999; Saltelli et al. 2008, sec. 4.9).
test_function ishigami(double a = 7.0, double b = 0.1) {
  test_function t;
  t.name = "Ishigami";
  t.inputs = 3;
  t.f = [a, b](const std::vector<double>& x) {
    return std::sin(x[0]) + a * std::sin(x[1]) * std::sin(x[1]) +
           b * std::pow(x[2], 4) * std::sin(x[0]);
  };
  t.draw = [](std::mt19937_64& g) { return std::uniform_real_distribution<double>(-pi, pi)(g); };
  const double pi4 = std::pow(pi, 4), pi8 = std::pow(pi, 8);
  const double v1 = 0.5 * (1 + b * pi4 / 5) * (1 + b * pi4 / 5), v2 = a * a / 8;
  const double v13 = 8 * b * b * pi8 / 225;
  t.variance = v1 + v2 + v13;
  t.first = {v1, v2, 0.0};
  t.total = {v1 + v13, v2, v13};
  return t;
}

// Sobol's g-function, x_i ~ U(0, 1), f = prod (|4 x_i - 2| + a_i) / (1 + a_i):
// V_i = 1 / (3 (1 + a_i)^2), Var f = prod (1 + V_i) - 1,
// VT_i = V_i prod_{j != i} (1 + V_j) (Saltelli and Sobol' 1995).
test_function g_function(std::vector<double> a = {0, 1, 4.5, 9, 99, 99}) {
  test_function t;
  t.name = "g-function";
  t.inputs = a.size();
  t.f = [a](const std::vector<double>& x) {
    double y = 1.0;
    for (std::size_t i = 0; i < a.size(); ++i) y *= (std::abs(4 * x[i] - 2) + a[i]) / (1 + a[i]);
    return y;
  };
  t.draw = [](std::mt19937_64& g) { return std::uniform_real_distribution<double>(0, 1)(g); };
  std::vector<double> v;
  double prod = 1.0;
  for (double ai : a) {
    v.push_back(1.0 / (3 * (1 + ai) * (1 + ai)));
    prod *= 1 + v.back();
  }
  t.variance = prod - 1;
  for (double vi : v) {
    t.first.push_back(vi);
    t.total.push_back(vi * prod / (1 + vi));
  }
  return t;
}

// One replication: N pick-freeze rows of f + sigma eps, every evaluation
// (the replicate included) with its own eps.
sobol_moments replicate(const test_function& t, std::size_t rows, double sigma,
                        std::uint64_t seed) {
  std::mt19937_64 g(seed);
  std::normal_distribution<double> eps;
  const std::size_t d = t.inputs;
  std::vector<double> xa(d), xb(d), xe(d), ye(d);
  sobol_moments m(d);
  auto noisy = [&](const std::vector<double>& x) {
    const double y = t.f(x);
    return sigma > 0 ? y + sigma * eps(g) : y;
  };
  for (std::size_t j = 0; j < rows; ++j) {
    for (auto& x : xa) x = t.draw(g);
    for (auto& x : xb) x = t.draw(g);
    const double ya = noisy(xa), ya2 = noisy(xa), yb = noisy(xb);
    for (std::size_t i = 0; i < d; ++i) {
      xe = xa;
      xe[i] = xb[i];
      ye[i] = noisy(xe);
    }
    m.add(ya, ya2, yb, ye);
  }
  return m;
}

bool covers(const interval_estimate& e, double truth, double width_factor) {
  const double h = width_factor * e.half_width();
  return e.value - h <= truth && truth <= e.value + h;
}

// The coverage of each estimate over `replications` runs: a named truth
// and the estimate it is compared with.
struct target {
  std::string name;
  double truth;
  std::function<const interval_estimate&(const sobol_estimates&)> pick;
};

struct coverage_row {
  std::string name;
  double truth = 0, mean_estimate = 0, mean_half_width = 0, coverage = 0, half_coverage = 0;
};

std::vector<coverage_row> coverage(const test_function& t, double sigma, std::size_t rows,
                                   std::size_t replications, std::uint64_t seed0,
                                   first_order_form form) {
  const double vy = t.variance + sigma * sigma;
  std::vector<target> targets;
  for (std::size_t i = 0; i < t.inputs; ++i) {
    targets.push_back({"S" + std::to_string(i + 1), t.first[i] / t.variance,
                       [i](const sobol_estimates& s) -> const interval_estimate& {
                         return s.first_order[i];
                       }});
    targets.push_back({"T" + std::to_string(i + 1), t.total[i] / t.variance,
                       [i](const sobol_estimates& s) -> const interval_estimate& {
                         return s.total_order[i];
                       }});
    if (sigma > 0)
      targets.push_back({"S" + std::to_string(i + 1) + "^Y", t.first[i] / vy,
                         [i](const sobol_estimates& s) -> const interval_estimate& {
                           return s.response_first_order[i];
                         }});
  }
  if (sigma > 0) {
    targets.push_back({"parameter share", t.variance / vy,
                       [](const sobol_estimates& s) -> const interval_estimate& {
                         return s.parameter_share;
                       }});
    targets.push_back({"intrinsic share", sigma * sigma / vy,
                       [](const sobol_estimates& s) -> const interval_estimate& {
                         return s.intrinsic_share;
                       }});
  }
  std::vector<coverage_row> table(targets.size());
  for (std::size_t k = 0; k < targets.size(); ++k) {
    table[k].name = targets[k].name;
    table[k].truth = targets[k].truth;
  }
  for (std::size_t r = 0; r < replications; ++r) {
    // Distinct, well-separated seeds per replication (splitmix64 of r).
    std::uint64_t z = seed0 + 0x9e3779b97f4a7c15ULL * (r + 1);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    const auto s = sobol_indices(replicate(t, rows, sigma, z ^ (z >> 31)), form);
    for (std::size_t k = 0; k < targets.size(); ++k) {
      const auto& e = targets[k].pick(s);
      table[k].mean_estimate += e.value;
      table[k].mean_half_width += e.half_width();
      table[k].coverage += covers(e, targets[k].truth, 1.0);
      table[k].half_coverage += covers(e, targets[k].truth, 0.5);
    }
  }
  for (auto& row : table) {
    const auto n = static_cast<double>(replications);
    row.mean_estimate /= n;
    row.mean_half_width /= n;
    row.coverage /= n;
    row.half_coverage /= n;
  }
  return table;
}

void print(const std::string& title, const std::vector<coverage_row>& table) {
  std::printf("%s\n  %-16s %10s %10s %10s %9s %14s\n", title.c_str(), "index", "true",
              "mean est.", "half-width", "coverage", "half-interval");
  for (const auto& r : table)
    std::printf("  %-16s %10.5f %10.5f %10.5f %8.1f%% %13.1f%%\n", r.name.c_str(), r.truth,
                r.mean_estimate, r.mean_half_width, 100 * r.coverage, 100 * r.half_coverage);
  std::fflush(stdout);
}

// N = 4000 rows: the pick-freeze products of the Ishigami function
// (x_3^4 terms) are skewed, and the delta method needs N in the thousands
// for its normal approximation to hold at the 95 % level. At N = 4000 the
// true coverage of every index and share below, both forms, is 94.2 % to
// 95.6 % (4000 runs each with other seeds, standard error 0.35 %).
// R = 2000 runs: an index with true coverage 94.2 % then falls below 93 %
// with probability ~1 % (2.3 standard errors); with R = 1000 it would be
// ~5 % per index, so that almost any reseeding of the whole table would
// fail somewhere.
constexpr std::size_t rows_per_run = 4000;
constexpr std::size_t replications = 2000;

void check_coverage(const test_function& t, double sigma, std::uint64_t seed,
                    first_order_form form, const std::string& form_name,
                    std::size_t rows = rows_per_run) {
  const auto start = std::chrono::steady_clock::now();
  const auto table = coverage(t, sigma, rows, replications, seed, form);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  print(t.name + (sigma > 0 ? " + noise sd " + std::to_string(sigma) : std::string{}) + ", " +
            form_name + ": " + std::to_string(replications) + " runs of N = " +
            std::to_string(rows) + " rows (" + std::to_string(seconds) + " s)",
        table);
  for (const auto& r : table) {
    EXPECT_GE(r.coverage, 0.93) << t.name << " " << r.name;
    // The sanity check: the same runs with intervals half as wide.
    EXPECT_LT(r.half_coverage, 0.85) << t.name << " " << r.name;
  }
}

}  // namespace

TEST(SobolCoverage, IshigamiDeterministic) {
  check_coverage(ishigami(), 0.0, 11, first_order_form::openturns_saltelli, "OpenTURNS Saltelli");
}

TEST(SobolCoverage, GFunctionDeterministic) {
  check_coverage(g_function(), 0.0, 12, first_order_form::openturns_saltelli,
                 "OpenTURNS Saltelli");
}

TEST(SobolCoverage, IshigamiWithNoise) {
  check_coverage(ishigami(), 2.0, 13, first_order_form::openturns_saltelli, "OpenTURNS Saltelli");
}

TEST(SobolCoverage, GFunctionWithNoise) {
  check_coverage(g_function(), 0.5, 14, first_order_form::openturns_saltelli,
                 "OpenTURNS Saltelli");
}

// The other first-order form (sobol.hpp), through the same intervals.
TEST(SobolCoverage, Saltelli2010FormWithNoise) {
  check_coverage(ishigami(), 2.0, 15, first_order_form::saltelli_2010, "Saltelli 2010");
  check_coverage(g_function(), 0.5, 16, first_order_form::saltelli_2010, "Saltelli 2010");
}

// The accumulator's algebra.
namespace {

void expect_close(const std::vector<double>& a, const std::vector<double>& b, double rel) {
  ASSERT_EQ(a.size(), b.size());
  double scale = 0;
  for (double x : b) scale = std::max(scale, std::abs(x));
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_NEAR(a[k], b[k], rel * scale) << "entry " << k;
}

// Rows of the noisy Ishigami design, for the algebra tests.
struct rows_of {
  std::vector<std::array<double, 3>> heads;  // y_A, y_A2, y_B
  std::vector<std::vector<double>> e;
};

rows_of some_rows(std::size_t n, double offset) {
  const auto t = ishigami();
  std::mt19937_64 g(99);
  std::normal_distribution<double> eps;
  rows_of r;
  std::vector<double> xa(3), xb(3), xe(3);
  for (std::size_t j = 0; j < n; ++j) {
    for (auto& x : xa) x = t.draw(g);
    for (auto& x : xb) x = t.draw(g);
    r.heads.push_back({offset + t.f(xa) + eps(g), offset + t.f(xa) + eps(g), offset + t.f(xb) + eps(g)});
    std::vector<double> ye(3);
    for (std::size_t i = 0; i < 3; ++i) {
      xe = xa;
      xe[i] = xb[i];
      ye[i] = offset + t.f(xe) + eps(g);
    }
    r.e.push_back(ye);
  }
  return r;
}

sobol_moments fill(const rows_of& r, std::size_t from, std::size_t to) {
  sobol_moments m(3);
  for (std::size_t j = from; j < to; ++j) m.add(r.heads[j][0], r.heads[j][1], r.heads[j][2], r.e[j]);
  return m;
}

}  // namespace

TEST(SobolMoments, MergeEqualsFillingEverything) {
  const auto r = some_rows(3001, 0.0);
  const auto whole = fill(r, 0, 3001);
  auto merged = fill(r, 0, 1000);
  merged += fill(r, 1000, 1001);
  merged += fill(r, 1001, 3001);
  EXPECT_EQ(merged.rows(), whole.rows());
  expect_close(merged.means(), whole.means(), 1e-12);
  expect_close(merged.comoments(), whole.comoments(), 1e-12);
  // Empty accumulators are neutral on both sides.
  sobol_moments empty;
  auto copy = whole;
  copy += empty;
  EXPECT_EQ(copy, whole);
  empty += whole;
  EXPECT_EQ(empty, whole);
  // The state round-trips.
  EXPECT_EQ(sobol_moments::from_state(3, whole.rows(), whole.means(), whole.comoments()), whole);
  EXPECT_THROW((void)sobol_moments::from_state(2, 1, whole.means(), whole.comoments()),
               stickslip::error);
  // A fixed merge order gives the same bits every time.
  auto again = fill(r, 0, 1000);
  again += fill(r, 1000, 1001);
  again += fill(r, 1001, 3001);
  EXPECT_EQ(again, merged);
}

TEST(SobolMoments, OffsetDataGivesTheSameEstimates) {
  // The point estimates use centred co-moments only: an offset of 1e6 (sd
  // Y = 4) leaves them to ~1e-10. The intervals' variance cancels terms
  // (offset / sd)^2 times its size, each accumulated with relative error
  // ~ N eps: at an offset of 1e3, 6e4 * 2000 * 1.1e-16 ~ 1e-8.
  const auto s0 = sobol_indices(fill(some_rows(2000, 0.0), 0, 2000));
  const auto s1 = sobol_indices(fill(some_rows(2000, 1e6), 0, 2000));
  const auto s2 = sobol_indices(fill(some_rows(2000, 1e3), 0, 2000));
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(s1.first_order[i].value, s0.first_order[i].value, 1e-8);
    EXPECT_NEAR(s1.total_order[i].value, s0.total_order[i].value, 1e-8);
    EXPECT_NEAR(s2.first_order[i].half_width(), s0.first_order[i].half_width(),
                1e-6 * s0.first_order[i].half_width());
    EXPECT_NEAR(s2.total_order[i].half_width(), s0.total_order[i].half_width(),
                1e-6 * s0.total_order[i].half_width());
  }
  EXPECT_NEAR(s1.intrinsic_share.value, s0.intrinsic_share.value, 1e-8);
}

TEST(SobolMoments, TooFewRowsOrNoVarianceGiveNaN) {
  sobol_moments one(2);
  one.add(1, 1, 2, std::vector<double>{1, 2});
  const auto s = sobol_indices(one);
  EXPECT_TRUE(std::isnan(s.first_order[0].value));
  EXPECT_TRUE(std::isnan(s.parameter_share.high));
  EXPECT_TRUE(std::isnan(s.max_half_width()));
  sobol_moments flat(2);
  for (int j = 0; j < 10; ++j) flat.add(3, 3, 3 + j, std::vector<double>{3, 3});
  const auto f = sobol_indices(flat);  // y_A constant: V = 0
  EXPECT_TRUE(std::isnan(f.total_order[1].value));
  EXPECT_TRUE(std::isnan(f.intrinsic_share.value));
  // y_B varies: not a constant statistic, too few rows (a review found the
  // note calling such a design constant)
  EXPECT_FALSE(f.constant_statistic);
  EXPECT_THAT(stickslip::undefined_indices_note(f, "S_T"),
              testing::HasSubstr("S_T is the same in every row's first output (variance 0) "
                                 "though not in the others: too few rows (10)"));
}

// An interval wider than [0, 1], the range of an index, gets its warning
// (a new user's --samples 2 gave a share of -5.8 without a word): over
// Var Y (the response's indices, the shares) as too few rows; only over
// Var g (the mean response's indices) as a small parameter share, which no
// number of rows mends (a review: it said "so few rows" at 4,000). A NaN
// interval does not hide a wide one; narrow ones and undefined ones get
// nothing; sensitivity_warning takes the undefined note first.
TEST(SobolMoments, IntervalsWiderThanTheRangeOfAnIndexAreWarnedOf) {
  sobol_estimates e;
  e.rows = 16;
  e.variance = 1.0;
  e.first_order = {{0.4, 0.1, 0.7}};
  e.total_order = {{0.5, 0.2, 0.8}};
  e.response_first_order = {{0.4, 0.1, 0.7}};
  e.parameter_share = {0.8, 0.75, 0.85};
  e.intrinsic_share = {0.2, 0.15, 0.25};
  EXPECT_EQ(stickslip::uninformative_indices_note(e, "R"), "");
  e.total_order[0] = {0.5, -0.01, 1.0};  // wider than 1 by 0.01, over Var g
  EXPECT_THAT(stickslip::uninformative_indices_note(e, "R"),  // a share of 0.8: the rows
              testing::HasSubstr("from 16 rows say little"));
  e.parameter_share = {0.1, 0.05, 0.15};
  e.intrinsic_share = {0.9, 0.85, 0.95};
  EXPECT_EQ(stickslip::uninformative_indices_note(e, "R"),  // a share of 0.1: the share
            "the Sobol' indices of E[R | theta] have 95 % intervals wider than [0, 1] (largest "
            "half-width 0.505): they divide by the parameters' share of Var R, here 0.1 "
            "[0.05, 0.15], which is small (below 1/4) and magnifies their intervals by about 1 / "
            "share, so that more rows narrow them only slowly; the first order in R and the "
            "shares are this study's better-determined estimates");
  e.parameter_share = {0.1, -0.2, 0.4};  // a share whose interval reaches 1/4: the rows
  EXPECT_THAT(stickslip::uninformative_indices_note(e, "R"), testing::HasSubstr("from 16 rows"));
  e.parameter_share = {0.1, 0.05, 0.15};
  e.response_first_order[0] = {0.4, -0.2, 1.0};  // over Var Y: too few rows
  EXPECT_EQ(stickslip::uninformative_indices_note(e, "R"),
            "the Sobol' estimates of R from 16 rows say little: a 95 % interval is wider than "
            "[0, 1], the range of an index (largest half-width 0.6), and these intervals, "
            "asymptotic (delta method), may not hold at so few rows; run more rows (--samples, "
            "or a larger --max-samples with --target-halfwidth)");
  EXPECT_EQ(stickslip::sensitivity_warning(e, "R"), stickslip::uninformative_indices_note(e, "R"));
  e.response_first_order[0].value = e.response_first_order[0].high = NAN;  // NaN is not wide...
  EXPECT_THAT(stickslip::uninformative_indices_note(e, "R"), testing::HasSubstr("E[R | theta]"));
  e.intrinsic_share = {0.2, -0.5, 0.9};  // ...nor does it hide a wide one
  EXPECT_THAT(stickslip::uninformative_indices_note(e, "R"), testing::HasSubstr("from 16 rows"));
  e.total_order[0] = {0.5, 0.2, 0.8};
  e.intrinsic_share = {0.2, 0.15, 0.25};
  EXPECT_EQ(stickslip::uninformative_indices_note(e, "R"), "");
  sobol_moments zero(1);
  for (int j = 0; j < 10; ++j) zero.add(0, 0, 0, std::vector<double>{0});
  const auto z = sobol_indices(zero);
  EXPECT_EQ(stickslip::sensitivity_warning(z, "c"), stickslip::undefined_indices_note(z, "c"));
  EXPECT_NE(stickslip::sensitivity_warning(z, "c"), "");
}

// A statistic constant over the design (damping_power without damping):
// its mean and variance 0 are estimates like any other, only the indices
// and shares are 0 / 0 (a new user found the mean reported as NaN, and no
// word of why); undefined_indices_note says why, and nothing otherwise.
TEST(SobolMoments, AConstantStatisticHasItsMeanAndNoIndices) {
  sobol_moments zero(2);
  for (int j = 0; j < 10; ++j) zero.add(0, 0, 0, std::vector<double>{0, 0});
  const auto z = sobol_indices(zero);
  EXPECT_EQ(z.mean, 0.0);
  EXPECT_EQ(z.variance, 0.0);
  EXPECT_EQ(z.intrinsic_variance, 0.0);
  EXPECT_EQ(z.rows, 10u);
  EXPECT_TRUE(z.constant_statistic);
  EXPECT_TRUE(std::isnan(z.first_order[0].value) && std::isnan(z.total_order[1].high));
  EXPECT_TRUE(std::isnan(z.parameter_share.value) && std::isnan(z.intrinsic_share.value));
  EXPECT_EQ(stickslip::undefined_indices_note(z, "damping_power"),
            "damping_power is constant over the design's 10 rows (mean 0, variance 0): its "
            "Sobol' indices and shares are 0 / 0, undefined, and written as NaN");
  sobol_moments two(1);
  for (int j = 0; j < 10; ++j) two.add(2.5, 2.5, 2.5, std::vector<double>{2.5});
  EXPECT_EQ(sobol_indices(two).mean, 2.5);
  sobol_moments varied(1);
  for (int j = 0; j < 10; ++j) varied.add(j, j + 0.5, 9 - j, std::vector<double>{j % 3 * 1.0});
  EXPECT_EQ(stickslip::undefined_indices_note(sobol_indices(varied), "R"), "");
}

TEST(SobolMoments, NegativeEstimatesAreNotClipped) {
  // A pure-noise output: every index of g is 0 and half the estimates fall
  // below it; they are reported as they are.
  test_function noise;
  noise.name = "noise";
  noise.inputs = 2;
  noise.f = [](const std::vector<double>& x) { return 1e-3 * x[0]; };
  noise.draw = [](std::mt19937_64& g) { return std::uniform_real_distribution<double>(0, 1)(g); };
  int negative = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const auto s = sobol_indices(replicate(noise, 200, 1.0, seed));
    negative += s.response_first_order[1].value < 0;
    EXPECT_LT(s.response_first_order[1].low, 0.0);
  }
  EXPECT_GT(negative, 0);
}
