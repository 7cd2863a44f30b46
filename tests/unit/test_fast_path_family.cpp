// The lane engine on the model family (detail::runs_in_lanes: c = 0, two
// nonzero levels of any signs, any rates, mu_s >= mu_k) against the family's
// scalar engine, simulate_model with markov_level_switches
// (simulate_family_realization, the oracle): every field of every episode and
// event and the event counts, by bit pattern, realization by realization, on
// random points and seeds; then every statistic and record of whole sweeps
// (sweep_engine::fast against reference, which runs simulate_model).
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "stickslip/detail/fast_block.hpp"
#include "stickslip/error.hpp"
#include "stickslip/model/model_realization.hpp"
#include "stickslip/observer.hpp"
#include "stickslip/sweep.hpp"
#include "unit/engine_agreement.hpp"
#include "unit/same_bits.hpp"

namespace stickslip {
namespace {

using testing_support::same_bits;
using testing_support::recorder;
using testing_support::describe;
using testing_support::same_episode;
using testing_support::same_event;
using testing_support::expect_engines_agree;

// Half-turn returns in a trace: a stick ended by a switch to the opposite
// level from the outer side of the new slip's centre, sigma (x - sigma a_k)
// > 0 (mu_s > mu_k), whose slip then ends in a stick (model_engine.hpp; the
// branch a user found wrong, returned at the mirror point).
int half_turn_returns(const recorder& r, double v_start, double ak) {
  int n = 0;
  bool sticking = !r.episodes.empty() && r.episodes.front().kind == mode::stick;
  bool half_turn = false;
  double v = v_start;
  for (const event& e : r.events) {
    if (e.kind == event_kind::stick_onset && half_turn) ++n;
    half_turn = false;
    if (e.kind == event_kind::belt_switch && sticking && e.belt_velocity == -v) {
      const double sigma = e.belt_velocity > v ? 1.0 : -1.0;
      half_turn = sigma * (e.position - sigma * ak) > 0.0;
    }
    if (e.kind == event_kind::belt_switch) v = e.belt_velocity;
    sticking = e.kind == event_kind::stick_onset;
  }
  return n;
}

// Realizations [first, last) of point 0 of s: lanes against simulate_model.
// Returns the episodes compared; `kinds` adds up the events by kind, and
// `half_turns` the half-turn returns of the reference's traces.
std::size_t expect_traces_agree(const sweep_spec& s, std::uint64_t first, std::uint64_t last,
                                event_counts& kinds, int& half_turns) {
  const auto p = point_parameters(s, 0);
  EXPECT_FALSE(p.is_paper_model());
  EXPECT_TRUE(detail::runs_in_lanes(p));
  const family_point fp(p);
  const auto lanes = detail::trace_realizations_lanes(s, 0, first, last);
  EXPECT_EQ(lanes.size(), last - first);
  std::size_t compared = 0;
  for (std::uint64_t r = first; r < last && r - first < lanes.size(); ++r) {
    recorder ref;
    const auto start = draw_model_initial_state(fp, s.initial, s.seed, r);
    const auto counts = simulate_family_realization(fp, start, s.seed, r, s.max_events, ref);
    half_turns += half_turn_returns(ref, fp.model.belt.levels[start.level], fp.model.kinetic_offset());
    const auto& got = lanes[r - first];
    const std::string where = "realization " + std::to_string(r);
    EXPECT_TRUE(same_bits(counts, got.counts)) << where;
    kinds += counts;
    EXPECT_EQ(ref.episodes.size(), got.episodes.size()) << where;
    if (ref.episodes.size() != got.episodes.size()) return compared;
    for (std::size_t i = 0; i < ref.episodes.size(); ++i)
      if (!same_episode(ref.episodes[i], got.episodes[i])) {
        ADD_FAILURE() << where << " episode " << i << ": " << describe(ref.episodes[i]) << " vs "
                      << describe(got.episodes[i]);
        return compared;
      }
    EXPECT_EQ(ref.events.size(), got.events.size()) << where;
    if (ref.events.size() != got.events.size()) return compared;
    for (std::size_t i = 0; i < ref.events.size(); ++i)
      if (!same_event(ref.events[i], got.events[i])) {
        ADD_FAILURE() << where << " event " << i << " (" << to_string(ref.events[i].kind)
                      << " vs " << to_string(got.events[i].kind) << ")";
        return compared;
      }
    compared += ref.episodes.size();
  }
  return compared;
}
std::size_t expect_traces_agree(const sweep_spec& s, std::uint64_t first, std::uint64_t last,
                                event_counts& kinds) {
  int half_turns = 0;
  return expect_traces_agree(s, first, last, kinds, half_turns);
}

// A random undamped two-level point: k, mu_k <= mu_s (equal one time in
// four), levels of any signs (v2 = -v1 one time in three), rates, t_a.
sweep_spec random_family_point(std::mt19937_64& rng) {
  auto uniform = [&](double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(rng); };
  auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<std::uint64_t>(n)); };
  auto log_uniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, uniform(0, 1)); };
  sweep_spec s;
  auto& b = s.base;
  b.stiffness = pick(3) == 0 ? 4.0 : pick(2) == 0 ? 40.0 : log_uniform(1.0, 100.0);
  b.kinetic_friction = log_uniform(0.3, 7.0);
  b.static_friction = pick(4) == 0 ? b.kinetic_friction : b.kinetic_friction * log_uniform(1.0, 4.0);
  double v1 = (pick(2) ? 1.0 : -1.0) * log_uniform(0.1, 3.0);
  double v2 = -v1;
  if (pick(3) != 0) {
    v2 = (pick(2) ? 1.0 : -1.0) * log_uniform(0.1, 3.0);
    if (v2 == v1) v2 = -v1;
  }
  if (pick(5) == 0) (pick(2) ? v1 : v2) = 0.0;  // a resting level
  b.belt_levels = {v1, v2};
  const double r1 = log_uniform(0.1, 30.0);
  b.belt_rates = {r1, pick(3) == 0 ? r1 : log_uniform(0.1, 30.0)};
  if (b.static_friction == b.kinetic_friction && v2 == -v1 && b.belt_rates[0] == b.belt_rates[1])
    b.belt_rates[1] *= 1.5;  // not the paper's model (that one has its own tests)
  b.window = uniform(5.0, 25.0);
  s.seed = rng();
  s.initial.belt_start = pick(3) - 1;
  if (pick(2) == 0) {
    s.initial.position_min = -3.0, s.initial.position_max = 3.0;
    s.initial.velocity_min = -4.0, s.initial.velocity_max = 4.0;
  }
  return s;
}

