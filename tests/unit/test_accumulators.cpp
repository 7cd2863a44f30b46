// Algebra of the accumulators (Boost.Histogram style): merging two halves
// equals filling everything at once; shifted data keeps its variance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "stickslip/accumulators/histogram.hpp"
#include "stickslip/accumulators/mean_variance.hpp"

using stickslip::histogram;
using stickslip::mean_variance;

namespace {
std::vector<double> sample(int n) {
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(std::sin(0.7 * i) + 0.01 * i);
  return v;
}
}  // namespace

TEST(MeanVariance, MatchesTwoPassFormulas) {
  const auto v = sample(1000);
  mean_variance a;
  for (double x : v) a.add(x);
  double m = 0;
  for (double x : v) m += x;
  m /= v.size();
  double s2 = 0;
  for (double x : v) s2 += (x - m) * (x - m);
  s2 /= (v.size() - 1);
  // Welford's update accumulates O(n eps) relative rounding.
  const double tol = v.size() * 2.2e-16;
  EXPECT_NEAR(a.mean(), m, tol * std::abs(m));
  EXPECT_NEAR(a.variance(), s2, tol * s2);
  EXPECT_EQ(a.count(), 1000u);
}

TEST(MeanVariance, MergeOfHalvesEqualsWhole) {
  const auto v = sample(777);
  mean_variance whole, left, right;
  for (std::size_t i = 0; i < v.size(); ++i) {
    whole.add(v[i]);
    (i < 300 ? left : right).add(v[i]);
  }
  left += right;
  EXPECT_EQ(left.count(), whole.count());
  const double tol = v.size() * 2.2e-16;
  EXPECT_NEAR(left.mean(), whole.mean(), tol * std::abs(whole.mean()));
  EXPECT_NEAR(left.variance(), whole.variance(), tol * whole.variance());
}

TEST(MeanVariance, MergeWithEmptyIsIdentity) {
  mean_variance a, empty;
  for (double x : sample(10)) a.add(x);
  const auto before = a;
  a += empty;
  EXPECT_EQ(a, before);
  empty += a;
  EXPECT_EQ(empty, a);
}

TEST(MeanVariance, RobustToLargeOffset) {
  mean_variance plain, shifted;
  for (double x : sample(500)) {
    plain.add(x);
    shifted.add(x + 1e8);
  }
  EXPECT_NEAR(shifted.variance(), plain.variance(), 1e-6 * plain.variance());
}

// add_batch (what point_statistics uses for the D_i and H_i of a
// realization): batches of any size, merged, agree with one sample at a time
// and with the two-pass formulas, also far from the origin; an empty batch
// changes nothing.
TEST(MeanVariance, BatchesEqualOneAtATime) {
  for (double offset : {0.0, 1e8}) {
    auto v = sample(1000);
    for (double& x : v) x += offset;
    mean_variance one, batched;
    for (double x : v) one.add(x);
    std::size_t i = 0, len = 0;
    while (i < v.size()) {  // batch sizes 0, 1, 2, ... 44
      const std::size_t n = std::min(len++, v.size() - i);
      batched.add_batch(v.data() + i, v.data() + i + n);
      i += n;
    }
    EXPECT_EQ(batched.count(), one.count());
    const double tol = v.size() * 2.2e-16;
    EXPECT_NEAR(batched.mean(), one.mean(), tol * std::abs(one.mean())) << offset;
    EXPECT_NEAR(batched.variance(), one.variance(), 1e-6 * one.variance()) << offset;
  }
  const auto v = sample(50);
  mean_variance a;
  a.add_batch(v.data(), v.data() + v.size());
  const auto before = a;
  a.add_batch(v.data(), v.data());
  EXPECT_EQ(a, before);
  mean_variance single;
  single.add_batch(v.data(), v.data() + 1);
  EXPECT_EQ(single.mean(), v[0]);
  EXPECT_EQ(single.sum_sq_dev(), 0.0);
}

