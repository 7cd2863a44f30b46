// The burn-in (sweep_spec::burn_in, burn_in.hpp): every statistic over
// [T, t_a] only.
//   - bookkeeping: a sweep's clipped statistics of single realizations equal
//     those computed by hand from the same realization's episode list, with
//     an episode straddling T and one starting exactly at T;
//   - the sums over pieces (level fractions, friction and damping power) are
//     additive: t_a W = T W[0, T] + (t_a - T) W[T, t_a], the [0, T] part from
//     the same realization run to t_a = T;
//   - oracle: R with a burn-in equals the long-time stick probability,
//     estimated independently from simulate()'s episodes at fixed times;
//   - lanes and scalar engines agree bit for bit with a burn-in, for any
//     thread count; T = 0 is the sweep without the field, to the byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "stickslip/model/model_engine.hpp"
#include "stickslip/model/model_realization.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/sweep.hpp"
#include "unit/engine_agreement.hpp"
#include "unit/same_bits.hpp"

namespace stickslip {
namespace {

using testing_support::expect_engines_agree;
using testing_support::recorder;
using testing_support::same_bits;

sweep_spec paper_point(double lambda, double window, double burn_in) {
  sweep_spec s;
  s.base.stiffness = 40.0;
  s.base.friction_coefficient = 5.0;
  s.base.switch_rate = lambda;
  s.base.window = window;
  s.burn_in = burn_in;
  s.seed = 3;
  return s;
}

// The episodes of realization r of the sweep's single point, as the sweep
// draws it (simulate_realization: the reference engine's draws).
std::vector<episode> episodes_of(const sweep_spec& s, std::uint64_t r) {
  recorder rec;
  (void)simulate_realization(s, point_parameters(s, 0), r, rec);
  return rec.episodes;
}

// What the statistics of one realization are over [T, t_a], by hand from
// its episodes (docs/outputs.md, "Burn-in").
struct by_hand {
  double stick_time = 0.0;
  std::uint32_t sticks = 0, slips = 0;
  double first_start = -1.0, first_duration = -1.0;
  std::vector<double> stick_durations, slip_durations;
  bool left_truncated = false;
};

by_hand clip_by_hand(const std::vector<episode>& episodes, double T) {
  by_hand h;
  for (const auto& e : episodes) {
    if (e.end <= T) continue;
    const double from = std::max(e.start, T);
    const double d = e.end - from;
    if (e.kind == mode::stick) {
      if (!(d > 0.0)) continue;
      if (e.start < T) h.left_truncated = true;
      ++h.sticks;
      h.stick_time += d;
      h.stick_durations.push_back(d);
      if (e.start >= T && h.first_start < 0.0) h.first_start = e.start, h.first_duration = d;
    } else if (h.sticks > 0) {
      ++h.slips;
      h.slip_durations.push_back(d);
    }
  }
  return h;
}

// The sweep's block of realization r alone (block size 1) against the hand
// count; returns whether the realization had a stick cut at T.
bool expect_block_matches_hand(sweep_spec s, std::uint64_t r) {
  s.block_size = 1;
  s.keep_records = true;
  s.realizations = r + 1;
  const auto h = clip_by_hand(episodes_of(s, r), s.burn_in);
  const block_result b = simulate_block(s, work_unit{0, r});
  const realization_record& rec = b.records.at(0);
  const double window = s.base.window - s.burn_in;
  EXPECT_EQ(rec.sticks, h.sticks) << r;
  EXPECT_EQ(rec.slips, h.slips) << r;
  EXPECT_TRUE(same_bits(rec.stick_fraction, h.stick_time / window)) << r;
  EXPECT_TRUE(same_bits(rec.first_stick_start, h.first_start)) << r;
  EXPECT_TRUE(same_bits(rec.first_stick_duration, h.first_duration)) << r;
  const point_statistics& st = b.stats;
  mean_variance d, hs;
  d.add_batch(h.stick_durations.data(), h.stick_durations.data() + h.stick_durations.size());
  hs.add_batch(h.slip_durations.data(), h.slip_durations.data() + h.slip_durations.size());
  EXPECT_TRUE(same_bits(st.stick_duration, d)) << r;
  EXPECT_TRUE(same_bits(st.slip_duration, hs)) << r;
  EXPECT_TRUE(same_bits(st.sticks_per_time.mean(), h.sticks / window)) << r;
  EXPECT_TRUE(same_bits(st.slips_per_time.mean(), h.slips / window)) << r;
  EXPECT_EQ(st.first_stick_duration.count(), h.first_start >= 0.0 ? 1u : 0u) << r;
  EXPECT_EQ(st.no_stick, h.first_start >= 0.0 ? 0u : 1u) << r;
  // A left-truncated stick has no onset (X) and is not in the survival
  // counts (Kaplan-Meier over the sticks that start in the window).
  const std::size_t whole = h.stick_durations.size() - (h.left_truncated ? 1 : 0);
  EXPECT_EQ(st.stick_onset_position.count(), whole) << r;
  std::uint64_t in_survival = st.stick_survival.ended().overflow() +
                              st.stick_survival.censored().overflow();
  for (std::size_t i = 0; i < st.stick_survival.bins(); ++i)
    in_survival += st.stick_survival.ended().count(i) + st.stick_survival.censored().count(i);
  EXPECT_EQ(in_survival, whole) << r;
  return h.left_truncated;
}

TEST(BurnIn, ClippedStatisticsEqualTheEpisodeListByHand) {
  sweep_spec s = paper_point(3.8, 30.0, 0.0);
  s.statistics.survival = true;
  resolve_survival_grid(s);
  const auto episodes = episodes_of(s, 0);
  // T inside a stick (it straddles T), exactly at the start of a stick,
  // inside a slip, and exactly at the start of a slip.
  std::vector<double> cuts;
  for (const auto& e : episodes) {
    if (e.start < 5.0) continue;
    if (e.kind == mode::stick && e.end - e.start > 0.2) {
      cuts.push_back(0.5 * (e.start + e.end));
      cuts.push_back(e.start);
    } else if (e.kind == mode::slip) {
      cuts.push_back(0.5 * (e.start + e.end));
      cuts.push_back(e.start);
    }
    if (cuts.size() >= 8) break;
  }
  ASSERT_GE(cuts.size(), 8u);
  int truncated = 0, exact = 0;
  for (double T : cuts) {
    s.burn_in = T;
    SCOPED_TRACE("T = " + std::to_string(T));
    truncated += expect_block_matches_hand(s, 0);
    exact += std::any_of(episodes.begin(), episodes.end(), [&](const episode& e) {
      return e.kind == mode::stick && e.start == T;
    });
    for (std::uint64_t r = 1; r < 6; ++r) expect_block_matches_hand(s, r);
  }
  EXPECT_GE(truncated, 2);  // the stick in progress at T was cut
  EXPECT_GE(exact, 2);      // and a stick started exactly at T
}

// The sums over pieces of one realization are additive over [0, T] and
// [T, t_a]: the [0, T] part is the same realization run to t_a = T (the
// engines' own state at T; the burn-in's comes from evaluate(segment)).
template <class Run>
void expect_additive(const model_parameters& p, double T, Run run) {
  model_parameters head = p;
  head.window = T;
  realization_observer whole(p), before(head), after(p, true, T);
  run(p, whole);
  run(head, before);
  run(p, after);
  whole.finish(), before.finish(), after.finish();
  const auto& w = whole.record();
  const auto& b = before.record();
  const auto& a = after.record();
  const double ta = p.window, rest = ta - T, tol = 1e-10 * ta;
  EXPECT_NEAR(ta * w.friction_power, T * b.friction_power + rest * a.friction_power,
              tol * (1.0 + w.friction_power));
  EXPECT_NEAR(ta * w.damping_power, T * b.damping_power + rest * a.damping_power,
              tol * (1.0 + w.damping_power));
  EXPECT_NEAR(ta * w.stick_fraction, T * b.stick_fraction + rest * a.stick_fraction, tol);
  const auto& lw = whole.samples().level_fractions;
  const auto& lb = before.samples().level_fractions;
  const auto& la = after.samples().level_fractions;
  for (std::size_t j = 0; j < lw.size(); ++j)
    EXPECT_NEAR(ta * lw[j], T * lb[j] + rest * la[j], tol) << "level " << j;
  EXPECT_GT(w.friction_power, 0.0);
}

TEST(BurnIn, PieceSumsAreAdditiveOverTheBurnIn) {
  for (double c : {0.0, 0.7}) {  // undamped and damped
    model_parameters p;
    p.stiffness = 40.0;
    p.damping = c;
    p.static_friction = 6.0;
    p.kinetic_friction = 4.0;
    p.belt_levels = {1.0, -0.5, 0.0};
    p.belt_generator = {-2.0, 1.5, 0.5, 0.25, -0.75, 0.5, 1.0, 2.0, -3.0};
    p.window = 20.0;
    const family_point fp(p);
    for (std::uint64_t r = 0; r < 20; ++r)
      for (double T : {3.3, 11.0}) {
        SCOPED_TRACE("c = " + std::to_string(c) + ", r = " + std::to_string(r));
        expect_additive(p, T, [&](const model_parameters& q, realization_observer& o) {
          family_point f(q, fp.key);
          const auto start = draw_model_initial_state(f, initial_condition_law{}, 1, r);
          o.reset(r, start.position, start.velocity, 1);
          (void)simulate_family_realization(f, start, 1, r, 1'000'000, o);
        });
      }
  }
}

// Oracle: at long times the stick fraction over [T, t_a] estimates the
// stationary stick probability, which simulate()'s episodes give at fixed
// times t >= T (the fraction of realizations sticking at t), from other
// realizations (another seed). Standard errors: R's over realizations; the
// episodes' from the per-realization means of the indicators over the times.
TEST(BurnIn, StickFractionAfterBurnInIsTheStationaryStickProbability) {
  for (double lambda : {0.5, 3.8}) {
    sweep_spec s = paper_point(lambda, 80.0, 20.0);
    s.realizations = 4000;
    const auto rs = run_sweep(s, 2);
    const mean_variance& R = rs.points[0].stats.stick_fraction;
    sweep_spec other = s;
    other.seed = 77;
    mean_variance sticking;  // per realization: the fraction of the times it sticks at
    const std::vector<double> times{20.0, 30.0, 40.0, 50.0, 60.0, 70.0, 79.0};
    for (std::uint64_t r = 0; r < 4000; ++r) {
      const auto episodes = episodes_of(other, r);
      int n = 0;
      for (double t : times)
        for (const auto& e : episodes)
          if (e.start <= t && t < e.end) {
            n += e.kind == mode::stick;
            break;
          }
      sticking.add(static_cast<double>(n) / static_cast<double>(times.size()));
    }
    const double se = std::hypot(R.std_error(), sticking.std_error());
    const double z = (R.mean() - sticking.mean()) / se;
    std::printf("lambda %g: R over [20, 80] = %.5f, stick probability = %.5f, %.2f SE\n", lambda,
                R.mean(), sticking.mean(), z);
    EXPECT_LT(std::abs(z), 4.0) << "lambda " << lambda;
    // And the burn-in matters at lambda = 0.5 here: R over [0, t_a] from the
    // uniform start is off the stationary value by many standard errors.
    if (lambda == 0.5) {
      s.burn_in = 0.0;
      s.base.window = 20.0;
      const auto head = run_sweep(s, 2);
      const mean_variance& R0 = head.points[0].stats.stick_fraction;
      EXPECT_GT(std::abs(R0.mean() - sticking.mean()) / se, 4.0);
    }
  }
}

// Lanes and scalar engines, bit for bit with a burn-in: the paper model
// (k = 4 and 40), undamped two-level family members in the lanes (mu_s >
// mu_k, rates), and the scalar-only ones (damped, three levels).
TEST(BurnIn, LanesEqualTheReferenceWithABurnIn) {
  sweep_spec s;
  s.realizations = 90;
  s.block_size = 16;
  s.seed = 4;
  s.keep_records = true;
  s.base.window = 20.0;
  s.burn_in = 7.5;
  s.statistics.survival = true;
  s.axes = {{"lambda", {0.3, 3.8, 30.0}}, {"mu", {0.5, 5.0}}, {"k", {4.0, 40.0}}};
  resolve_survival_grid(s);
  expect_engines_agree(s, 2);
  s.base.stiffness = 40.0;
  s.base.static_friction = 8.0;
  s.axes = {{"mu_k", {0.5, 4.0, 8.0}}, {"lambda", {0.3, 5.0}}};
  s.survival = {};
  resolve_survival_grid(s);
  expect_engines_agree(s, 2);
  s.base.belt_levels = {2.0, -0.5};
  s.axes = {{"mu_k", {0.5, 4.0}}, {"r1", {0.3, 5.0}}, {"r2", {1.0, 20.0}}, {"c", {0.0, 0.4}}};
  s.survival = {};
  resolve_survival_grid(s);
  expect_engines_agree(s, 3);
  s.base.belt_levels = {1.0, -0.5, 0.0};
  s.axes = {{"c", {0.0, 0.5}}};
  s.base.belt_generator = {-2.0, 1.5, 0.5, 0.25, -0.75, 0.5, 1.0, 2.0, -3.0};
  s.survival = {};
  resolve_survival_grid(s);
  expect_engines_agree(s, 2);
}

// The survival counts too (same_bits(point_statistics) leaves them out),
// for 1 and 2 threads.
TEST(BurnIn, ThreadsDoNotChangeTheBits) {
  sweep_spec s = paper_point(3.8, 30.0, 12.0);
  s.axes = {{"lambda", {0.5, 3.8}}, {"mu", {0.5, 5.0}}};
  s.realizations = 300;
  s.statistics.survival = true;
  resolve_survival_grid(s);
  const auto one = run_sweep(s, 1), two = run_sweep(s, 2);
  for (std::size_t i = 0; i < one.points.size(); ++i) {
    EXPECT_TRUE(same_bits(one.points[i].stats, two.points[i].stats));
    EXPECT_TRUE(one.points[i].stats.stick_survival == two.points[i].stats.stick_survival);
  }
}

// T = 0 is no burn-in: the same spec bytes (journal identity) and the same
// statistics; a burn-in is part of the identity, named by first_difference
// and round-tripped by the serializer.
TEST(BurnIn, IsPartOfTheIdentityAndZeroIsNone) {
  sweep_spec a = paper_point(3.8, 30.0, 0.0), b = a;
  EXPECT_EQ(serialize(a), serialize(sweep_spec(a)));
  b.burn_in = 10.0;
  EXPECT_NE(serialize(a), serialize(b));
  EXPECT_FALSE(same_results(a, b));
  EXPECT_NE(fingerprint(a), fingerprint(b));
  EXPECT_EQ(first_difference(a, b), "burn-in: 0 s vs 10 s");
  EXPECT_EQ(deserialize_sweep_spec(serialize(b)).burn_in, 10.0);
  EXPECT_EQ(deserialize_sweep_spec(serialize(a)).burn_in, 0.0);
  // A spec without the field is the bytes it was before: the observe times
  // (format 10; none: their count 0) last.
  const auto bytes = serialize(a);
  sweep_spec c = a;
  c.observe_times = {1.0};  // the last field: its count ends the bytes
  const auto changed = serialize(c);
  EXPECT_EQ(bytes.size() + 8, changed.size());
  EXPECT_EQ(bytes.substr(bytes.size() - 8), std::string(8, '\0'));
  EXPECT_NE(bytes.substr(bytes.size() - 8), changed.substr(changed.size() - 16, 8));
  a.realizations = b.realizations = 120;
  a.axes = b.axes = {{"lambda", {0.5, 3.8}}};
  b.burn_in = 0.0;
  const auto x = run_sweep(a, 2), y = run_sweep(b, 2);
  for (std::size_t i = 0; i < x.points.size(); ++i)
    EXPECT_TRUE(same_bits(x.points[i].stats, y.points[i].stats));
}

TEST(BurnIn, OutOfRangeIsRefusedByName) {
  for (double T : {-1.0, 30.0, 31.0, std::nan(""), HUGE_VAL}) {
    sweep_spec s = paper_point(3.8, 30.0, T);
    try {
      validate(s);
      ADD_FAILURE() << "accepted burn-in " << T;
    } catch (const error& e) {
      EXPECT_EQ(e.code(), exit_code::invalid_input);
      EXPECT_NE(std::string(e.what()).find("burn_in"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("t_a = 30"), std::string::npos) << e.what();
    }
  }
  // The shortest window of a t_a axis bounds it.
  sweep_spec s = paper_point(3.8, 30.0, 15.0);
  s.axes = {{"ta", {40.0, 15.0}}};
  EXPECT_THROW(validate(s), error);
  s.axes = {{"ta", {40.0, 16.0}}};
  EXPECT_NO_THROW(validate(s));
}

}  // namespace
}  // namespace stickslip
