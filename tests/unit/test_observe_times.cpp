// Observe times (sweep --observe-times): the ensemble's state at observe times,
// point_statistics::observed, against an independent computation from the
// same realizations' episodes and events.
//   - the stick count at t equals, exactly, the number of realizations whose
//     simulate() episode list has a stick episode [start, end) holding t (the
//     last episode at t = t_a), at t = 0, in the transient, late and at t_a,
//     for the paper model at k = 40, mu = 5, lambda = 0.5, 3.8, 10, a
//     mu_s > mu_k point and a start at the belt velocity (sticks at t = 0);
//     and from another seed within 4 standard errors;
//   - x, x' and the energy at t, from the test's own closed form of the slip
//     (from the last event before t; never evaluate() or a segment): the
//     sweep's moments to 1e-12, its quantile sketches equal to the sketches
//     of these states (every state in the same bin), its quantiles within
//     the sketch's accuracy of the exact order statistics;
//   - quantile_sketch alone against sorted samples, and merges in any order;
//   - the lanes and the reference engine give the same `observed`, bit for
//     bit, with times at event instants (and one ulp either side), t = 0 and
//     t_a; blocks of 10 and 50 give the same counts and sketches; at an
//     event instant the state is the one just after the event; a dense grid
//     equals the episodes on both engines;
//   - observe times change no other statistic or record, do not depend on
//     the burn-in, and are filled alike without the family statistics, with
//     means only, with records and with common random numbers;
//   - validation refuses times out of [0, t_a] (the shortest t_a of a t_a
//     axis), out of order or not finite, and t = t_a of the shorter window
//     of a t_a axis is that point's last state.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/model/model_realization.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/sweep.hpp"
#include "unit/engine_agreement.hpp"

namespace stickslip {
namespace {

using testing_support::recorder;

// ---- the independent state at t, from a realization's episodes and events ----

struct realization_run {
  std::vector<episode> episodes;
  std::vector<event> events;
  double x0 = 0, xd0 = 0, v0 = 0;
};

// Realization r of the spec's point `point`, as the sweep draws it: the
// paper's model with simulate() (simulate_realization), the family with
// simulate_model (model_realization.hpp).
realization_run run_realization(const sweep_spec& s, std::size_t point, std::uint64_t r) {
  const model_parameters p = point_parameters(s, point);
  realization_run out;
  recorder rec;
  if (p.is_paper_model()) {
    const auto ic = draw_initial_conditions(s.initial, s.seed, stream_key(s, p), r);
    out.x0 = ic.position;
    out.xd0 = ic.velocity;
    out.v0 = ic.belt_direction * p.belt_speed;
    (void)simulate_realization(s, p, r, rec);
  } else {
    const family_point fp(p, stream_key(s, p));
    const auto start = draw_model_initial_state(fp, s.initial, s.seed, r);
    out.x0 = start.position;
    out.xd0 = start.velocity;
    out.v0 = fp.model.belt.levels[start.level];
    (void)simulate_family_realization(fp, start, s.seed, r, s.max_events, rec);
  }
  out.episodes = std::move(rec.episodes);
  out.events = std::move(rec.events);
  return out;
}

struct state {
  bool stick;
  double x, xd, v;
};

// The state at t (0 <= t <= t_a) of an undamped model with kinetic offset
// a_k = mu_k m g / k: the episode [start, end) that holds t (the last one at
// t = t_a) says stick or slip; a stick moves with the belt from where it
// started; a slip is the harmonic orbit about sigma a_k from the state after
// the last event at or before t (or the start), sigma = sgn(v - x'), or at
// x' = v (a reversal or a break) the side the spring pushes to, sgn(x).
state state_at(const realization_run& run, double kinetic_offset, double omega, double t) {
  const episode* e = &run.episodes.back();
  for (const auto& ep : run.episodes)
    if (ep.start <= t && t < ep.end) {
      e = &ep;
      break;
    }
  if (e->kind == mode::stick)
    return {true, e->position_at_start + e->belt_velocity * (t - e->start), e->belt_velocity,
            e->belt_velocity};
  double t0 = 0.0, x = run.x0, z = run.xd0, v = run.v0;
  for (const auto& ev : run.events) {
    if (ev.time > t) break;
    t0 = ev.time, x = ev.position, z = ev.velocity, v = ev.belt_velocity;
  }
  const double sigma = z != v ? (v > z ? 1.0 : -1.0) : (x > 0.0 ? 1.0 : -1.0);
  const double c = sigma * kinetic_offset, cs = std::cos(omega * (t - t0)),
               sn = std::sin(omega * (t - t0));
  return {false, c + (x - c) * cs + z / omega * sn, z * cs - omega * (x - c) * sn, v};
}

// Every realization's state at every observe time of one point.
struct independent {
  std::vector<std::vector<state>> at;  // [time][realization]
  std::vector<realization_run> runs;
};

independent states_of(const sweep_spec& s, std::size_t point, bool keep_runs = false) {
  const model_parameters p = point_parameters(s, point);
  const double ak = p.mu_k() * p.mass * p.gravity / p.stiffness, w = p.natural_frequency();
  independent out;
  out.at.resize(s.observe_times.size());
  for (std::uint64_t r = 0; r < s.realizations; ++r) {
    realization_run run = run_realization(s, point, r);
    for (std::size_t j = 0; j < s.observe_times.size(); ++j)
      out.at[j].push_back(state_at(run, ak, w, s.observe_times[j]));
    if (keep_runs) out.runs.push_back(std::move(run));
  }
  return out;
}

std::size_t level_of(const model_parameters& p, double v) {
  const auto levels = p.levels();
  return static_cast<std::size_t>(std::find(levels.begin(), levels.end(), v) - levels.begin());
}

// The sweep's state of realization r alone (a block of one: its means are
// the values), printed next to the independent one: the diagnosis of a
// mismatch.
void explain_mismatches(const sweep_spec& s, std::size_t point, const independent& ind,
                        std::size_t j) {
  sweep_spec one = s;
  one.block_size = 1;
  int shown = 0;
  for (std::uint64_t r = 0; r < s.realizations && shown < 3; ++r) {
    const auto b = simulate_block(one, work_unit{point, r});
    const time_point_statistics& a = b.stats.observed.at(j);
    const state& i = ind.at[j][r];
    if ((a.sticking == 1) == i.stick && std::abs(a.position.mean() - i.x) < 1e-9) continue;
    ++shown;
    std::printf("  point %zu realization %llu t = %.17g: sweep stick %llu x %.17g x' %.17g;"
                " episodes say stick %d x %.17g x' %.17g\n",
                point, static_cast<unsigned long long>(r), s.observe_times[j],
                static_cast<unsigned long long>(a.sticking), a.position.mean(), a.velocity.mean(),
                i.stick, i.x, i.xd);
    const auto run = run_realization(s, point, r);
    for (const auto& e : run.episodes)
      if (e.end >= s.observe_times[j] - 1.0 && e.start <= s.observe_times[j] + 1.0)
        std::printf("    %s\n", testing_support::describe(e).c_str());
  }
}

// Exact order statistic x_(k), k = max(1, ceil(q n)), of the samples.
double order_statistic(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const auto n = static_cast<double>(v.size());
  const auto k = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(q * n)));
  return v[k - 1];
}