TEST(MeanVariance, ConfidenceIntervalIsNormalApproximation) {
  mean_variance a;
  for (double x : {1.0, 2.0, 3.0, 4.0}) a.add(x);
  // s^2 = 5/3, se = sqrt(5/3/4)
  EXPECT_NEAR(a.ci95_half_width(), 1.959963984540054 * std::sqrt(5.0 / 12.0), 1e-15);
}

TEST(Histogram, BinsEdgesAndOutOfRange) {
  histogram h(0.0, 1.0, 4);
  for (double x : {0.0, 0.1, 0.25, 0.5, 0.99, 1.0, -0.1, 1.5, std::nan("")}) h.add(x);
  EXPECT_EQ(h.count(0), 2u);  // 0, 0.1
  EXPECT_EQ(h.count(1), 1u);  // 0.25
  EXPECT_EQ(h.count(2), 1u);  // 0.5
  EXPECT_EQ(h.count(3), 2u);  // 0.99, 1.0 (closed right edge)
  EXPECT_EQ(h.underflow(), 2u);  // -0.1, NaN
  EXPECT_EQ(h.overflow(), 1u);
  EXPECT_EQ(h.total(), 9u);
}

// add_all is add in one loop: the same counts, also for the edges, the
// closed right edge, out-of-range values, NaN and infinities, and added to
// counts already there.
TEST(Histogram, AddAllEqualsAddingOneAtATime) {
  std::vector<double> xs = {0.0,  0.1, 0.25, 0.5, 0.99, 1.0, -0.1, 1.5, std::nan(""),
                            -0.0, std::nextafter(1.0, 2.0), INFINITY, -INFINITY, 0.75};
  for (double x : sample(500)) xs.push_back(x / 2 + 0.5);  // some beyond [0, 1] either side
  histogram one(0.0, 1.0, 7), all(0.0, 1.0, 7);
  one.add(0.3), all.add(0.3), one.add(-1.0), all.add(-1.0);
  for (double x : xs) one.add(x);
  all.add_all(xs.data(), xs.data() + xs.size());
  EXPECT_EQ(one, all);
  EXPECT_GT(all.underflow(), 3u);
  EXPECT_GT(all.overflow(), 2u);
  all.add_all(xs.data(), xs.data());  // nothing
  EXPECT_EQ(one, all);
}

TEST(Histogram, DensityIntegratesToInRangeFraction) {
  histogram h(0.0, 2.0, 10);
  for (double x : sample(1000)) h.add(std::abs(x));
  double area = 0;
  for (std::size_t i = 0; i < h.bins(); ++i) area += h.density(i) * h.width();
  const double inside = double(h.total() - h.underflow() - h.overflow()) / h.total();
  EXPECT_NEAR(area, inside, 1e-12);
}

TEST(Histogram, MergeEqualsFillingTwice) {
  histogram a(0, 1, 8), b(0, 1, 8), both(0, 1, 8);
  for (double x : sample(100)) {
    a.add(std::abs(x) / 2);
    both.add(std::abs(x) / 2);
  }
  for (double x : sample(50)) {
    b.add(std::abs(x) / 3);
    both.add(std::abs(x) / 3);
  }
  a += b;
  EXPECT_EQ(a, both);
}

#include "stickslip/sweep.hpp"

TEST(ConvergenceTrace, EveryBlockUpTo64ThenLogarithmic) {
  using stickslip::records_convergence_after;
  for (std::uint64_t b = 1; b <= 64; ++b) EXPECT_TRUE(records_convergence_after(b, 1000));
  EXPECT_FALSE(records_convergence_after(65, 1000));
  EXPECT_TRUE(records_convergence_after(66, 1000));
  EXPECT_TRUE(records_convergence_after(999, 999));  // the last block always
  // N = 10^6 in blocks of 50: 20000 blocks, a trace of a few hundred points.
  std::uint64_t points = 0;
  for (std::uint64_t b = 1; b <= 20000; ++b) points += records_convergence_after(b, 20000);
  EXPECT_GT(points, 300u);
  EXPECT_LT(points, 400u);
}