std::string describe(const sweep_spec& s) {
  const auto& b = s.base;
  return "k " + std::to_string(b.stiffness) + " mu_s " + std::to_string(b.static_friction) +
         " mu_k " + std::to_string(b.kinetic_friction) + " levels " +
         std::to_string(b.belt_levels[0]) + "," + std::to_string(b.belt_levels[1]) + " rates " +
         std::to_string(b.belt_rates[0]) + "," + std::to_string(b.belt_rates[1]) + " ta " +
         std::to_string(b.window) + " seed " + std::to_string(s.seed) + " start " +
         std::to_string(s.initial.belt_start);
}

TEST(FastPathFamily, EveryFieldEqualsSimulateModelOnRandomPoints) {
  std::mt19937_64 rng(20240611);
  std::size_t compared = 0;
  event_counts kinds;
  for (int i = 0; i < 60; ++i) {
    const auto s = random_family_point(rng);
    SCOPED_TRACE(describe(s));
    validate(s);
    compared += expect_traces_agree(s, 0, 40, kinds);
    if (HasFailure()) return;
  }
  EXPECT_GT(compared, 20000u);
  // every kind of event occurred, many times
  EXPECT_GT(kinds.stick_breaks, 500u);
  EXPECT_GT(kinds.slip_reversals, 500u);
  EXPECT_GT(kinds.stick_onsets, 5000u);
}