// The sketch's answer for x_(k): the middle of x_(k)'s bin (zero near 0).
void expect_quantile_near(double estimate, double exact, const char* what) {
  if (std::abs(exact) < quantile_sketch::zero_threshold) {
    EXPECT_LE(std::abs(estimate), quantile_sketch::zero_threshold) << what << " exact " << exact;
    return;
  }
  EXPECT_LE(std::abs(estimate - exact),
            quantile_sketch::relative_accuracy * std::abs(exact) * (1.0 + 1e-12))
      << what << ": sketch " << estimate << ", exact " << exact;
  EXPECT_EQ(quantile_sketch::key(estimate), quantile_sketch::key(exact))
      << what << ": sketch " << estimate << ", exact " << exact;
  EXPECT_EQ(estimate > 0.0, exact > 0.0) << what;
}

// Everything `observed` holds at point `point`, against the states computed
// from the same realizations' episodes (the sweep of `s`, any threads).
// Returns the stick counts per time.
std::vector<std::uint64_t> expect_observed_matches_episodes(const sweep_spec& s,
                                                            const result_set& rs,
                                                            std::size_t point) {
  const model_parameters p = point_parameters(s, point);
  const time_statistics& o = rs.points.at(point).stats.observed;
  const std::size_t levels = p.levels().size();
  EXPECT_EQ(o.realizations(), s.realizations);
  EXPECT_EQ(o.times(), s.observe_times);
  EXPECT_EQ(o.levels(), levels);
  std::vector<std::uint64_t> sticking(s.observe_times.size(), 0);
  if (o.realizations() != s.realizations || o.times() != s.observe_times) return sticking;
  const independent ind = states_of(s, point);
  const double n = static_cast<double>(s.realizations);
  for (std::size_t j = 0; j < s.observe_times.size(); ++j) {
    SCOPED_TRACE(testing::Message() << "lambda " << p.switch_rate << " mu_s " << p.mu_s()
                                    << " mu_k " << p.mu_k() << " t_a " << p.window << " t = "
                                    << s.observe_times[j]);
    mean_variance x, xd, u, energy;
    quantile_sketch xs, xds;
    std::vector<std::uint64_t> at_level(levels, 0);
    std::vector<double> xv, xdv;
    for (const state& st : ind.at[j]) {
      sticking[j] += st.stick;
      x.add(st.x);
      xd.add(st.xd);
      u.add(st.xd - st.v);
      energy.add(0.5 * p.mass * st.xd * st.xd + 0.5 * p.stiffness * st.x * st.x);
      xs.add(st.x);
      xds.add(st.xd);
      xv.push_back(st.x);
      xdv.push_back(st.xd);
      ++at_level.at(level_of(p, st.v));
    }
    const time_point_statistics& a = o.at(j);
    EXPECT_EQ(a.sticking, sticking[j]);
    if (a.sticking != sticking[j]) explain_mismatches(s, point, ind, j);
    EXPECT_EQ(o.stick_probability(j), static_cast<double>(sticking[j]) / n);
    for (std::size_t l = 0; l < levels; ++l) EXPECT_EQ(o.level_count(j, l), at_level[l]) << l;
    // Moments: the same states summed in another order.
    auto near = [](const mean_variance& sweep, const mean_variance& mine, double scale,
                   const char* what) {
      EXPECT_EQ(sweep.count(), mine.count()) << what;
      EXPECT_NEAR(sweep.mean(), mine.mean(), 1e-12 * scale) << what;
      EXPECT_NEAR(sweep.variance(), mine.variance(), 1e-10 * scale * scale) << what;
    };
    const double xscale = std::sqrt(x.variance() + x.mean() * x.mean()) + 1e-3;
    const double vscale = std::sqrt(xd.variance() + xd.mean() * xd.mean()) + 1e-3;
    near(a.position, x, xscale, "x");
    near(a.velocity, xd, vscale, "x'");
    near(a.relative_velocity, u, vscale + p.belt_speed, "x' - v");
    EXPECT_NEAR(a.energy.mean(), energy.mean(), 1e-12 * energy.mean()) << "energy";
    EXPECT_NEAR(a.energy.variance(), energy.variance(), 1e-10 * energy.variance()) << "energy";
    // Sketches: every state in the bin the sweep put it in; quantiles.
    EXPECT_EQ(a.position_quantiles, xs) << "x sketch";
    EXPECT_EQ(a.velocity_quantiles, xds) << "x' sketch";
    for (double q : observed_quantile_levels) {
      SCOPED_TRACE(testing::Message() << "q = " << q);
      expect_quantile_near(a.position_quantiles.quantile(q), order_statistic(xv, q), "x");
      expect_quantile_near(a.velocity_quantiles.quantile(q), order_statistic(xdv, q), "x'");
    }
  }
  return sticking;
}

