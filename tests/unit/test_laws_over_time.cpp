// A burn-in and observe times with uncertain parameters (laws): each
// realization is clipped at T and observed at its own drawn parameters.
//   - the records of a sweep with a burn-in equal, field by field, what the
//     same realization's episode list gives by hand over [T, t_a], with the
//     drawn window when t_a has a law (each realization its own t_a - T);
//   - the stick count at each observe time equals, exactly, the number of
//     realizations whose episode list holds a stick at t; x and x' at t, from
//     the test's own closed form of the slip at the drawn k, m and mu_k,
//     give the sweep's means to 1e-12;
//   - a law on t_a bounds the burn-in and the observe times by the low end
//     of its support (a gamma law: no burn-in); a sensitivity study takes
//     neither a burn-in nor observe times;
//   - threads change no bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/uncertainty/parameter_law.hpp"
#include "stickslip/uncertainty/uncertain_realization.hpp"
#include "unit/engine_agreement.hpp"
#include "unit/same_bits.hpp"

namespace stickslip {
namespace {

using testing_support::same_bits;

uncertain_parameter law(const char* symbol, const char* text) {
  return {symbol, parse_law(text, symbol)};
}

// The episodes and events of a realization, and where it started.
struct run_log : observer_base {
  std::vector<episode> episodes;
  std::vector<event> events;
  double x0 = 0, xd0 = 0;
  int belt = 0;
  void reset(std::uint64_t, double x, double xd, int b) { x0 = x, xd0 = xd, belt = b; }
  void on_episode(const episode& e) { episodes.push_back(e); }
  void on_event(const event& e) { events.push_back(e); }
};

struct drawn_run {
  model_parameters p;
  run_log log;
};

drawn_run run_drawn(const sweep_spec& s, std::size_t point, std::uint64_t r) {
  drawn_run out;
  out.p = draw_realization(s, point, r).parameters;
  (void)simulate_with_values(s, out.p, uncertain_stream_key(s, point), r, out.log);
  return out;
}

// The paper's model at k = 40 with laws on mu and t_a: every draw is a
// paper-model realization with its own window.
sweep_spec laws_spec() {
  sweep_spec s;
  s.base.stiffness = 40;
  s.axes = {{"lambda", {0.5, 3.8}}};
  s.uncertain = {law("mu", "uniform(min=4,max=6)"), law("ta", "uniform(min=30,max=60)")};
  s.realizations = 120;
  s.block_size = 16;
  s.seed = 7;
  s.keep_records = true;
  return s;
}

TEST(LawsOverTime, BurnInRecordsEqualTheEpisodesClippedByHand) {
  sweep_spec s = laws_spec();
  s.burn_in = 20.0;
  const result_set rs = run_sweep(s, 2);
  std::size_t straddling = 0;
  double shortest = 1e300, longest = 0.0;
  for (std::size_t point = 0; point < 2; ++point)
    for (std::uint64_t r = 0; r < s.realizations; ++r) {
      SCOPED_TRACE(testing::Message() << "point " << point << " realization " << r);
      const drawn_run run = run_drawn(s, point, r);
      double stick_time = 0.0;
      std::uint32_t sticks = 0, slips = 0;
      for (const auto& e : run.log.episodes) {
        if (e.end <= s.burn_in) continue;
        const double d = e.end - std::max(e.start, s.burn_in);
        if (e.kind == mode::stick) {
          if (!(d > 0.0)) continue;
          straddling += e.start < s.burn_in;
          ++sticks;
          stick_time += d;
        } else if (sticks > 0) {
          ++slips;
        }
      }
      const realization_record& rec = rs.records.at(point).at(r);
      const double window = run.p.window - s.burn_in;
      shortest = std::min(shortest, run.p.window), longest = std::max(longest, run.p.window);
      EXPECT_EQ(rec.sticks, sticks);
      EXPECT_EQ(rec.slips, slips);
      EXPECT_TRUE(same_bits(rec.stick_fraction, stick_time / window))
          << rec.stick_fraction << " vs " << stick_time / window;
    }
  EXPECT_GE(straddling, 20u) << "sticks in progress at T";
  // Each draw its own t_a, over most of uniform(30, 60).
  EXPECT_GT(shortest, 30.0);
  EXPECT_LT(longest, 60.0);
  EXPECT_GT(longest - shortest, 20.0);
  // R's mean over the point is the mean of the records.
  for (std::size_t point = 0; point < 2; ++point) {
    mean_variance r;
    for (const auto& rec : rs.records[point]) r.add(rec.stick_fraction);
    EXPECT_NEAR(rs.points[point].stats.stick_fraction.mean(), r.mean(), 1e-14);
  }
}

// The state at t of an undamped paper-model realization (as
// test_observe_times.cpp computes it): the episode that holds t says stick
// or slip; a slip is the harmonic orbit about sigma mu_k m g / k from the
// last event at or before t.
struct state {
  bool stick;
  double x, xd;
};

state state_at(const drawn_run& run, double t) {
  const auto& p = run.p;
  const double ak = p.mu_k() * p.mass * p.gravity / p.stiffness, w = p.natural_frequency();
  const episode* e = &run.log.episodes.back();
  for (const auto& ep : run.log.episodes)
    if (ep.start <= t && t < ep.end) {
      e = &ep;
      break;
    }
  if (e->kind == mode::stick)
    return {true, e->position_at_start + e->belt_velocity * (t - e->start), e->belt_velocity};
  double t0 = 0.0, x = run.log.x0, z = run.log.xd0, v = run.log.belt * p.belt_speed;
  for (const auto& ev : run.log.events) {
    if (ev.time > t) break;
    t0 = ev.time, x = ev.position, z = ev.velocity, v = ev.belt_velocity;
  }
  const double sigma = z != v ? (v > z ? 1.0 : -1.0) : (x > 0.0 ? 1.0 : -1.0);
  const double c = sigma * ak, cs = std::cos(w * (t - t0)), sn = std::sin(w * (t - t0));
  return {false, c + (x - c) * cs + z / w * sn, z * cs - w * (x - c) * sn};
}

TEST(LawsOverTime, ObservedStatesEqualTheEpisodesAtTheDrawnParameters) {
  sweep_spec s = laws_spec();
  s.uncertain = {law("mu", "uniform(min=4,max=6)"), law("k", "gamma(mean=40,cv=0.2)")};
  s.base.window = 30;
  s.observe_times = {0.0, 0.7, 3.0, 12.5, 29.0, 30.0};
  s.keep_records = false;
  const result_set rs = run_sweep(s, 2);
  std::size_t stuck = 0, slipping = 0;
  for (std::size_t point = 0; point < 2; ++point) {
    std::vector<drawn_run> runs;
    for (std::uint64_t r = 0; r < s.realizations; ++r) runs.push_back(run_drawn(s, point, r));
    const time_statistics& o = rs.points[point].stats.observed;
    ASSERT_EQ(o.times(), s.observe_times);
    ASSERT_EQ(o.realizations(), s.realizations);
    for (std::size_t j = 0; j < s.observe_times.size(); ++j) {
      SCOPED_TRACE(testing::Message() << "point " << point << " t = " << s.observe_times[j]);
      std::uint64_t sticking = 0;
      mean_variance x, xd;
      for (const auto& run : runs) {
        const state st = state_at(run, s.observe_times[j]);
        sticking += st.stick;
        x.add(st.x);
        xd.add(st.xd);
      }
      stuck += sticking;
      slipping += s.realizations - sticking;
      EXPECT_EQ(o.at(j).sticking, sticking);
      EXPECT_NEAR(o.at(j).position.mean(), x.mean(), 1e-12 * (std::abs(x.mean()) + 1.0));
      EXPECT_NEAR(o.at(j).velocity.mean(), xd.mean(), 1e-12 * (std::abs(xd.mean()) + 1.0));
    }
  }
  EXPECT_GE(stuck, 100u);
  EXPECT_GE(slipping, 100u);
  // Threads change no bit.
  const result_set rs1 = run_sweep(s, 1);
  for (std::size_t point = 0; point < 2; ++point)
    for (std::size_t j = 0; j < s.observe_times.size(); ++j) {
      const auto& a = rs.points[point].stats.observed.at(j);
      const auto& b = rs1.points[point].stats.observed.at(j);
      EXPECT_EQ(a.sticking, b.sticking);
      EXPECT_TRUE(same_bits(a.position.mean(), b.position.mean()));
      EXPECT_TRUE(same_bits(a.velocity.variance(), b.velocity.variance()));
      EXPECT_EQ(a.position_quantiles, b.position_quantiles);
    }
}

// validate(s) refuses s with a message holding `phrase`.
void expect_refused(const sweep_spec& s, const std::string& phrase, const char* what) {
  try {
    validate(s);
    ADD_FAILURE() << what << " was accepted";
  } catch (const error& e) {
    EXPECT_NE(std::string(e.what()).find(phrase), std::string::npos) << e.what();
  }
}

TEST(LawsOverTime, ALawOnTheWindowBoundsTheBurnInAndTheTimes) {
  sweep_spec s = laws_spec();
  s.burn_in = 30.0;  // the low end of uniform(30, 60)
  EXPECT_THROW(validate(s), error);
  s.burn_in = 29.5;
  EXPECT_NO_THROW(validate(s));
  s.observe_times = {0.0, 30.0};
  EXPECT_NO_THROW(validate(s));
  s.observe_times = {0.0, 30.5};
  EXPECT_THROW(validate(s), error);
  s.burn_in = 0.0;
  s.observe_times = {1.0};
  s.uncertain[1] = law("ta", "gamma(mean=40,cv=0.1)");  // support from 0
  expect_refused(s, "the low end of the support of t_a's law",
                 "an observe time beyond a gamma law's low end");
  s.observe_times = {0.0};
  EXPECT_NO_THROW(validate(s));
  // A law on t_a whose support starts at 0 takes no burn-in, by name.
  s.observe_times.clear();
  s.burn_in = 1.0;
  expect_refused(s, "a draw can be shorter than any burn-in", "a burn-in with a gamma law on t_a");
}

// A sensitivity study's statistics are over [0, t_a]: no burn-in, no
// observe times.
TEST(LawsOverTime, ASensitivityStudyTakesNoBurnInNorObserveTimes) {
  sweep_spec s;
  s.base.stiffness = 40;
  s.uncertain = {law("mu", "uniform(min=4,max=6)"), law("lambda", "uniform(min=1,max=5)")};
  s.sensitivity_statistic = "R";
  s.realizations = 64;
  EXPECT_NO_THROW(validate(s));
  s.burn_in = 5.0;
  expect_refused(s, "0 in a sensitivity study", "a sensitivity study with a burn-in");
  s.burn_in = 0.0;
  s.observe_times = {1.0};
  EXPECT_THROW(validate(s), error);
}

}  // namespace
}  // namespace stickslip