// The paper's grid as a family model (mu_s > mu_k, levels +-1, both rates
// lambda), and asymmetric belts. The symmetric grid must take the half-turn
// return (a switch out of a stick between a_k and a_s) many times.
TEST(FastPathFamily, EveryFieldEqualsSimulateModelOnGrids) {
  int half_turns = 0;
  for (const bool asymmetric : {false, true})
    for (const double k : {4.0, 40.0})
      for (const double lambda : {0.1, 3.8, 30.0})
        for (const double mu_k : {0.5, 3.0, 7.0}) {
          sweep_spec s;
          s.base.stiffness = k;
          s.base.window = 20.0;
          s.base.kinetic_friction = mu_k;
          s.base.static_friction = 8.0;
          s.base.switch_rate = lambda;
          if (asymmetric) {
            s.base.belt_levels = {1.5, -0.4};
            s.base.belt_rates = {lambda, 0.3 * lambda};
          }
          s.seed = 4242;
          SCOPED_TRACE("k " + std::to_string(k) + " lambda " + std::to_string(lambda) + " mu_k " +
                       std::to_string(mu_k) + (asymmetric ? " asymmetric" : ""));
          event_counts kinds;
          EXPECT_GT(expect_traces_agree(s, 5, 80, kinds, half_turns), 75u);
          if (HasFailure()) return;
        }
  std::printf("half-turn returns compared: %d\n", half_turns);
  EXPECT_GE(half_turns, 50);
}

// Starts with x' = v: inside the band, on its outward and inward edges and
// outside it, both levels, mu_s > mu_k and mu_s = mu_k, levels of one sign
// and of both signs.
TEST(FastPathFamily, StartsOnTheBeltVelocity) {
  for (const double mu_s : {2.0, 5.0})
    for (const auto& levels : {std::vector<double>{1.0, -0.5}, std::vector<double>{0.7, 2.0},
                               std::vector<double>{-1.2, 1.2}, std::vector<double>{0.0, 1.3},
                               std::vector<double>{-0.8, 0.0}})
      for (const int start : {1, -1})
        for (const double where : {0.3, 1.0, -1.0, 1.7, -2.5}) {
          sweep_spec s;
          s.base.stiffness = 40.0;
          s.base.window = 15.0;
          s.base.static_friction = mu_s;
          s.base.kinetic_friction = 2.0;
          s.base.belt_levels = levels;
          s.base.belt_rates = {3.0, 0.7};
          s.seed = 99;
          s.initial.belt_start = start;
          const double v = levels[start == 1 ? 0 : 1];
          s.initial.velocity_min = s.initial.velocity_max = v;
          const double as = mu_s * s.base.mass * s.base.gravity / s.base.stiffness;
          s.initial.position_min = s.initial.position_max = where * as;
          SCOPED_TRACE("mu_s " + std::to_string(mu_s) + " levels " + std::to_string(levels[0]) +
                       "," + std::to_string(levels[1]) + " start " + std::to_string(start) +
                       " x0/a_s " + std::to_string(where));
          event_counts kinds;
          (void)expect_traces_agree(s, 0, 12, kinds);
          if (HasFailure()) return;
        }
}

// A contact whose stick would last less than the resolution of t is a
// grazing touch in both engines (tests/regression/
// test_stick_shorter_than_time_resolution.cpp): mu_s one ulp above mu_k, a
// start stuck on the inner edge, no switch before t_a. With mu_s = mu_k
// (1 + 1e-9) the sticks last 4e-11 s and both engines keep them.
TEST(FastPathFamily, SticksShorterThanTheTimeResolutionAgree) {
  const double mu_k = 0.88670581033261642;
  for (const double mu_s : {std::nextafter(mu_k, 1.0), mu_k * (1.0 + 1e-9)}) {
    sweep_spec s;
    s.base.mass = 0.0228760208502688;
    s.base.stiffness = 1000.0;
    s.base.kinetic_friction = mu_k;
    s.base.static_friction = mu_s;
    s.base.belt_levels = {0.01, 0.0};
    s.base.belt_rates = {1e-3, 1e-3};
    s.base.window = 0.1;
    s.seed = 5;
    s.initial.belt_start = 1;
    s.initial.velocity_min = s.initial.velocity_max = 0.01;
    s.initial.position_min = s.initial.position_max = -0.00019898898893724184;
    SCOPED_TRACE("mu_s " + std::to_string(mu_s));
    event_counts kinds;
    EXPECT_GT(expect_traces_agree(s, 0, 4, kinds), 0u);
    if (mu_s == std::nextafter(mu_k, 1.0)) {
      EXPECT_EQ(kinds.stick_onsets, 0);
    } else {
      EXPECT_GT(kinds.stick_onsets, 0);
    }
  }
}