// From another seed: the stick probability within 4 standard errors; returns
// the largest |z|.
double expect_other_seed_agrees(sweep_spec s, const time_statistics& sweep, std::size_t point) {
  s.seed += 1000;
  const independent ind = states_of(s, point);
  const double n = static_cast<double>(s.realizations);
  double max_z = 0.0;
  for (std::size_t j = 0; j < s.observe_times.size(); ++j) {
    double k = 0;
    for (const state& st : ind.at[j]) k += st.stick;
    const double p1 = sweep.stick_probability(j), p2 = k / n;
    const double se = std::hypot(sweep.stick_probability_std_error(j), std::sqrt(p2 * (1 - p2) / n));
    const double z = se > 0.0 ? (p1 - p2) / se : (p1 == p2 ? 0.0 : HUGE_VAL);
    max_z = std::max(max_z, std::abs(z));
    EXPECT_LT(std::abs(z), 4.0) << "point " << point << " t = " << s.observe_times[j] << ": sweep "
                                << p1 << ", episodes of seed " << s.seed << " " << p2;
  }
  return max_z;
}

sweep_spec paper_spec() {
  sweep_spec s;
  s.base.stiffness = 40.0;
  s.base.friction_coefficient = 5.0;
  s.base.window = 50.0;
  s.seed = 27;
  s.realizations = 4000;
  // 0, the transient from the uniform start, late times, and t_a.
  s.observe_times = {0.0, 0.3, 2.0, 7.5, 25.0, 50.0};
  return s;
}

TEST(ObserveTimes, StickCountsEqualSimulatesEpisodesOnThePapersPoints) {
  sweep_spec s = paper_spec();
  s.axes = {{"lambda", {0.5, 3.8, 10.0}}};
  const auto rs = run_sweep(s, 2);
  for (std::size_t i = 0; i < point_count(s); ++i) {
    const auto sticking = expect_observed_matches_episodes(s, rs, i);
    const double z = expect_other_seed_agrees(s, rs.points[i].stats.observed, i);
    std::printf("lambda %g: sticking at t = 0, 0.3, 2, 7.5, 25, 50: %llu %llu %llu %llu %llu %llu"
                " of %llu; other seed max |z| %.2f\n",
                rs.points[i].parameters.switch_rate, static_cast<unsigned long long>(sticking[0]),
                static_cast<unsigned long long>(sticking[1]),
                static_cast<unsigned long long>(sticking[2]),
                static_cast<unsigned long long>(sticking[3]),
                static_cast<unsigned long long>(sticking[4]),
                static_cast<unsigned long long>(sticking[5]),
                static_cast<unsigned long long>(s.realizations), z);
    // Not trivial: sticks and slips in the transient and late.
    for (std::size_t j = 2; j < sticking.size(); ++j) {
      EXPECT_GT(sticking[j], s.realizations / 20) << i << " " << j;
      EXPECT_LT(sticking[j], s.realizations - s.realizations / 20) << i << " " << j;
    }
  }
}

