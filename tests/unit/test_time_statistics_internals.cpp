// The observe-time accumulator's shortcuts against the plain forms they
// replace:
//   - quantile_sketch::code (written without a branch) equals its definition
//     written plainly here (0 unless |x| >= zero_threshold, else key(x) with
//     sign_bit for x < 0) for every class of double (±0, subnormals, the zero
//     threshold and its neighbours, ±inf, NaN, and random bit patterns): the
//     sketches' bins cannot change;
//   - count(), kept as samples are added, is the sum of the bins after
//     add, +=, set_raw and a copy;
//   - quantiles() with more levels than its fixed room for ranks (17) and
//     in no order equals quantile() level by level;
//   - time_statistics::finish() changes no value, and adds and merges after
//     it give what they give without it;
//   - time_statistics::quantiles() equals the sketches' own quantiles after
//     every kind of change (add, +=, set_raw): a cached value is never stale.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <random>
#include <vector>

#include "stickslip/accumulators/quantile_sketch.hpp"
#include "stickslip/accumulators/time_statistics.hpp"

namespace stickslip {
namespace {

// The code as first defined, with branches.
std::uint32_t code_by_definition(double x) {
  if (!(std::abs(x) >= quantile_sketch::zero_threshold)) return 0;
  return quantile_sketch::key(x) | (x < 0.0 ? quantile_sketch::sign_bit : 0u);
}

TEST(QuantileSketchCode, EqualsItsDefinitionForEveryKindOfDouble) {
  using lim = std::numeric_limits<double>;
  const double z = quantile_sketch::zero_threshold;
  std::vector<double> xs = {0.0,
                            -0.0,
                            lim::denorm_min(),
                            lim::min(),
                            z,
                            std::nextafter(z, 0.0),
                            std::nextafter(z, lim::infinity()),
                            1.0,
                            0.1,
                            123.456,
                            lim::max(),
                            lim::infinity(),
                            lim::quiet_NaN(),
                            std::bit_cast<double>(std::uint64_t{0x7FF0000000000001})};  // sNaN
  const std::size_t fixed = xs.size();
  for (std::size_t i = 0; i < fixed; ++i) xs.push_back(-xs[i]);
  std::mt19937_64 bits(20261128);
  for (int i = 0; i < 200000; ++i) xs.push_back(std::bit_cast<double>(bits()));
  std::size_t nonzero = 0, negative = 0;
  for (double x : xs) {
    const auto c = code_by_definition(x);
    ASSERT_EQ(quantile_sketch::code(x), c) << "x = " << x;
    nonzero += c != 0;
    negative += (c & quantile_sketch::sign_bit) != 0;
  }
  // the comparison covered both signs and both kinds of codes
  EXPECT_GT(nonzero, xs.size() / 4);
  EXPECT_GT(negative, xs.size() / 8);
}

// count() is kept as samples are added: it must stay the sum of the bins
// after add, +=, set_raw and a copy.
std::uint64_t bin_sum(const quantile_sketch& s) {
  std::uint64_t n = s.zero();
  for (const auto& st : {s.negative(), s.positive()})
    for (auto c : st.counts) n += c;
  return n;
}

TEST(QuantileSketchCount, IsTheSumOfTheBinsAfterEveryChange) {
  quantile_sketch a, b;
  for (int i = -300; i < 500; ++i) a.add(i % 7 == 0 ? 0.0 : 1e-3 * i);
  EXPECT_EQ(a.count(), 800u);
  EXPECT_EQ(a.count(), bin_sum(a));
  for (int i = 0; i < 123; ++i) b.add(-1e5 * i);
  a += b;
  EXPECT_EQ(a.count(), 923u);
  EXPECT_EQ(a.count(), bin_sum(a));
  quantile_sketch c;
  c.set_raw(a.negative(), a.zero(), a.positive());
  EXPECT_EQ(c.count(), 923u);
  EXPECT_EQ(c, a);
  const quantile_sketch d = c;
  EXPECT_EQ(d.count(), 923u);
  c.set_raw({}, 0, {});
  EXPECT_EQ(c.count(), 0u);
  EXPECT_TRUE(std::isnan(c.quantile(0.5)));
}

TEST(QuantileSketchBlock, ManyLevelsInAnyOrderAreTheLevelByLevelQuantiles) {
  quantile_sketch s;
  for (int i = -500; i < 700; ++i) s.add(0.01 * i * std::abs(i));
  std::vector<double> levels;
  for (int i = 0; i <= 20; ++i) levels.push_back(i / 20.0);  // 21 levels, ascending
  std::vector<double> shuffled(levels.rbegin(), levels.rend());  // and descending
  for (const auto& q : {levels, shuffled}) {
    std::vector<double> out(q.size());
    s.quantiles(q.data(), q.size(), out.data());
    for (std::size_t i = 0; i < q.size(); ++i) ASSERT_EQ(out[i], s.quantile(q[i])) << q[i];
  }
}

observed_states states(std::size_t n, double shift) {
  observed_states s(n);
  for (std::size_t j = 0; j < n; ++j) {
    s.position()[j] = std::sin(0.7 * static_cast<double>(j) + shift);
    s.velocity()[j] = std::cos(1.3 * static_cast<double>(j) - shift) * (1.0 + shift);
    s.belt_velocity()[j] = j % 2 ? 1.0 : -1.0;
    s.energy()[j] = 0.5 + shift;
    s.level()[j] = static_cast<double>(j % 2);
    s.sticking()[j] = (j + static_cast<std::size_t>(10 * shift)) % 3 == 0 ? 1.0 : 0.0;
  }
  return s;
}

// quantiles() of both sketches at every time against the sketches' own.
void expect_fresh(const time_statistics& t) {
  constexpr std::size_t q = std::size(observed_quantile_levels);
  for (std::size_t j = 0; j < t.times().size(); ++j) {
    for (auto sketch : {&time_point_statistics::position_quantiles,
                        &time_point_statistics::velocity_quantiles}) {
      double cached[q], own[q];
      t.quantiles(j, sketch, cached);
      (t.at(j).*sketch).quantiles(observed_quantile_levels, q, own);
      for (std::size_t i = 0; i < q; ++i) ASSERT_EQ(cached[i], own[i]) << "t_" << j;
    }
  }
}

TEST(TimeStatisticsQuantiles, TheCacheFollowsEveryChange) {
  const std::vector<double> times = {0.0, 0.5, 1.0, 2.0, 3.5, 5.0, 7.0};
  time_statistics a(times, 2), b(times, 2);
  double before[5];
  for (int r = 0; r < 5; ++r) a.add(states(times.size(), 0.1 * r));
  a.quantiles(3, &time_point_statistics::position_quantiles, before);
  expect_fresh(a);
  for (int r = 0; r < 40; ++r) a.add(states(times.size(), 2.0 + 0.37 * r));  // after add
  expect_fresh(a);
  double after[5];
  a.quantiles(3, &time_point_statistics::position_quantiles, after);
  EXPECT_NE(std::vector<double>(before, before + 5), std::vector<double>(after, after + 5))
      << "the samples added should move a quantile (else this test proves nothing)";
  for (int r = 0; r < 30; ++r) b.add(states(times.size(), -3.0 - 0.5 * r));
  a += b;  // after +=
  expect_fresh(a);
  std::vector<time_point_statistics> at;
  for (std::size_t j = 0; j < times.size(); ++j) at.push_back(b.at(j));
  a.set_raw(b.realizations(), at, b.level_counts());  // after set_raw
  expect_fresh(a);
  EXPECT_EQ(a, b);
}

// finish() (a complete point's accumulator: room freed, quantiles computed)
// changes no value, and an accumulator after it still adds and merges as
// one that was never finished.
TEST(TimeStatisticsFinish, ChangesNoValueAndAddsStillWork) {
  const std::vector<double> times = {0.0, 0.5, 1.0, 2.0, 3.5, 5.0, 7.0};
  time_statistics a(times, 2), plain(times, 2), more(times, 2);
  for (int r = 0; r < 150; ++r) {  // past buffered_realizations: settled and buffered codes
    a.add(states(times.size(), 0.05 * r));
    plain.add(states(times.size(), 0.05 * r));
  }
  a.finish();
  EXPECT_EQ(a, plain);
  expect_fresh(a);
  for (std::size_t j = 0; j < times.size(); ++j) {
    double x[5], y[5];
    a.quantiles(j, &time_point_statistics::velocity_quantiles, x);
    plain.quantiles(j, &time_point_statistics::velocity_quantiles, y);
    for (int i = 0; i < 5; ++i) ASSERT_EQ(x[i], y[i]);
  }
  for (int r = 0; r < 20; ++r) more.add(states(times.size(), 40.0 + r));  // beyond the range
  a += more, plain += more;
  a.add(states(times.size(), -60.0)), plain.add(states(times.size(), -60.0));
  EXPECT_EQ(a, plain);
  expect_fresh(a);
  time_statistics none;
  none.finish();  // not selected: nothing to do
  EXPECT_FALSE(none.selected());
}

}  // namespace
}  // namespace stickslip