// Every SIMD target this CPU runs, forced one at a time (lane layouts of 8, 4,
// 2 and 1 doubles), each against simulate_model on that target.
TEST(FastPathFamily, EveryFieldEqualsSimulateModelOnEveryTarget) {
  std::mt19937_64 rng(77);
  std::vector<sweep_spec> points;
  for (int i = 0; i < 6; ++i) points.push_back(random_family_point(rng));
  for (const std::int64_t t : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(t);
    SCOPED_TRACE(hwy::TargetName(t));
    event_counts kinds;
    std::size_t compared = 0;
    for (const auto& s : points) compared += expect_traces_agree(s, 3, 40, kinds);
    EXPECT_GT(compared, 1000u);
  }
  hwy::SetSupportedTargetsForTest(0);
}

// Whole sweeps: every statistic, histogram and record of the fast engine
// (lanes) equals the reference's (simulate_model), for any threads and block
// sizes; a grid that mixes points the lanes run with points they do not
// (damped, three levels) and the paper's model, levels 0 included.
TEST(FastPathFamily, SweepStatisticsEqualTheReference) {
  sweep_spec s;
  s.base.stiffness = 40.0;
  s.base.window = 20.0;
  s.base.static_friction = 8.0;
  s.realizations = 70;
  s.block_size = 16;
  s.seed = 5;
  s.keep_records = true;
  s.axes = {{"mu_k", {0.5, 4.0, 8.0}}, {"lambda", {0.3, 5.0, 30.0}}};
  expect_engines_agree(s, 2);
  s.base.belt_levels = {2.0, -0.5};
  s.axes = {{"mu_k", {0.5, 4.0}}, {"r1", {0.3, 5.0}}, {"r2", {1.0, 20.0}}};
  s.block_size = 7;
  s.initial.belt_start = -1;
  expect_engines_agree(s, 3);
}

// The time at each level, and what uses it (P_j, the belt-rate scores), for
// two-level belts whose levels are not (positive, non-positive): both
// positive, both negative, a resting first level. The lanes booked the time
// by the sign of v (a fuzzer found P_1 = 1, P_2 = 0 for levels 0.5 and 1).
TEST(FastPathFamily, LevelTimesEqualTheReferenceForLevelsOfAnySigns) {
  for (const auto& levels : {std::vector<double>{0.5, 1.0}, std::vector<double>{-1.0, -0.3},
                             std::vector<double>{0.0, 1.0}, std::vector<double>{-0.5, 2.0}}) {
    sweep_spec s;
    s.base.stiffness = 40.0;
    s.base.window = 10.0;
    s.base.static_friction = 6.0;
    s.base.kinetic_friction = 4.0;
    s.base.belt_levels = levels;
    s.base.belt_rates = {2.0, 0.7};
    s.realizations = 60;
    s.block_size = 16;
    s.seed = 12;
    s.keep_records = true;
    SCOPED_TRACE("levels " + std::to_string(levels[0]) + "," + std::to_string(levels[1]));
    expect_engines_agree(s, 2);
    if (HasFailure()) return;
  }
}