TEST(ObserveTimes, StickCountsEqualTheEpisodesWithStaticAboveKineticFriction) {
  sweep_spec s = paper_spec();
  s.base.switch_rate = 3.8;
  s.base.static_friction = 8.0;
  s.base.kinetic_friction = 5.0;
  s.realizations = 3000;
  ASSERT_FALSE(point_parameters(s, 0).is_paper_model());
  const auto rs = run_sweep(s, 2);
  const auto sticking = expect_observed_matches_episodes(s, rs, 0);
  const double z = expect_other_seed_agrees(s, rs.points[0].stats.observed, 0);
  std::printf("mu_s 8, mu_k 5: sticking at t_a %llu of %llu; other seed max |z| %.2f\n",
              static_cast<unsigned long long>(sticking.back()),
              static_cast<unsigned long long>(s.realizations), z);
  EXPECT_GT(sticking[3], s.realizations / 20);
}

// A start at the belt velocity, x0 uniform on [-2, 2] with a = 1.226: the
// realizations inside the band stick at t = 0 (the first episode is a stick
// that starts at 0), the others start with a reversal-like slip (x' = v
// outside the band). The bookkeeping of t = 0 is exercised on both.
TEST(ObserveTimes, StickAtTimeZeroFromAStartAtTheBeltVelocity) {
  sweep_spec s = paper_spec();
  s.base.switch_rate = 3.8;
  s.base.window = 20.0;
  s.initial.position_min = -2.0;
  s.initial.position_max = 2.0;
  s.initial.velocity_min = s.initial.velocity_max = 1.0;
  s.initial.belt_start = 1;
  s.realizations = 1000;
  s.observe_times = {0.0, 0.05, 1.0, 20.0};
  const auto rs = run_sweep(s, 2);
  const auto sticking = expect_observed_matches_episodes(s, rs, 0);
  (void)expect_other_seed_agrees(s, rs.points[0].stats.observed, 0);
  const double a = s.base.band_half_width();
  EXPECT_NEAR(static_cast<double>(sticking[0]) / 1000.0, a / 2.0, 4.0 * std::sqrt(0.25 / 1000.0));
  EXPECT_GT(sticking[0], 500u);
  EXPECT_LT(sticking[0], 1000u);
}

// ---- energy: the mean of m x'^2/2 + k x^2/2 (checked above per point too) ----

TEST(ObserveTimes, MeanEnergyIsTheMeanOfTheStatesEnergy) {
  sweep_spec s = paper_spec();
  s.base.switch_rate = 3.8;
  s.base.mass = 1.7;  // m != 1, so that m x'^2 / 2 is not x'^2 / 2
  s.realizations = 600;
  const auto rs = run_sweep(s, 2);
  const independent ind = states_of(s, 0);
  for (std::size_t j = 0; j < s.observe_times.size(); ++j) {
    double sum = 0.0;
    for (const state& st : ind.at[j])
      sum += 0.5 * s.base.mass * st.xd * st.xd + 0.5 * s.base.stiffness * st.x * st.x;
    const double mine = sum / static_cast<double>(s.realizations);
    const double sweep = rs.points[0].stats.observed.at(j).energy.mean();
    EXPECT_NEAR(sweep, mine, 1e-12 * mine) << "t = " << s.observe_times[j];
  }
}

// ---- quantile_sketch alone ----

void expect_sketch_quantiles(const std::vector<double>& samples, const char* what) {
  quantile_sketch sk;
  for (double x : samples) sk.add(x);
  EXPECT_EQ(sk.count(), samples.size()) << what;
  for (double q : {0.0, 0.001, 0.05, 0.25, 0.5, 0.75, 0.95, 0.999, 1.0}) {
    SCOPED_TRACE(testing::Message() << what << " q = " << q << " n = " << samples.size());
    expect_quantile_near(sk.quantile(q), order_statistic(samples, q), what);
  }
  // Canonical stores: trimmed, the first and last counts > 0.
  for (const auto& st : {sk.negative(), sk.positive()})
    if (!st.counts.empty()) {
      EXPECT_GT(st.counts.front(), 0u) << what;
      EXPECT_GT(st.counts.back(), 0u) << what;
    }
}

