// The survival group (--statistics survival): the grouped Kaplan-Meier
// estimate against a hand computation, the counts' merge and engines, and
// the oracle: Kaplan-Meier of the stick durations censored at
// t_a = 50 against the uncensored durations of the very same sticks, taken
// from the same realizations run on a longer window.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "stickslip/io/config.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/survival_estimate.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip {
namespace {

// Six episodes on [0, 4] in 4 bins: ended at 0.5, 1.5, 1.5, 2.5; censored
// at 1.8 (after the events of its bin) and 3.5.
survival_counts six_episodes() {
  survival_counts c(4.0, 4);
  for (double d : {0.5, 1.5, 1.5, 2.5}) c.add(d, false);
  for (double d : {1.8, 3.5}) c.add(d, true);
  return c;
}

TEST(KaplanMeier, MatchesAHandComputation) {
  // n = 6, 5, 2, 1, 0 at the edges 0, 1, 2, 3, 4; d = 1, 2, 1, 0 per bin.
  // S = 1, 5/6, 5/6 * 3/5 = 1/2, 1/2 * 1/2 = 1/4, 1/4.
  // Greenwood V = 0, 1/(6*5) = 1/30, 1/30 + 2/(5*3) = 1/6, 1/6 + 1/(2*1) = 2/3, 2/3.
  // Restricted mean (trapezoids of width 1):
  // (1 + 5/6)/2 + (5/6 + 1/2)/2 + (1/2 + 1/4)/2 + (1/4 + 1/4)/2 = 53/24.
  const auto k = kaplan_meier(six_episodes());
  const std::vector<double> edges{0, 1, 2, 3, 4}, s{1, 5.0 / 6, 0.5, 0.25, 0.25},
      v{0, 1.0 / 30, 1.0 / 6, 2.0 / 3, 2.0 / 3};
  const std::vector<std::uint64_t> n{6, 5, 2, 1, 0};
  ASSERT_EQ(k.duration.size(), 5u);
  EXPECT_EQ(k.at_risk, n);
  for (std::size_t j = 0; j < 5; ++j) {
    EXPECT_EQ(k.duration[j], edges[j]);
    EXPECT_NEAR(k.survival[j], s[j], 1e-15) << j;
    EXPECT_NEAR(k.greenwood[j], v[j], 1e-15) << j;
    // The log(-log) interval written the way lifelines writes it:
    // exp(-exp(log(-log S) -+ z sqrt(V) / log S)).
    if (s[j] < 1) {
      const double ls = std::log(s[j]), w = survival_z95 * std::sqrt(v[j]) / ls;
      EXPECT_NEAR(k.ci95_low[j], std::exp(-std::exp(std::log(-ls) - w)), 1e-14) << j;
      EXPECT_NEAR(k.ci95_high[j], std::exp(-std::exp(std::log(-ls) + w)), 1e-14) << j;
      EXPECT_LT(k.ci95_low[j], s[j]);
      EXPECT_GT(k.ci95_high[j], s[j]);
    } else {
      EXPECT_EQ(k.ci95_low[j], 1.0);
      EXPECT_EQ(k.ci95_high[j], 1.0);
    }
  }
  EXPECT_NEAR(k.restricted_mean, 53.0 / 24, 1e-15);
}

TEST(KaplanMeier, WithoutCensoringIsTheEmpiricalSurvival) {
  survival_counts c(1.0, 10);
  std::vector<double> d;
  for (int i = 0; i < 97; ++i) d.push_back(std::fmod(0.6180339887 * i, 1.0));
  for (double x : d) c.add(x, false);
  const auto k = kaplan_meier(c);
  for (std::size_t j = 0; j <= 10; ++j) {
    std::size_t above = 0;
    for (double x : d) above += c.ended().slot(x) - 1 >= j;
    EXPECT_NEAR(k.survival[j], above / 97.0, 1e-14) << j;
    EXPECT_EQ(k.at_risk[j], above) << j;
  }
}

TEST(KaplanMeier, EmptyCountsGiveNaN) {
  const auto k = kaplan_meier(survival_counts(2.0, 3));
  EXPECT_TRUE(std::isnan(k.survival[0]));
  EXPECT_TRUE(std::isnan(k.restricted_mean));
  EXPECT_EQ(k.at_risk[0], 0u);
}

TEST(SurvivalCounts, MergingHalvesEqualsFillingAtOnce) {
  survival_counts all(4.0, 4), a(4.0, 4), b(4.0, 4);
  const double d[] = {0.1, 3.9, 4.0, 7.0, 2.2, 1.0};
  for (int i = 0; i < 6; ++i) {
    all.add(d[i], i % 3 == 0);
    (i < 3 ? a : b).add(d[i], i % 3 == 0);
  }
  a += b;
  EXPECT_EQ(a, all);
  EXPECT_EQ(all.ended().overflow(), 0u);
  EXPECT_EQ(all.censored().overflow(), 1u);  // 7 > 4, censored
}

sweep_spec small_sweep(sweep_engine engine) {
  sweep_spec s;
  s.base.stiffness = 40.0;
  s.base.window = 20.0;
  s.realizations = 120;
  s.seed = 20261127;
  s.engine = engine;
  s.axes = {{"lambda", {0.3, 3.8}}, {"mu", {0.5, 5.0}}};
  s.statistics.survival = true;
  resolve_survival_grid(s);
  return s;
}

TEST(SurvivalSweep, FastAndReferenceEnginesAndThreadCountsGiveTheSameBits) {
  const auto fast1 = run_sweep(small_sweep(sweep_engine::fast), 1);
  const auto fast2 = run_sweep(small_sweep(sweep_engine::fast), 2);
  const auto ref2 = run_sweep(small_sweep(sweep_engine::reference), 2);
  ASSERT_EQ(fast1.points.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    const auto& s = fast1.points[i].stats;
    ASSERT_TRUE(s.stick_survival.selected());
    EXPECT_EQ(s, fast2.points[i].stats) << i;
    EXPECT_EQ(s, ref2.points[i].stats) << i;
    // Every stick and counted slip is counted once; one episode per
    // realization is cut by t_a (a stick, a counted slip, or the uncounted
    // slip of a realization without a stick).
    const auto k = kaplan_meier(s.stick_survival), h = kaplan_meier(s.slip_survival);
    EXPECT_EQ(k.at_risk[0], s.stick_duration.count());
    EXPECT_EQ(h.at_risk[0], s.slip_duration.count());
    const auto cut = s.stick_survival.censored().total() + s.slip_survival.censored().total();
    EXPECT_EQ(cut, s.realizations - s.no_stick) << i;
  }
}

TEST(SurvivalSweep, ModelFamilyEnginesAgreeToo) {
  auto family = [](sweep_engine e) {
    sweep_spec s = small_sweep(e);
    s.axes = {{"lambda", {0.5, 3.0}}};
    s.base.static_friction = 6.0;
    s.base.kinetic_friction = 5.0;
    resolve_survival_grid(s);
    return run_sweep(s, 2);
  };
  const auto fast = family(sweep_engine::fast), ref = family(sweep_engine::reference);
  for (std::size_t i = 0; i < fast.points.size(); ++i)
    EXPECT_EQ(fast.points[i].stats, ref.points[i].stats) << i;
}

TEST(SurvivalSweep, TheGroupChangesNoOtherStatistic) {
  sweep_spec with = small_sweep(sweep_engine::fast), without = with;
  without.statistics.survival = false;
  const auto a = run_sweep(with, 2), b = run_sweep(without, 2);
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    auto s = a.points[i].stats;
    s.stick_survival = s.slip_survival = survival_counts{};
    EXPECT_EQ(s, b.points[i].stats) << i;
  }
}

