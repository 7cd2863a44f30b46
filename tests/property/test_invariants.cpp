// Invariants of the exact integrator on many random realizations (Poisson
// belt switches from poisson_switches) across wide parameter ranges:
//   - episodes alternate and tile [0, t_a] exactly;
//   - |x| <= a throughout every stick, and x' = v there;
//   - S_T <= (number of belt switches) + 1 and |S_T - S_L| <= 1;
//   - the number of events is bounded (no runaway loop), so a work bound at
//     that physical limit is never hit;
//   - consecutive closed-form segments join: evaluate(segment, end) is the
//     next segment's start state, and each slip conserves its orbit energy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "stickslip/belt_switches.hpp"
#include "stickslip/initial_conditions.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/observer.hpp"
#include "stickslip/statistics.hpp"

namespace stickslip {
namespace {

struct recorded {
  std::vector<episode> episodes;
  std::vector<segment> segments;
  void on_event(const event&) {}
  void on_segment(const segment& s) { segments.push_back(s); }
  void on_episode(const episode& e) { episodes.push_back(e); }
};

struct realization {
  model_parameters params;
  initial_conditions ic;
  std::uint64_t seed, index;
};

// lambda in [0.01, 100], mu in [0.01, 20], k in [0.5, 100], m and V in
// [0.1, 10] (log-uniform), t_a in [1, 50]; initial state either the paper's
// law or scaled to the band.
model_parameters draw_parameters(std::mt19937_64& rng) {
  std::uniform_real_distribution<> u(0.0, 1.0);
  auto log_uniform = [&](double lo, double hi) {
    return std::exp(std::log(lo) + u(rng) * (std::log(hi) - std::log(lo)));
  };
  model_parameters p;
  p.switch_rate = log_uniform(0.01, 100.0);
  p.friction_coefficient = log_uniform(0.01, 20.0);
  p.stiffness = log_uniform(0.5, 100.0);
  p.mass = log_uniform(0.1, 10.0);
  p.belt_speed = log_uniform(0.1, 10.0);
  p.window = 1.0 + 49.0 * u(rng);
  return p;
}

initial_condition_law draw_law(const model_parameters& p, std::mt19937_64& rng) {
  initial_condition_law law;  // paper: uniform on [-1, 1]
  if (std::uniform_real_distribution<>(0.0, 1.0)(rng) < 0.5) {
    const double x = 2.0 * (p.band_half_width() + p.belt_speed / p.natural_frequency());
    law = {-x, x, -2.0 * p.belt_speed, 2.0 * p.belt_speed, 0};
  }
  return law;
}

constexpr int parameter_sets = 400;
constexpr int realizations_per_set = 8;

class Invariants : public ::testing::Test {
 protected:
  // Runs every realization once; `check` sees the recorded stream.
  template <class Check>
  void for_each_realization(Check check) {
    std::mt19937_64 rng(0x1a7a'2024);
    for (int i = 0; i < parameter_sets; ++i) {
      const model_parameters p = draw_parameters(rng);
      const initial_condition_law law = draw_law(p, rng);
      for (std::uint64_t r = 0; r < realizations_per_set; ++r) {
        const std::uint64_t seed = 1000 + static_cast<std::uint64_t>(i);
        const initial_conditions ic = draw_initial_conditions(law, seed, 0, r);
        poisson_switches sw(p.switch_rate, seed, 0, r);
        recorded rec;
        realization_observer stats(p);
        stats.reset(r, ic.position, ic.velocity, ic.belt_direction);
        observer_pair<recorded, realization_observer> both{rec, stats};
        const event_counts counts = simulate(p, ic, sw, both);
        stats.finish();
        check(realization{p, ic, seed, r}, rec, stats.record(), counts);
        if (::testing::Test::HasFatalFailure()) return;
      }
    }
  }
};

std::string describe(const realization& x) {
  const auto& p = x.params;
  return "m=" + std::to_string(p.mass) + " k=" + std::to_string(p.stiffness) +
         " mu=" + std::to_string(p.friction_coefficient) + " V=" + std::to_string(p.belt_speed) +
         " lambda=" + std::to_string(p.switch_rate) + " ta=" + std::to_string(p.window) +
         " seed=" + std::to_string(x.seed) + " realization=" + std::to_string(x.index);
}

TEST_F(Invariants, EpisodesAlternateAndTileTheWindowExactly) {
  for_each_realization([](const realization& x, const recorded& rec, const realization_record&,
                          const event_counts&) {
    const auto& e = rec.episodes;
    ASSERT_FALSE(e.empty()) << describe(x);
    ASSERT_EQ(e.front().start, 0.0) << describe(x);
    ASSERT_EQ(e.back().end, x.params.window) << describe(x);
    ASSERT_TRUE(e.back().censored) << describe(x);
    for (std::size_t i = 0; i < e.size(); ++i) {
      ASSERT_GT(e[i].end, e[i].start) << describe(x) << " episode " << i;
      if (i + 1 == e.size()) break;
      ASSERT_EQ(e[i].end, e[i + 1].start) << describe(x) << " episode " << i;
      ASSERT_NE(e[i].kind, e[i + 1].kind) << describe(x) << " episode " << i;
      ASSERT_FALSE(e[i].censored) << describe(x) << " episode " << i;
    }
  });
}

TEST_F(Invariants, SticksStayInTheBandAtBeltVelocity) {
  for_each_realization([](const realization& x, const recorded& rec, const realization_record&,
                          const event_counts&) {
    const double a = x.params.band_half_width();
    // evaluate() works from t - t_start: the rounding of times up to t_a moves
    // x by V ulp(t_a).
    const double slack =
        4 * std::numeric_limits<double>::epsilon() * (a + x.params.belt_speed * x.params.window);
    for (const segment& s : rec.segments) {
      if (s.kind != mode::stick) continue;
      // x is linear during a stick: the ends bound it.
      const phase_point begin = evaluate(s, s.start), end = evaluate(s, s.end);
      ASSERT_LE(std::abs(begin.position), a + slack) << describe(x);
      ASSERT_LE(std::abs(end.position), a + slack) << describe(x);
      ASSERT_EQ(s.velocity, s.belt_velocity) << describe(x);
      ASSERT_EQ(std::abs(s.belt_velocity), x.params.belt_speed) << describe(x);
      ASSERT_EQ(begin.velocity, s.belt_velocity) << describe(x);
    }
    for (const episode& e : rec.episodes) {
      if (e.kind == mode::stick) {
        ASSERT_LE(std::abs(e.position_at_start), a + slack) << describe(x);
      }
    }
  });
}

TEST_F(Invariants, StickCountsBoundedBySwitchesAndAlternation) {
  std::uint64_t sticks = 0;
  for_each_realization([&](const realization& x, const recorded&, const realization_record& r,
                           const event_counts& counts) {
    ASSERT_LE(r.sticks, counts.belt_switches + 1) << describe(x);
    ASSERT_LE(std::abs(static_cast<long long>(r.sticks) - static_cast<long long>(r.slips)), 1)
        << describe(x);
    sticks += r.sticks;
  });
  EXPECT_GT(sticks, 10'000u);  // the invariants were really exercised
}

// Between two belt switches the motion is deterministic: at most one stick
// (it lasts to the switch, or breaks into the grazing orbit, which never
// sticks again), and relative-velocity roots at most 2 per half period plus 3:
// of two consecutive slip regions one spans at least pi in phase. Hence
//   events <= n_switch + (n_switch + 1) * 5 + 2 t_a w / pi.
// A work bound set to that limit is never hit.
TEST_F(Invariants, EventCountStaysBelowThePhysicalBound) {
  for_each_realization([](const realization& x, const recorded&, const realization_record&,
                          const event_counts& counts) {
    const double w = x.params.natural_frequency();
    const double n = static_cast<double>(counts.belt_switches);
    const double bound = n + 5.0 * (n + 1) + 2.0 * x.params.window * w / std::numbers::pi;
    ASSERT_LE(static_cast<double>(counts.total()), bound) << describe(x);
    poisson_switches sw(x.params.switch_rate, x.seed, 0, x.index);
    null_observer none;
    EXPECT_NO_THROW(simulate(x.params, x.ic, sw, none, static_cast<std::int64_t>(bound) + 2))
        << describe(x);
  });
}

TEST_F(Invariants, WorkBoundIsReportedNotTruncated) {
  model_parameters p;
  p.switch_rate = 50;
  const initial_conditions ic{0.1, 0.2, 1};
  poisson_switches sw(p.switch_rate, 1, 0, 0);
  null_observer none;
  try {
    simulate(p, ic, sw, none, 10);
    FAIL() << "a realization with ~2500 switches finished within 10 events";
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::work_bound);
  }
}

// evaluate(segment, end) must be the next segment's start state, up to
// rounding: of cos/sin of phases up to w t_a (relative 1e-13 per radian), and
// of a contact position x = c -+ sqrt(B^2 - v^2)/w, whose square root turns a
// rounding eps B^2 of its argument into eps B^2 / (w^2 |x - c|) near tangency.
// Each slip segment conserves B = |(w (x - c), x')|.
TEST_F(Invariants, SegmentsJoinAndConserveOrbitEnergy) {
  for_each_realization([](const realization& x, const recorded& rec, const realization_record&,
                          const event_counts&) {
    const auto& s = rec.segments;
    ASSERT_FALSE(s.empty());
    ASSERT_EQ(s.front().start, 0.0) << describe(x);
    ASSERT_EQ(s.back().end, x.params.window) << describe(x);
    const double a = x.params.band_half_width(), w = x.params.natural_frequency();
    for (std::size_t i = 0; i < s.size(); ++i) {
      const phase_point end = evaluate(s[i], s[i].end);
      const double speed =
          std::hypot(w * (s[i].position - s[i].center), s[i].velocity) + x.params.belt_speed;
      const double phase = 1.0 + w * (s[i].end - s[i].start);
      const double tol_x = 1e-13 * phase * (a + std::abs(s[i].position) + speed / w);
      const double tol_v = 1e-13 * phase * speed;
      if (s[i].kind == mode::slip) {
        const double e0 = std::hypot(w * (s[i].position - s[i].center), s[i].velocity);
        const double e1 = std::hypot(w * (end.position - s[i].center), end.velocity);
        ASSERT_NEAR(e1, e0, tol_v) << describe(x) << " segment " << i;
      }
      if (i + 1 == s.size()) break;
      ASSERT_EQ(s[i].end, s[i + 1].start) << describe(x) << " segment " << i;
      const double eps = std::numeric_limits<double>::epsilon();
      const double offset = std::max(std::abs(s[i + 1].position - s[i].center), eps * a);
      const double tol_contact = 8 * eps * speed * speed / (w * w * offset);
      ASSERT_NEAR(end.position, s[i + 1].position, tol_x + tol_contact)
          << describe(x) << " segment " << i;
      ASSERT_NEAR(end.velocity, s[i + 1].velocity, tol_v) << describe(x) << " segment " << i;
    }
  });
}

}  // namespace
}  // namespace stickslip