TEST(QuantileSketch, QuantilesAreTheOrderStatisticsWithinHalfABin) {
  std::mt19937_64 rng(27);
  const std::size_t n = 10001;  // q n is not an integer for the q tested
  std::vector<double> normal, uniform, zeros, negative, point_mass, wide;
  std::normal_distribution<> g(0.3, 2.0);
  std::uniform_real_distribution<> u(-3.0, 5.0), unit(0.0, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    normal.push_back(g(rng));
    uniform.push_back(u(rng));
    const double pick = unit(rng);
    // 30 % exact zeros, 10 % below the zero threshold (counted as 0).
    zeros.push_back(pick < 0.3 ? 0.0 : pick < 0.4 ? (pick - 0.35) * 1e-11 : g(rng));
    negative.push_back(-std::exp(g(rng)));
    // A stuck mass moves at the belt velocity: point masses at +-V.
    point_mass.push_back(pick < 0.4 ? 1.0 : pick < 0.75 ? -1.0 : u(rng) / 3.0);
    wide.push_back((unit(rng) < 0.5 ? -1.0 : 1.0) * std::exp(u(rng) * 20.0));
  }
  expect_sketch_quantiles(normal, "normal");
  expect_sketch_quantiles(uniform, "uniform");
  expect_sketch_quantiles(zeros, "with zeros");
  expect_sketch_quantiles(negative, "negative");
  expect_sketch_quantiles(point_mass, "point masses at +-1");
  expect_sketch_quantiles(wide, "60 decades");
  // Small samples, where ceil(q n) decides: n = 1, 2, 3, 4.
  expect_sketch_quantiles({2.5}, "one");
  expect_sketch_quantiles({-1.0, 3.0}, "two");
  expect_sketch_quantiles({3.0, -7.0, 0.5}, "three");
  expect_sketch_quantiles({4.0, 1.0, 3.0, 2.0}, "four");
  // Exactly 1: the sketch reports its bin's middle, 1 + 2^-(mantissa_bits + 1).
  quantile_sketch one;
  one.add(1.0);
  EXPECT_EQ(one.quantile(0.5), 1.0 + quantile_sketch::relative_accuracy);
  EXPECT_TRUE(std::isnan(quantile_sketch{}.quantile(0.5)));
  // The zero threshold: 2^-40 is a value, just below it is 0.
  quantile_sketch tiny;
  tiny.add(0x1p-40);
  tiny.add(std::nextafter(0x1p-40, 0.0));
  tiny.add(-std::nextafter(0x1p-40, 0.0));
  EXPECT_EQ(tiny.zero(), 2u);
  EXPECT_EQ(tiny.count(), 3u);
  EXPECT_EQ(tiny.quantile(0.5), 0.0);
  EXPECT_GT(tiny.quantile(1.0), 0.0);
}

// quantiles() answers ascending levels in one walk over the bins and other
// orders rank by rank (ranked()): the same values, level by level.
TEST(QuantileSketch, OneWalkGivesTheRankByRankQuantiles) {
  std::mt19937_64 rng(2728);
  std::normal_distribution<> g(0.3, 2.0);
  std::uniform_real_distribution<> unit(0.0, 1.0);
  std::vector<double> levels;
  for (int i = 0; i <= 200; ++i) levels.push_back(i / 200.0);
  for (std::size_t n : {1u, 2u, 3u, 7u, 1000u, 10001u}) {
    quantile_sketch s;
    for (std::size_t i = 0; i < n; ++i) {
      const double pick = unit(rng);
      s.add(pick < 0.2 ? 0.0 : pick < 0.5 ? 1.0 : g(rng));
    }
    std::vector<double> walked(levels.size()), ranked(levels.size());
    s.quantiles(levels.data(), levels.size(), walked.data());
    const std::vector<double> reversed(levels.rbegin(), levels.rend());
    s.quantiles(reversed.data(), reversed.size(), ranked.data());
    for (std::size_t i = 0; i < levels.size(); ++i)
      EXPECT_EQ(walked[i], ranked[levels.size() - 1 - i]) << "n " << n << " q " << levels[i];
  }
}

TEST(QuantileSketch, MergeOrderDoesNotMatter) {
  std::mt19937_64 rng(2727);
  std::normal_distribution<> g(0.0, 1.0);
  std::uniform_real_distribution<> unit(0.0, 1.0);
  std::vector<double> all;
  for (int i = 0; i < 5000; ++i) {
    const double pick = unit(rng);
    all.push_back(pick < 0.2 ? 0.0 : pick < 0.4 ? (pick < 0.3 ? 1.0 : -1.0) : g(rng) * 10.0);
  }
  // Five unequal parts, each with its own range of bins.
  const std::size_t cuts[] = {0, 7, 900, 2000, 2001, 5000};
  std::vector<quantile_sketch> parts(5);
  quantile_sketch whole;
  for (std::size_t p = 0; p < 5; ++p)
    for (std::size_t i = cuts[p]; i < cuts[p + 1]; ++i) parts[p].add(all[i]);
  for (double x : all) whole.add(x);
  quantile_sketch forward, backward, shuffled;
  for (std::size_t p = 0; p < 5; ++p) forward += parts[p];
  for (std::size_t p = 5; p-- > 0;) backward += parts[p];
  const std::size_t order[] = {3, 0, 4, 2, 1};
  for (std::size_t p : order) shuffled += parts[p];
  EXPECT_EQ(forward, whole);
  EXPECT_EQ(backward, whole);
  EXPECT_EQ(shuffled, whole);
  // A tree of merges, and an empty sketch on either side.
  quantile_sketch left = parts[0], right = parts[3];
  left += parts[1];
  right += parts[4];
  right += parts[2];
  quantile_sketch tree = right;
  tree += quantile_sketch{};
  tree += left;
  quantile_sketch empty;
  empty += tree;
  EXPECT_EQ(tree, whole);
  EXPECT_EQ(empty, whole);
  EXPECT_EQ(whole.count(), all.size());
  // A part whose bins lie strictly inside another's, and one strictly outside.
  quantile_sketch inner, outer;
  inner.add(0.5);
  outer.add(-1e6);
  outer.add(1e-9);
  outer.add(1e6);
  quantile_sketch a = outer, b = inner;
  a += inner;
  b += outer;
  EXPECT_EQ(a, b);
}

// ---- engines, blocks and event instants ----

