// The lanes' tallies of the closed episodes (realization_observer::
// set_closed_episode_tallies: a means-only sweep without the causal score,
// e.g. `sweep --statistics R`): the vector step sums the sticks, the slips
// after the first stick, the stick time and the first stick instead of
// handing each episode to the observer. Oracle: the same tallies counted by
// hand from a replay's episodes (the reference engine's episode stream),
// realization by realization, to the bit; and, with a burn-in (where the
// lanes hand over every episode again), the reference engine's records.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "stickslip/engines/integration_counts.hpp"
#include "stickslip/replay.hpp"
#include "stickslip/sweep.hpp"
#include "unit/figure_spec.hpp"

namespace stickslip {
namespace {

using testing_support::figure_spec;

static_assert(takes_episode_tallies<mean_statistics_observer>);
static_assert(!takes_episode_tallies<mean_and_causal_score_observer>);
static_assert(!takes_episode_tallies<paper_statistics_observer>);

struct tallies {
  std::uint32_t sticks = 0, slips = 0;
  double stick_time = 0, first_start = -1, first_duration = -1;
  bool first_censored = false;
};

// collect_in_window's definitions over a whole window: sticks of positive
// length, slips after the first stick, the stick time summed in order.
tallies by_hand(const realization_trace& tr) {
  tallies t;
  for (const auto& e : tr.episodes) {
    const double d = e.end - e.start;
    if (e.kind == mode::stick) {
      if (!(d > 0.0)) continue;
      if (t.first_start < 0.0) t.first_start = e.start, t.first_duration = d,
                               t.first_censored = e.censored;
      ++t.sticks;
      t.stick_time += d;
    } else if (t.sticks > 0) {
      ++t.slips;
    }
  }
  return t;
}

std::vector<sweep_spec> models() {
  std::vector<sweep_spec> out;
  for (double k : {4.0, 40.0}) {  // the paper's model at the printed k and at k = 40
    sweep_spec s = figure_spec(5.0, {0.7, 3.8, 20.0}, 150, false, 23);
    s.base.stiffness = k;
    out.push_back(s);
  }
  sweep_spec mus = figure_spec(3.0, {0.7, 3.8}, 150, false, 29);
  mus.base.static_friction = 5.0;  // mu_s > mu_k: the family lanes
  out.push_back(mus);
  sweep_spec resting = figure_spec(2.0, {0.7, 3.8}, 150, false, 31);
  resting.base.belt_levels = {1.0, 0.0};  // a stick at rest lasts to the switch
  out.push_back(resting);
  for (double mu : {0.5, 5.0}) {  // a short window: first sticks cut by t_a, and no stick at all
    sweep_spec s = figure_spec(mu, {0.1, 1.0}, 300, false, 37);
    s.base.window = 0.5;
    out.push_back(s);
  }
  return out;
}

sweep_spec means_of_R(sweep_spec s, sweep_engine engine) {
  s.statistics = parse_statistics_selection("statistics", "R");
  apply_statistics_selection(s);
  s.engine = engine;
  s.keep_records = true;
  s.block_size = 50;
  return s;
}

TEST(EpisodeTallies, TheLanesTalliesEqualACountFromTheEpisodes) {
  std::uint64_t sticks = 0, slips = 0, late_first = 0, censored_first = 0, no_stick = 0;
  for (const auto& model : models()) {
    const sweep_spec s = means_of_R(model, sweep_engine::fast);
    ASSERT_TRUE(s.means_only);
    ASSERT_FALSE(keeps_causal_score(s));  // the tallying observer
    // The lanes ran every realization: no scalar integrator did (no rerun
    // after max_events, no engine choice that sends the model elsewhere).
    const std::uint64_t paper_before = detail::integrations(integrator::paper),
                        model_before = detail::integrations(integrator::model);
    const auto rs = run_sweep(s, 2);
    ASSERT_EQ(detail::integrations(integrator::paper), paper_before);
    ASSERT_EQ(detail::integrations(integrator::model), model_before);
    for (std::size_t p = 0; p < rs.points.size(); ++p) {
      const model_parameters params = point_parameters(s, p);
      for (std::uint64_t r = 0; r < s.realizations; ++r) {
        replay_request q;
        q.parameters = params;
        q.seed = s.seed;
        q.realization = r;
        const tallies want = by_hand(replay(q));
        const realization_record& got = rs.records[p][r];
        ASSERT_EQ(got.sticks, want.sticks) << "point " << p << " realization " << r;
        ASSERT_EQ(got.slips, want.slips) << "point " << p << " realization " << r;
        ASSERT_EQ(got.stick_fraction, want.stick_time / params.window) << "point " << p << " r " << r;
        ASSERT_EQ(got.first_stick_start, want.first_start) << "point " << p << " r " << r;
        ASSERT_EQ(got.first_stick_duration, want.first_duration) << "point " << p << " r " << r;
        ASSERT_EQ(got.first_stick_censored, want.first_censored) << "point " << p << " r " << r;
        sticks += want.sticks;
        slips += want.slips;
        late_first += want.first_start > 0.0;
        censored_first += want.first_censored;
        no_stick += want.sticks == 0;
      }
    }
  }
  std::printf("tallied: %llu sticks, %llu slips; first stick after t = 0 in %llu, censored in "
              "%llu; no stick in %llu realizations\n",
              static_cast<unsigned long long>(sticks), static_cast<unsigned long long>(slips),
              static_cast<unsigned long long>(late_first),
              static_cast<unsigned long long>(censored_first),
              static_cast<unsigned long long>(no_stick));
  // Every branch of the tally is taken, many times.
  EXPECT_GT(sticks, 10000u);
  EXPECT_GT(slips, 10000u);
  EXPECT_GT(late_first, 100u);
  EXPECT_GT(censored_first, 10u);
  EXPECT_GT(no_stick, 0u);
}

// With a burn-in the lanes hand over every episode (it cuts them at T):
// the records are still the reference engine's.
TEST(EpisodeTallies, WithABurnInTheLanesHandOverEveryEpisode) {
  for (auto model : models()) {
    model.burn_in = 0.2 * model.base.window;  // a fifth of each model's window
    const auto fast = run_sweep(means_of_R(model, sweep_engine::fast), 2);
    const auto ref = run_sweep(means_of_R(model, sweep_engine::reference), 2);
    for (std::size_t p = 0; p < fast.points.size(); ++p)
      for (std::size_t r = 0; r < fast.records[p].size(); ++r) {
        const auto &a = fast.records[p][r], &b = ref.records[p][r];
        ASSERT_EQ(a.sticks, b.sticks) << "point " << p << " realization " << r;
        ASSERT_EQ(a.slips, b.slips) << "point " << p << " realization " << r;
        ASSERT_EQ(a.stick_fraction, b.stick_fraction) << "point " << p << " realization " << r;
        ASSERT_EQ(a.first_stick_start, b.first_stick_start) << "point " << p << " r " << r;
        ASSERT_EQ(a.first_stick_duration, b.first_stick_duration) << "point " << p << " r " << r;
      }
  }
}

}  // namespace
}  // namespace stickslip
