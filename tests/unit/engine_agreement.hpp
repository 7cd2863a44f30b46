// Helpers of the tests that hold two engines to the same episodes, events
// and statistics, bit for bit (test_fast_path*.cpp).
#pragma once
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "stickslip/observer.hpp"
#include "stickslip/sweep.hpp"
#include "unit/same_bits.hpp"

namespace stickslip::testing_support {

// Every episode and event of one realization.
struct recorder : observer_base {
  std::vector<episode> episodes;
  std::vector<event> events;
  void on_episode(const episode& e) { episodes.push_back(e); }
  void on_event(const event& e) { events.push_back(e); }
};

inline std::string describe(const episode& e) {
  return std::string(to_string(e.kind)) + " [" + std::to_string(e.start) + ", " +
         std::to_string(e.end) + "] x=" + std::to_string(e.position_at_start) +
         " v=" + std::to_string(e.belt_velocity) + (e.censored ? " censored" : "");
}

// Every field, by bit pattern.
inline bool same_episode(const episode& a, const episode& b) {
  return a.kind == b.kind && same_bits(a.start, b.start) && same_bits(a.end, b.end) &&
         same_bits(a.position_at_start, b.position_at_start) &&
         same_bits(a.belt_velocity, b.belt_velocity) && a.censored == b.censored &&
         same_bits(a.switches_before, b.switches_before);
}
inline bool same_event(const event& a, const event& b) {
  return a.kind == b.kind && same_bits(a.time, b.time) && same_bits(a.position, b.position) &&
         same_bits(a.velocity, b.velocity) && same_bits(a.belt_velocity, b.belt_velocity);
}

// The sweep of `s` on the reference engine (1 thread) and on the fast engine
// (`threads`): every statistic and record bit for bit.
inline void expect_engines_agree(sweep_spec s, unsigned threads) {
  s.engine = sweep_engine::reference;
  const auto ref = run_sweep(s, 1);
  s.engine = sweep_engine::fast;
  const auto fast = run_sweep(s, threads);
  ASSERT_EQ(ref.points.size(), fast.points.size());
  for (std::size_t i = 0; i < ref.points.size(); ++i)
    EXPECT_TRUE(same_bits(ref.points[i].stats, fast.points[i].stats)) << "point " << i;
  ASSERT_EQ(ref.records.size(), fast.records.size());
  for (std::size_t i = 0; i < ref.records.size(); ++i) {
    ASSERT_EQ(ref.records[i].size(), fast.records[i].size());
    for (std::size_t j = 0; j < ref.records[i].size(); ++j)
      EXPECT_TRUE(same_bits(ref.records[i][j], fast.records[i][j])) << i << "/" << j;
  }
}

}  // namespace stickslip::testing_support