TEST(SurvivalSweep, ASpecWithAnotherSelectionIsNamedAsTheDifference) {
  sweep_spec with = small_sweep(sweep_engine::fast), without = with;
  without.statistics.survival = false;
  EXPECT_FALSE(same_results(with, without));
  EXPECT_EQ(first_difference(without, with), "statistics: paper vs paper,survival");
  sweep_spec finer = with;
  finer.survival.bins = 400;
  EXPECT_NE(first_difference(with, finer).find("survival grid: 200 bins"), std::string::npos);
  EXPECT_EQ(deserialize_sweep_spec(serialize(with)), with);
  EXPECT_EQ(io::parse_sweep_toml(io::to_toml(with), "resolved"), with);
  EXPECT_EQ(io::parse_sweep_toml(io::to_toml(without), "resolved"), without);
}

// Every episode of one realization.
struct episode_list : observer_base {
  std::vector<episode> episodes;
  void on_episode(const episode& e) { episodes.push_back(e); }
};

// The oracle. The paper model at k = 40, mu = 5 and a small lambda
// (long sticks, few per realization: the stick cut by t_a is a material
// fraction of them, about 3 %). With common random numbers the streams do not depend
// on t_a, so the realizations on [0, 60] are those on [0, 50] continued:
// every stick that starts before 50 is whole there (sticks last at most
// d_max = 2.45 s). Kaplan-Meier of the censored sweep must hold their
// empirical survival inside its Greenwood 95 % interval; the naive estimate
// (the cut sticks taken as ended) must not, or the check has no power.
TEST(SurvivalOracle, KaplanMeierCensoredAtTaHoldsTheUncensoredLawOfTheSameSticks) {
  sweep_spec s;
  s.base.stiffness = 40.0;
  s.base.friction_coefficient = 5.0;
  s.base.switch_rate = 0.1;
  s.base.window = 50.0;
  s.realizations = 2000;
  s.seed = 27;
  s.common_random_numbers = true;
  s.statistics.survival = true;
  s.survival.bins = 40;
  resolve_survival_grid(s);
  const auto censored_run = run_sweep(s, 2);
  const survival_counts& counts = censored_run.points[0].stats.stick_survival;
  const auto km = kaplan_meier(counts);

  survival_counts whole(counts.upper(), counts.bins()), naive(counts.upper(), counts.bins());
  model_parameters longer = point_parameters(s, 0);
  longer.window = 60.0;
  for (std::uint64_t r = 0; r < s.realizations; ++r) {
    episode_list obs;
    (void)simulate_realization(s, longer, r, obs);
    for (const auto& e : obs.episodes)
      if (e.kind == mode::stick && e.start < 50.0 && e.duration() > 0.0) {
        ASSERT_FALSE(e.censored) << "a stick that started before 50 is cut at 60";
        whole.add(e.duration(), false);
        naive.add(std::min(e.end, 50.0) - e.start, false);
      }
  }
  const auto truth = kaplan_meier(whole), clipped = kaplan_meier(naive);
  // The same sticks: as many, and cut ones among them.
  ASSERT_EQ(truth.at_risk[0], km.at_risk[0]);
  const double cut_fraction = static_cast<double>(counts.censored().total()) /
                              static_cast<double>(km.at_risk[0]);
  std::printf("sticks %llu, censored by t_a %.4f\n",
              static_cast<unsigned long long>(km.at_risk[0]), cut_fraction);
  // One episode per realization is cut, against ~6 sticks: about 3 % of
  // the sticks (2.3 to 3.1 % for lambda from 0.02 to 0.3 at this k and mu),
  // the longest ones, enough to move the naive estimate out of the interval.
  EXPECT_GT(cut_fraction, 0.025);
  std::size_t checked = 0, naive_outside = 0;
  for (std::size_t j = 1; j < km.duration.size(); j += 4) {
    if (!(km.survival[j] > 0.05 && km.survival[j] < 0.95)) continue;
    ++checked;
    std::printf("D >= %.3f s: KM %.4f [%.4f, %.4f], uncensored %.4f, naive %.4f\n",
                km.duration[j], km.survival[j], km.ci95_low[j], km.ci95_high[j],
                truth.survival[j], clipped.survival[j]);
    EXPECT_GE(truth.survival[j], km.ci95_low[j]) << km.duration[j];
    EXPECT_LE(truth.survival[j], km.ci95_high[j]) << km.duration[j];
    naive_outside += clipped.survival[j] < km.ci95_low[j] || clipped.survival[j] > km.ci95_high[j];
  }
  EXPECT_GE(checked, 5u);
  EXPECT_GE(naive_outside, 3u);
}

}  // namespace
}  // namespace stickslip