// With common random numbers every point draws from one key: the lanes must
// use it for the family's start level and switch waits too.
TEST(FastPathFamily, CommonRandomNumbersEqualTheReference) {
  sweep_spec s;
  s.base.stiffness = 40.0;
  s.base.window = 20.0;
  s.base.static_friction = 8.0;
  s.base.belt_levels = {1.5, -0.5};
  s.base.belt_rates = {2.0, 1.0};
  s.realizations = 60;
  s.block_size = 16;
  s.seed = 9;
  s.keep_records = true;
  s.common_random_numbers = true;
  s.axes = {{"mu_k", {0.5, 4.0, 8.0}}};
  expect_engines_agree(s, 2);
}

TEST(FastPathFamily, OtherModelsStayOnSimulateModel) {
  model_parameters p;
  p.static_friction = 6.0;
  p.kinetic_friction = 4.0;
  EXPECT_TRUE(detail::runs_in_lanes(p));
  EXPECT_TRUE(detail::runs_in_lanes(model_parameters{}));  // the paper
  auto damped = p;
  damped.damping = 0.5;
  EXPECT_FALSE(detail::runs_in_lanes(damped));
  auto resting = p;
  resting.belt_levels = {1.0, 0.0};
  EXPECT_TRUE(detail::runs_in_lanes(resting));
  auto three = p;
  three.belt_levels = {1.0, -1.0, 2.0};
  three.belt_generator = {-2, 1, 1, 1, -2, 1, 1, 1, -2};
  EXPECT_FALSE(detail::runs_in_lanes(three));

  sweep_spec s;
  s.base.window = 15.0;
  s.realizations = 40;
  s.block_size = 9;
  s.seed = 11;
  s.base.static_friction = 6.0;
  s.base.kinetic_friction = 4.0;
  s.base.belt_levels = {1.0, 0.0};
  s.axes = {{"c", {0.4, 0.0}}, {"v2", {0.0, -1.0}}};
  expect_engines_agree(s, 2);
  EXPECT_THROW((void)detail::trace_realizations_lanes(s, 0, 0, 3), error);  // damped
}

// Levels at rest: a stick at 0 lasts until the switch, the band edge at 0
// is no outward edge; mu_s > mu_k and mu_s = mu_k.
TEST(FastPathFamily, EveryFieldEqualsSimulateModelWithARestingLevel) {
  for (const double mu_s : {3.0, 6.0})
    for (const double k : {4.0, 40.0})
      for (const auto& levels : {std::vector<double>{0.0, 1.0}, std::vector<double>{-2.0, 0.0}}) {
        sweep_spec s;
        s.base.stiffness = k;
        s.base.window = 20.0;
        s.base.static_friction = mu_s;
        s.base.kinetic_friction = 3.0;
        s.base.belt_levels = levels;
        s.base.belt_rates = {2.0, 0.5};
        s.seed = 8;
        s.initial.position_min = -4.0, s.initial.position_max = 4.0;
        SCOPED_TRACE("mu_s " + std::to_string(mu_s) + " k " + std::to_string(k) + " levels " +
                     std::to_string(levels[0]) + "," + std::to_string(levels[1]));
        event_counts kinds;
        EXPECT_GT(expect_traces_agree(s, 0, 60, kinds), 100u);
        if (HasFailure()) return;
      }
}

// Over max_events the lanes report the family engine's error.
TEST(FastPathFamily, WorkBoundGivesTheReferenceError) {
  sweep_spec s;
  s.base.static_friction = 6.0;
  s.base.kinetic_friction = 2.0;
  s.base.belt_rates = {30.0, 20.0};
  s.base.window = 20.0;
  s.max_events = 40;
  std::string ref, lanes;
  try {
    const family_point fp(point_parameters(s, 0));
    recorder r;
    const auto start = draw_model_initial_state(fp, s.initial, s.seed, 0);
    (void)simulate_family_realization(fp, start, s.seed, 0, s.max_events, r);
  } catch (const error& e) {
    ref = e.what();
  }
  try {
    (void)detail::trace_realizations_lanes(s, 0, 0, 5);
  } catch (const error& e) {
    lanes = e.what();
  }
  EXPECT_FALSE(ref.empty());
  EXPECT_EQ(ref, lanes);
}

}  // namespace
}  // namespace stickslip
