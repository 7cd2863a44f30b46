// The model family's statistics on sweeps, for the paper's model (lane engine)
// and the family (simulate_model), fixed seeds, tolerances from standard
// errors:
//   - the time fraction at each belt level: per realization the fractions
//     sum to 1 (to rounding, 1e-12); across realizations started from the
//     stationary law, the mean at each level equals the stationary law pi
//     (stationary_law, Gaussian elimination on Q^T) within 4 standard errors;
//   - every stick-onset position lies in the stick band [-(a_s + c max|v|/k),
//     +(...)] (no under- or overflow of its histogram);
//   - the joint (D, X) histogram's marginals equal the 1-D histograms'
//     counts exactly, under- and overflow included;
//   - the paper's model has no damping power (exactly 0), and the family's
//     engine run on the paper's model gives the lane engine's new statistics
//     within 1e-12 relative (the pieces' end positions come from other closed
//     forms: sums of the same pieces, rounded differently).
// Bit identity of the lane and reference engines on every statistic is
// test_fast_path.cpp's (same_bits covers every schema row).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>

#include "stickslip/model/model_realization.hpp"
#include "stickslip/model/oscillator_model.hpp"
#include "stickslip/statistics_schema.hpp"
#include "stickslip/sweep.hpp"
#include "unit/engine_agreement.hpp"

namespace stickslip {
namespace {

sweep_spec family_spec() {
  sweep_spec s;
  s.base.damping = 0.5;
  s.base.static_friction = 6.0;
  s.base.kinetic_friction = 4.0;
  s.base.belt_levels = {1.0, -0.5, 0.0};
  s.base.belt_generator = {-2, 1.5, 0.5, 0.25, -0.75, 0.5, 1, 2, -3};
  s.base.window = 20.0;
  s.realizations = 4000;
  s.block_size = 250;
  s.seed = 2024;
  return s;
}

sweep_spec paper_spec() {
  sweep_spec s;
  s.base.window = 20.0;
  s.realizations = 400;
  s.block_size = 50;
  s.seed = 99;
  s.axes = {{"lambda", {0.5, 3.8}}, {"mu", {1.0, 5.0}}};
  return s;
}

TEST(FamilyStatistics, LevelFractionsAreTheStationaryLaw) {
  const sweep_spec s = family_spec();
  const auto rs = run_sweep(s, 2);
  const auto& st = rs.points[0].stats;
  const auto pi = stationary_law(model_of(rs.points[0].parameters).belt);
  ASSERT_EQ(st.level_fraction.size(), 3u);
  double sum_of_means = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& m = st.level_fraction[i];
    EXPECT_EQ(m.count(), s.realizations);
    EXPECT_LE(std::abs(m.mean() - pi[i]), 4.0 * m.std_error())
        << "level " << i << ": " << m.mean() << " vs pi " << pi[i] << " (SE " << m.std_error() << ")";
    sum_of_means += m.mean();
  }
  EXPECT_NEAR(sum_of_means, 1.0, 1e-12);
}

TEST(FamilyStatistics, LevelFractionsOfEachRealizationSumToOne) {
  const sweep_spec s = family_spec();
  const model_parameters p = point_parameters(s, 0);
  const family_point fp(p);
  realization_observer obs(p);
  for (std::uint64_t r = 0; r < 300; ++r) {
    const auto start = draw_model_initial_state(fp, s.initial, s.seed, r);
    obs.reset(r, start.position, start.velocity, 1);
    simulate_family_realization(fp, start, s.seed, r, s.max_events, obs);
    obs.finish();
    const auto& f = obs.samples().level_fractions;
    EXPECT_NEAR(std::accumulate(f.begin(), f.end(), 0.0), 1.0, 1e-12) << r;
    for (double x : f) EXPECT_GE(x, 0.0);
    EXPECT_GE(obs.record().friction_power, 0.0);
  }
}

// Marginals of the joint histogram against the 1-D histograms, slot by slot.
void expect_marginals_exact(const point_statistics& st) {
  const auto& j = st.stick_duration_onset;
  const auto& d = st.stick_duration_hist;
  const auto& x = st.stick_onset_position_hist;
  const std::size_t nx = d.bins() + 2, ny = x.bins() + 2;
  auto slot_count = [](const histogram& h, std::size_t slot) {
    return slot == 0 ? h.underflow() : slot == h.bins() + 1 ? h.overflow() : h.count(slot - 1);
  };
  for (std::size_t a = 0; a < nx; ++a) {
    std::uint64_t row = 0;
    for (std::size_t b = 0; b < ny; ++b) row += j.cell(a, b);
    EXPECT_EQ(row, slot_count(d, a)) << "D slot " << a;
  }
  for (std::size_t b = 0; b < ny; ++b) {
    std::uint64_t col = 0;
    for (std::size_t a = 0; a < nx; ++a) col += j.cell(a, b);
    EXPECT_EQ(col, slot_count(x, b)) << "X slot " << b;
  }
  EXPECT_EQ(j.total(), st.stick_duration.count());
}

TEST(FamilyStatistics, OnsetsLieInTheBandAndJointMarginalsAreExact) {
  for (const sweep_spec& s : {family_spec(), paper_spec()}) {
    const auto rs = run_sweep(s, 2);
    for (const auto& p : rs.points) {
      const auto& st = p.stats;
      ASSERT_GT(st.stick_onset_position.count(), 0u);
      EXPECT_EQ(st.stick_onset_position.count(), st.stick_duration.count());
      EXPECT_EQ(st.stick_onset_position_hist.underflow(), 0u);
      EXPECT_EQ(st.stick_onset_position_hist.overflow(), 0u);
      double vmax = 0;
      for (double v : p.parameters.levels()) vmax = std::max(vmax, std::abs(v));
      EXPECT_EQ(st.stick_onset_position_hist.hi(),
                p.parameters.band_half_width() + p.parameters.damping * vmax / p.parameters.stiffness);
      EXPECT_EQ(st.stick_onset_position_hist.lo(), -st.stick_onset_position_hist.hi());
      expect_marginals_exact(st);
    }
  }
}

TEST(FamilyStatistics, PaperModelHasNoDampingPower) {
  const sweep_spec s = paper_spec();
  const auto rs = run_sweep(s, 2);
  for (const auto& p : rs.points) {
    EXPECT_EQ(p.stats.damping_power.count(), s.realizations);
    EXPECT_EQ(p.stats.damping_power.mean(), 0.0);
    EXPECT_EQ(p.stats.damping_power.sum_sq_dev(), 0.0);
    EXPECT_GT(p.stats.friction_power.mean(), 0.0);
    ASSERT_EQ(p.stats.level_fraction.size(), 2u);
  }
}

TEST(FamilyStatistics, FamilyEngineGivesTheLaneEnginesStatisticsOnThePaperModel) {
  const sweep_spec s = paper_spec();
  auto close = [](double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b)); };
  int differ = 0;
  for (std::size_t point = 0; point < point_count(s); ++point) {
    for (std::uint64_t block = 0; block < blocks_per_point(s); ++block) {
      const work_unit u{point, block};
      const auto lanes = simulate_block(s, u).stats;
      const auto family = simulate_block_reference(s, u).stats;
      // Episodes are the same bits: X and the joint histogram too.
      EXPECT_TRUE(lanes.stick_onset_position == family.stick_onset_position);
      EXPECT_TRUE(lanes.stick_duration_onset == family.stick_duration_onset);
      if (!(lanes.friction_power == family.friction_power)) ++differ;
      EXPECT_TRUE(close(lanes.friction_power.mean(), family.friction_power.mean()))
          << lanes.friction_power.mean() << " vs " << family.friction_power.mean();
      EXPECT_TRUE(close(lanes.friction_power.std_dev(), family.friction_power.std_dev()));
      for (std::size_t i = 0; i < 2; ++i)
        EXPECT_TRUE(close(lanes.level_fraction[i].mean(), family.level_fraction[i].mean()))
            << lanes.level_fraction[i].mean() << " vs " << family.level_fraction[i].mean();
      EXPECT_EQ(family.damping_power.mean(), 0.0);
    }
  }
  std::printf("friction power: %d of %zu blocks differ in the last bits between the engines\n",
              differ, point_count(s) * blocks_per_point(s));
}

