// Adaptive sampling (--target-ci) across a stop and --resume: the stop rule
// sees only the ordered merge, so a run stopped after some units and resumed
// from its journal gives bit for bit the results of an uninterrupted run,
// whatever blocks were computed ahead of the stop rule. Likewise with common
// random numbers.
#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "stickslip/error.hpp"
#include "stickslip/run/journaled_run.hpp"
#include "stickslip/run/runner.hpp"
#include "unit/same_bits.hpp"

namespace stickslip {
namespace {
namespace fs = std::filesystem;
using testing_support::same_bits;

sweep_spec adaptive_spec(bool crn) {
  sweep_spec s;
  s.base.stiffness = 40.0;
  s.axes = {{"lambda", {0.3, 1.0, 3.8, 12.0}}, {"mu", {0.5, 5.0}}};
  s.realizations = 100000;  // the cap
  s.target_statistic = std::string(1, 'R');  // not = "R": a false -Wrestrict of GCC 12
  s.target_halfwidth = 0.003;
  s.min_realizations = 300;
  s.common_random_numbers = crn;
  s.seed = 4;
  return s;
}

struct temp_dir {
  fs::path path;
  temp_dir() {
    std::string name = "stickslip-target-ci-";
    name.append(::testing::UnitTest::GetInstance()->current_test_info()->name());
    name.append(std::to_string(::getpid()));
    path = fs::temp_directory_path() / name;
    fs::remove_all(path);
  }
  ~temp_dir() { fs::remove_all(path); }
};

void expect_same(const result_set& a, const result_set& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t p = 0; p < a.points.size(); ++p)
    EXPECT_TRUE(same_bits(a.points[p].stats, b.points[p].stats)) << "point " << p;
}

void stopped_then_resumed(bool crn) {
  const auto s = adaptive_spec(crn);
  const auto whole = run_sweep(s, 1);
  for (std::uint64_t stop_after : {3u, 40u, 200u}) {
    temp_dir d;
    run::stop_token stop;
    run::run_plan plan;
    plan.dir = d.path.string();
    plan.stop = &stop;
    plan.checkpoint_interval = std::chrono::duration<double>(0);
    std::atomic<std::uint64_t> seen{0};
    plan.progress = [&](std::uint64_t, std::uint64_t, double) {
      if (++seen == stop_after) stop.request(15);
    };
    run::thread_runner two(2);
    bool stopped = false;
    try {
      (void)run::run_journaled(s, plan, {}, two);
    } catch (const error& e) {
      EXPECT_EQ(static_cast<int>(e.code()), 128 + 15) << e.what();
      stopped = true;
    }
    if (stop_after == 3) {
      EXPECT_TRUE(stopped) << "the first run must be cut short";
    }
    stop.reset();
    plan.resume = true;
    plan.progress = nullptr;
    run::thread_runner one(1);
    const auto out = run::run_journaled(s, plan, {}, one);
    ASSERT_TRUE(out.results);
    expect_same(*out.results, whole);
  }
  expect_same(run_sweep(s, 2), whole);
}

TEST(TargetCiResume, StoppedAndResumedRunsEqualAnUninterruptedOne) { stopped_then_resumed(false); }
TEST(TargetCiResume, SoWithCommonRandomNumbers) { stopped_then_resumed(true); }

TEST(TargetCiResume, ShardsAreRefused) {
  temp_dir d;
  run::run_plan plan;
  plan.dir = d.path.string();
  plan.slice = run::parse_shard("0/2");
  run::thread_runner one(1);
  EXPECT_THROW((void)run::run_journaled(adaptive_spec(false), plan, {}, one), error);
}

}  // namespace
}  // namespace stickslip