// Observe times at event instants of realization `r` of the spec's point:
// its stick onsets, breaks and belt switches (sorted, with 0 and t_a).
std::vector<double> times_at_events(const sweep_spec& s, std::uint64_t r, std::size_t count) {
  const auto run = run_realization(s, 0, r);
  std::vector<double> t{0.0, point_parameters(s, 0).window};
  int kinds[4] = {0, 0, 0, 0};
  for (const auto& e : run.events) {
    auto& seen = kinds[static_cast<int>(e.kind)];
    if (seen < static_cast<int>(count)) t.push_back(e.time), ++seen;
  }
  // And one ulp either side of each event: the comparisons at segment ends.
  const std::size_t events = t.size();
  for (std::size_t i = 2; i < events; ++i) {
    t.push_back(std::nextafter(t[i], 0.0));
    t.push_back(std::nextafter(t[i], HUGE_VAL));
  }
  for (double x : {0.77, 3.3, 11.1}) t.push_back(x);
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

// At every event instant of realization r among the observe times, its state
// is the one just after the event: a stick onset sticks there, a break or a
// switch out of a stick does not, and x is the event's x.
void expect_state_after_events(sweep_spec s, std::uint64_t r, sweep_engine engine) {
  s.engine = engine;
  s.block_size = 1;
  s.realizations = r + 1;
  const time_statistics o = simulate_block(s, work_unit{0, r}).stats.observed;
  ASSERT_EQ(o.realizations(), 1u);
  const auto run = run_realization(s, 0, r);
  int checked = 0;
  for (std::size_t j = 0; j < s.observe_times.size(); ++j) {
    const double t = s.observe_times[j];
    const event* last = nullptr;  // the last event at t
    for (const auto& e : run.events)
      if (e.time == t) last = &e;
    if (!last) continue;
    ++checked;
    SCOPED_TRACE(testing::Message() << to_string(engine) << " r " << r << " t = " << t << " after "
                                    << to_string(last->kind));
    const bool stick_starts = last->kind == event_kind::stick_onset;
    EXPECT_EQ(o.at(j).sticking, stick_starts ? 1u : 0u);
    EXPECT_NEAR(o.at(j).position.mean(), last->position, 1e-12);
    EXPECT_NEAR(o.at(j).velocity.mean(), last->velocity, 1e-12);
    EXPECT_EQ(o.level_count(j, level_of(point_parameters(s, 0), last->belt_velocity)), 1u);
  }
  EXPECT_GE(checked, 6);
}

void expect_engines_and_blocks_agree(sweep_spec s) {
  s.engine = sweep_engine::reference;
  const auto ref = run_sweep(s, 1);
  s.engine = sweep_engine::fast;
  const auto fast = run_sweep(s, 3);
  const time_statistics& a = ref.points.at(0).stats.observed;
  const time_statistics& b = fast.points.at(0).stats.observed;
  ASSERT_TRUE(a.selected());
  EXPECT_TRUE(a == b) << "reference and lanes differ";
  for (std::size_t j = 0; j < a.times().size(); ++j) {
    EXPECT_EQ(a.at(j).sticking, b.at(j).sticking) << j;
    EXPECT_EQ(a.at(j).position, b.at(j).position) << j;
    EXPECT_EQ(a.at(j).velocity, b.at(j).velocity) << j;
    EXPECT_EQ(a.at(j).energy, b.at(j).energy) << j;
    EXPECT_EQ(a.at(j).position_quantiles, b.at(j).position_quantiles) << j;
  }
  // Blocks of 10 instead of 50: counts and sketches exactly, moments merge
  // in another order.
  sweep_spec small = s;
  small.block_size = 10;
  const auto split = run_sweep(small, 2);
  const time_statistics& c = split.points.at(0).stats.observed;
  EXPECT_EQ(c.realizations(), a.realizations());
  EXPECT_EQ(c.level_counts(), a.level_counts());
  for (std::size_t j = 0; j < a.times().size(); ++j) {
    EXPECT_EQ(c.at(j).sticking, a.at(j).sticking) << j;
    EXPECT_EQ(c.at(j).position_quantiles, a.at(j).position_quantiles) << j;
    EXPECT_EQ(c.at(j).velocity_quantiles, a.at(j).velocity_quantiles) << j;
    EXPECT_EQ(c.at(j).position.count(), a.at(j).position.count()) << j;
    EXPECT_NEAR(c.at(j).position.mean(), a.at(j).position.mean(), 1e-13) << j;
    EXPECT_NEAR(c.at(j).energy.mean(), a.at(j).energy.mean(), 1e-12 * a.at(j).energy.mean()) << j;
  }
  // The same block size on the other engine with one thread: every bit.
  small.engine = sweep_engine::reference;
  EXPECT_TRUE(run_sweep(small, 1).points.at(0).stats.observed == c);
}

TEST(ObserveTimes, LanesEqualTheReferenceWithTimesAtEventInstants) {
  sweep_spec s = paper_spec();
  s.base.switch_rate = 3.8;
  s.base.window = 20.0;
  s.realizations = 300;
  s.observe_times = times_at_events(s, 2, 3);
  std::vector<double> more = times_at_events(s, 7, 3);
  s.observe_times.insert(s.observe_times.end(), more.begin(), more.end());
  std::sort(s.observe_times.begin(), s.observe_times.end());
  s.observe_times.erase(std::unique(s.observe_times.begin(), s.observe_times.end()),
                        s.observe_times.end());
  EXPECT_GE(s.observe_times.size(), 50u);
  expect_engines_and_blocks_agree(s);
  for (auto engine : {sweep_engine::reference, sweep_engine::fast}) {
    expect_state_after_events(s, 2, engine);
    expect_state_after_events(s, 7, engine);
  }
}

TEST(ObserveTimes, LanesEqualTheReferenceOnATwoLevelFamilyPoint) {
  sweep_spec s = paper_spec();
  s.base.switch_rate = 3.8;
  s.base.static_friction = 8.0;
  s.base.kinetic_friction = 5.0;
  s.base.window = 20.0;
  s.realizations = 300;
  s.observe_times = times_at_events(s, 1, 3);
  expect_engines_and_blocks_agree(s);
  // Asymmetric levels and rates: still the lanes (undamped, two levels).
  s.base.belt_levels = {1.5, -0.5};
  s.base.belt_rates = {2.0, 6.0};
  s.observe_times = times_at_events(s, 4, 3);
  expect_engines_and_blocks_agree(s);
  for (auto engine : {sweep_engine::reference, sweep_engine::fast})
    expect_state_after_events(s, 4, engine);
}

// A dense grid (0.05 s, many times per stick and slip) on both engines:
// every count and sketch equals the episodes', at both paper stiffnesses.
TEST(ObserveTimes, DenseGridEqualsTheEpisodesOnBothEngines) {
  sweep_spec s = paper_spec();
  s.base.window = 20.0;
  s.realizations = 150;
  s.observe_times.clear();
  for (int i = 0; i <= 400; ++i) s.observe_times.push_back(0.05 * i);
  s.observe_times.back() = 20.0;
  s.axes = {{"lambda", {0.5, 10.0}}, {"k", {4.0, 40.0}}};
  for (auto engine : {sweep_engine::fast, sweep_engine::reference}) {
    s.engine = engine;
    const auto rs = run_sweep(s, 2);
    for (std::size_t i = 0; i < point_count(s); ++i) {
      SCOPED_TRACE(to_string(engine));
      (void)expect_observed_matches_episodes(s, rs, i);
    }
  }
}

// Observe times add the states and change nothing else: every other
// statistic and record is the same bits with and without them, on both
// engines, with and without a burn-in (paper model, a lanes family point, a
// damped and a three-level one); and the states do not depend on the
// burn-in (they are the physics at t_j, whatever window the totals count).
TEST(ObserveTimes, ChangeNoOtherStatisticAndIgnoreTheBurnIn) {
  std::vector<sweep_spec> specs;
  sweep_spec s = paper_spec();
  s.base.window = 20.0;
  s.realizations = 120;
  s.block_size = 25;
  s.keep_records = true;
  s.observe_times = {0.0, 3.0, 7.5, 12.0, 20.0};
  s.axes = {{"lambda", {0.5, 3.8}}, {"mu", {0.5, 5.0}}};
  specs.push_back(s);
  s.axes = {{"mu_k", {2.0, 5.0}}, {"c", {0.0, 0.6}}};
  s.base.static_friction = 8.0;
  specs.push_back(s);
  s.axes = {};
  s.base.static_friction = 0.0;
  s.base.belt_levels = {1.0, -0.5, 0.0};
  s.base.belt_generator = {-2.0, 1.5, 0.5, 0.25, -0.75, 0.5, 1.0, 2.0, -3.0};
  specs.push_back(s);
  for (const sweep_spec& base : specs)
    for (double T : {0.0, 7.5})
      for (auto engine : {sweep_engine::fast, sweep_engine::reference}) {
        SCOPED_TRACE(testing::Message() << to_string(engine) << " burn-in " << T << " levels "
                                        << base.base.levels().size());
        sweep_spec with = base, without = base;
        with.engine = without.engine = engine;
        with.burn_in = without.burn_in = T;
        without.observe_times.clear();
        const auto a = run_sweep(with, 2), b = run_sweep(without, 2);
        sweep_spec no_burn_in = with;
        no_burn_in.burn_in = 0.0;
        const auto c = T > 0.0 ? run_sweep(no_burn_in, 2) : a;
        for (std::size_t i = 0; i < a.points.size(); ++i) {
          EXPECT_TRUE(testing_support::same_bits(a.points[i].stats, b.points[i].stats)) << i;
          EXPECT_TRUE(a.points[i].stats.stick_survival == b.points[i].stats.stick_survival) << i;
          EXPECT_FALSE(b.points[i].stats.observed.selected());
          EXPECT_EQ(a.points[i].stats.observed.realizations(), base.realizations) << i;
          EXPECT_TRUE(a.points[i].stats.observed == c.points[i].stats.observed) << i;
          for (std::size_t r = 0; r < a.records[i].size(); ++r)
            EXPECT_TRUE(testing_support::same_bits(a.records[i][r], b.records[i][r])) << i << "/" << r;
        }
      }
}

// The configurations that take other observers or streams still fill the
// states, and the same ones: without the family statistics (the paper
// study's lane observer), means only, without records; and common random
// numbers (every point on the same streams) against the episodes.
TEST(ObserveTimes, EveryConfigurationFillsTheSameStates) {
  sweep_spec s = paper_spec();
  s.base.window = 20.0;
  s.realizations = 200;
  s.observe_times = {0.0, 1.0, 7.5, 20.0};
  s.axes = {{"lambda", {0.5, 3.8}}, {"k", {4.0, 40.0}}};
  const auto reference = run_sweep(s, 2);
  for (int config = 0; config < 3; ++config) {
    sweep_spec t = s;
    if (config == 0) t.family_statistics = false;
    if (config == 1) t.means_only = true;
    if (config == 2) t.keep_records = true;
    for (auto engine : {sweep_engine::fast, sweep_engine::reference}) {
      t.engine = engine;
      const auto r = run_sweep(t, 2);
      for (std::size_t i = 0; i < r.points.size(); ++i)
        EXPECT_TRUE(r.points[i].stats.observed == reference.points[i].stats.observed)
            << "config " << config << " " << to_string(engine) << " point " << i;
    }
  }
  s.common_random_numbers = true;
  const auto crn = run_sweep(s, 2);
  for (std::size_t i = 0; i < point_count(s); ++i) (void)expect_observed_matches_episodes(s, crn, i);
}

// The journal: a unit's result and a merged prefix keep `observed` through
// serialization, a resume from a prefix ends with the same bits as the run
// without one, and the times are part of the spec's identity.
TEST(ObserveTimes, SurviveTheJournalAndAResume) {
  sweep_spec s = paper_spec();
  s.base.window = 20.0;
  s.realizations = 200;
  s.observe_times = {0.0, 1.0, 7.5, 20.0};
  const work_unit u{0, 1};
  const block_result r = simulate_block(s, u);
  const auto [u2, r2] = deserialize_unit_result(serialize(u, r));
  EXPECT_EQ(u2, u);
  EXPECT_TRUE(r2.stats.observed == r.stats.observed);
  EXPECT_EQ(r2.stats.observed.realizations(), 50u);
  EXPECT_NO_THROW(check_block_shape(s, u, r2));

  const auto whole = run_sweep(s, 1);
  ordered_merger first(s);
  for (std::uint64_t b = 0; b < 2; ++b) first.add({0, b}, simulate_block(s, {0, b}));
  const merged_prefix prefix = deserialize_merged_prefix(serialize_merged_prefix(0, 2, first.merged(0)));
  EXPECT_TRUE(prefix.stats.observed == first.merged(0).observed);
  EXPECT_NO_THROW(check_prefix_shape(s, prefix));
  ordered_merger resumed(s);
  resumed.restore(prefix);
  for (std::uint64_t b = 2; b < 4; ++b) resumed.add({0, b}, simulate_block(s, {0, b}));
  EXPECT_TRUE(resumed.merged(0).observed == whole.points[0].stats.observed);

  const sweep_spec back = deserialize_sweep_spec(serialize(s));
  EXPECT_EQ(back.observe_times, s.observe_times);
  sweep_spec other = s;
  other.observe_times[1] = 1.5;
  EXPECT_FALSE(same_results(s, other));
  EXPECT_NE(fingerprint(s), fingerprint(other));
  EXPECT_FALSE(first_difference(s, other).empty());
}

// Observe times are part of the sweep's validation: ascending, in [0, t_a]
// at every point, finite, not -0 (whose bits would name another spec).
TEST(ObserveTimes, OutOfRangeTimesAreRefused) {
  sweep_spec s = paper_spec();
  s.realizations = 10;
  EXPECT_NO_THROW(validate(s));
  for (const std::vector<double>& bad :
       {std::vector<double>{-0.1, 1.0}, {1.0, 0.5}, {0.0, 50.5}, {std::nan(""), 1.0},
        {0.0, HUGE_VAL}, {-0.0, 1.0}, {1.0, 1.0}}) {
    s.observe_times = bad;
    EXPECT_THROW(validate(s), error) << bad[0] << " " << bad[1];
  }
  s.observe_times = {0.0, 30.0};
  s.axes = {{"ta", {50.0, 20.0}}};
  EXPECT_THROW(validate(s), error);
  s.observe_times = {0.0, 20.0};
  EXPECT_NO_THROW(validate(s));
}

// A t_a axis: t = 20 is t_a at the point with t_a = 20 (the state at t_a,
// the last episode) and an inner time at the other.
TEST(ObserveTimes, TimeEqualToTheWindowOfOnePointOfATaAxis) {
  sweep_spec s = paper_spec();
  s.base.switch_rate = 3.8;
  s.realizations = 400;
  s.observe_times = {0.0, 5.0, 20.0};
  s.axes = {{"ta", {50.0, 20.0}}};
  const auto rs = run_sweep(s, 2);
  for (std::size_t i = 0; i < 2; ++i) (void)expect_observed_matches_episodes(s, rs, i);
}

}  // namespace
}  // namespace stickslip