// The paper study's setting: the paper's statistics are the same bits, the
// family's stay empty, on both engines.
TEST(FamilyStatistics, OffLeavesThePapersStatisticsAndEmptiesTheFamilys) {
  for (const sweep_engine engine : {sweep_engine::fast, sweep_engine::reference}) {
    sweep_spec on = paper_spec();
    on.engine = engine;
    sweep_spec off = on;
    off.family_statistics = false;
    const auto a = run_sweep(on, 2), b = run_sweep(off, 2);
    for (std::size_t i = 0; i < a.points.size(); ++i) {
      const auto &x = a.points[i].stats, &y = b.points[i].stats;
      for (std::size_t q = 0; q < paper_quantity_count; ++q) {
        EXPECT_TRUE(x.*quantity_table[q].moments == y.*quantity_table[q].moments) << q;
        if (quantity_table[q].density) {
          EXPECT_TRUE(x.*quantity_table[q].density == y.*quantity_table[q].density) << q;
        }
      }
      EXPECT_EQ(x.events, y.events);
      EXPECT_EQ(y.stick_onset_position.count(), 0u);
      EXPECT_EQ(y.friction_power.count(), 0u);
      EXPECT_EQ(y.level_fraction[0].count(), 0u);
      EXPECT_EQ(y.stick_duration_onset.total(), 0u);
    }
  }
}

// The study's setting skips the causal score's bookkeeping on the lane
// engine (paper_statistics_observer) and drops it on the reference engines:
// the statistics stay the same bits on every engine, for the paper's model
// and a family model, the score is left empty, and the records carry none of
// its sums. (Their friction and damping power are not the same there: the
// lane engine's paper observer does not sum pieces of motion.)
TEST(FamilyStatistics, OffLeavesNoCausalScoreAndTheEnginesAgree) {
  for (sweep_spec s : {paper_spec(), family_spec()}) {
    s.family_statistics = false;
    testing_support::expect_engines_agree(s, 2);
    s.keep_records = true;
    for (const sweep_engine engine : {sweep_engine::fast, sweep_engine::reference}) {
      s.engine = engine;
      const auto rs = run_sweep(s, 2);
      for (const auto& p : rs.points) EXPECT_EQ(p.stats.stick_fraction_causal_score.count(), 0u);
      for (const auto& r : rs.records[0]) {
        EXPECT_EQ(r.events.switch_time_sum, 0.0);
        EXPECT_EQ(r.stick_switch_moment, 0.0);
        EXPECT_EQ(r.stick_time_moment, 0.0);
      }
    }
  }
}

}  // namespace
}  // namespace stickslip
