// A large grid runs window by window (run_plan::window_points,
// journaled_run.cpp): the same bits as one window, also when interrupted in
// a later window and resumed; and the memory estimate that decides whether a
// grid is refused follows what the windows hold.
#include <gtest/gtest.h>
#include <malloc.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/io/journal.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/run/journaled_run.hpp"
#include "stickslip/run/merge.hpp"
#include "stickslip/run/result_memory.hpp"
#include "stickslip/run/runner.hpp"
#include "stickslip/run/shard.hpp"
#include "stickslip/statistics_groups.hpp"
#include "stickslip/serialize.hpp"

using namespace stickslip;
namespace fs = std::filesystem;

namespace {

// 5 x 3 points, 4 blocks each; family statistics on (the engine fills the
// joint histograms), the paper's selection (they are not written).
sweep_spec grid() {
  sweep_spec s;
  s.axes = {{"lambda", {0.3, 1.0, 2.0, 3.8, 9.0}}, {"mu", {0.5, 3.0, 7.0}}};
  s.base.window = 10.0;
  s.realizations = 40;
  s.block_size = 10;
  s.histograms.bins = 8;
  s.seed = 11;
  return s;
}

fs::path fresh(const std::string& name) {
  const auto p = fs::temp_directory_path() / ("stickslip-windows-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(p);
  return p;
}

bytes bits(const point_statistics& s) { return serialize(work_unit{}, block_result{s, {}}); }

run::run_outcome run_in(const sweep_spec& s, const fs::path& dir, std::size_t window,
                        unsigned threads = 2) {
  run::run_plan plan;
  plan.dir = dir.string();
  plan.window_points = window;
  run::thread_runner runner(threads);
  return run::run_journaled(s, plan, io::run_metadata{"cmd", "cfg", "v", "g", "t"}, runner);
}

// Point by point: the parameters, grid index and statistics (after
// release_unselected) of `b` are those of `a`, and so are the outputs.
void expect_same_results(const result_set& a, const result_set& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    auto sa = a.points[i].stats, sb = b.points[i].stats;
    run::release_unselected(sa, a.spec);
    run::release_unselected(sb, b.spec);
    EXPECT_EQ(bits(sa), bits(sb)) << "point " << i;
    EXPECT_EQ(a.points[i].index, b.points[i].index) << "point " << i;
    EXPECT_EQ(a.points[i].parameters, b.points[i].parameters) << "point " << i;
  }
  EXPECT_EQ(io::summary_json_points(a), io::summary_json_points(b));
}

}  // namespace

TEST(GridWindows, AWindowedRunHasTheBitsOfOneWindow) {
  const auto s = grid();
  const auto one = fresh("one"), windows = fresh("windows");
  const auto whole = run_in(s, one, 0);
  ASSERT_TRUE(whole.results);
  // 4 points a window: one slab of 3 points at a time (5 windows).
  for (const std::size_t window : {4u, 7u}) {
    const auto parts = run_in(s, windows, window, window == 4 ? 1 : 2);
    ASSERT_TRUE(parts.results);
    EXPECT_EQ(parts.computed_units, unit_count(s));
    expect_same_results(*whole.results, *parts.results);
    // The finished points of a windowed run hold no unselected histograms.
    EXPECT_TRUE(parts.results->points[4].stats.stick_duration_onset.cells().empty());
    EXPECT_FALSE(whole.results->points[4].stats.stick_duration_onset.cells().empty());
    fs::remove_all(windows);
  }
  fs::remove_all(one);
}

namespace {
// A thread runner that counts the specs it is given (one per window).
class counting_runner final : public run::runner {
 public:
  explicit counting_runner(unsigned threads) : inner_(threads) {}
  void run(const sweep_spec& s, ordered_merger& merger, const sweep_hooks& hooks) override {
    ++specs;
    points = std::max(points, point_count(s));
    inner_.run(s, merger, hooks);
  }
  [[nodiscard]] unsigned threads() const noexcept override { return inner_.threads(); }
  [[nodiscard]] bool runs_any_spec() const noexcept override { return true; }
  int specs = 0;
  std::size_t points = 0;  // the largest spec given

 private:
  run::thread_runner inner_;
};
}  // namespace

namespace {
// Shard i of 2 of the grid into a fresh directory, one slab (3 points) a
// window; the directory joins `dirs` (for merge_shards).
run::run_plan shard_plan(const std::string& name, std::uint32_t i, std::vector<std::string>& dirs) {
  const auto dir = fresh(name + std::to_string(i));
  dirs.push_back(dir.string());
  run::run_plan plan;
  plan.dir = dir.string();
  plan.window_points = 3;  // 5 windows of the 15-point grid
  plan.slice = run::shard{i, 2};
  return plan;
}

// Runs `plan` on one thread and stops it (SIGINT) once `units` units are
// merged: the run throws, with what it finished journaled.
void run_and_stop_after(const sweep_spec& s, run::run_plan plan, std::uint64_t units) {
  run::stop_token stop;
  plan.stop = &stop;
  plan.progress = [&](std::uint64_t done, std::uint64_t, double) {
    if (done >= units) stop.request(SIGINT);
  };
  run::thread_runner runner(1);
  EXPECT_THROW((void)run::run_journaled(s, plan, io::run_metadata{"c", "f", "v", "g", "t"}, runner),
               error);
}
}  // namespace

// A shard of a large grid runs window by window too (it journals every unit
// and keeps no results), and `stickslip merge` merges window by window: the
// same bits as one run of the whole grid at once, whatever the windows.
TEST(GridWindows, ShardsRunInWindowsAndMergeWindowByWindowWithTheBitsOfOneRun) {
  const auto s = grid();
  const auto one = fresh("shards-ref");
  const auto whole = run_in(s, one, 0);
  ASSERT_TRUE(whole.results);
  std::vector<std::string> dirs;
  for (std::uint32_t i = 0; i < 2; ++i) {
    run::run_plan plan = shard_plan("shard", i, dirs);
    EXPECT_EQ(run::memory_window(s, plan, counting_runner(1)), 3u);
    counting_runner runner(2);
    const auto out = run::run_journaled(s, plan, io::run_metadata{"c", "f", "v", "g", "t"}, runner);
    EXPECT_FALSE(out.results);
    EXPECT_EQ(runner.specs, 5) << "shard " << i;
    EXPECT_EQ(runner.points, 3u) << "shard " << i;
    EXPECT_EQ(out.computed_units, unit_count(s) / 2) << "shard " << i;
  }
  for (const std::size_t window : {0u, 3u, 4u, 7u, 1000u}) {
    const auto merged = run::merge_shards(dirs, {}, window);
    EXPECT_EQ(merged.duplicates, 0u);
    expect_same_results(*whole.results, merged.results);
    // Merged in windows, the finished points hold no unselected histograms.
    EXPECT_EQ(merged.results.points[4].stats.stick_duration_onset.cells().empty(),
              window > 0 && window < point_count(s))
        << "window " << window;
  }
  for (const auto& d : dirs) fs::remove_all(d);
  fs::remove_all(one);
}

// A shard stopped in a later window journals what it finished; resumed (in
// windows again) it runs only the rest of its units, and the merge of the
// two shards has the bits of one run.
TEST(GridWindows, AShardStoppedInALaterWindowResumesAndMergesWithTheSameBits) {
  const auto s = grid();  // 15 points x 4 blocks: 30 units a shard
  const auto one = fresh("shard-stop-ref");
  const auto whole = run_in(s, one, 0);
  ASSERT_TRUE(whole.results);
  std::vector<std::string> dirs;
  for (std::uint32_t i = 0; i < 2; ++i) {
    run::run_plan plan = shard_plan("shard-stop", i, dirs);  // 5 windows of 6 of its units
    run_and_stop_after(s, plan, 14);  // in the third window (this shard's units 13..18)
    const auto journaled = io::read_journal(plan.dir, &s).units.size();
    EXPECT_GE(journaled, 14u) << "shard " << i;
    EXPECT_LT(journaled, 30u) << "shard " << i;
    plan.resume = true;
    counting_runner again(2);
    const auto resumed = run::run_journaled(s, plan, io::run_metadata{}, again);
    EXPECT_FALSE(resumed.results);
    EXPECT_EQ(resumed.resumed_units, journaled) << "shard " << i;
    EXPECT_EQ(resumed.resumed_units + resumed.computed_units, 30u) << "shard " << i;
    EXPECT_EQ(again.points, 3u) << "shard " << i;
  }
  const auto merged = run::merge_shards(dirs, {}, 3);
  expect_same_results(*whole.results, merged.results);
  for (const auto& d : dirs) fs::remove_all(d);
  fs::remove_all(one);
}

TEST(GridWindows, AWindowedRunStoppedInALaterWindowResumesWithTheSameBits) {
  const auto s = grid();
  const auto one = fresh("ref"), dir = fresh("stopped");
  const auto whole = run_in(s, one, 0);
  run::run_plan plan;
  plan.dir = dir.string();
  plan.window_points = 3;  // one slab a window
  plan.checkpoint_interval = std::chrono::duration<double>(0);
  // Stop in the third window (units 24..35), after a unit of it is merged.
  run_and_stop_after(s, plan, 26);
  plan.resume = true;
  run::thread_runner runner(1);
  const auto resumed = run::run_journaled(s, plan, io::run_metadata{}, runner);
  ASSERT_TRUE(resumed.results);
  EXPECT_GE(resumed.resumed_units, 26u);
  EXPECT_EQ(resumed.resumed_units + resumed.computed_units, unit_count(s));
  expect_same_results(*whole.results, *resumed.results);
  fs::remove_all(one);
  fs::remove_all(dir);
}

namespace {
// The 100,000-point grid: 400 lambda x 250 mu, 20 realizations.
sweep_spec hundred_thousand_points() {
  sweep_spec s;
  s.axes = {{"lambda", std::vector<double>(400, 1.0)}, {"mu", std::vector<double>(250, 5.0)}};
  for (std::size_t i = 0; i < 400; ++i) s.axes[0].values[i] = 0.1 + 0.01 * static_cast<double>(i);
  for (std::size_t i = 0; i < 250; ++i) s.axes[1].values[i] = 0.5 + 0.02 * static_cast<double>(i);
  s.realizations = 20;
  return s;
}
}  // namespace

// The 100,000-point grid (400 x 250, 20 realizations): measured
// 3.09 GB peak RSS merged at once, 475 MB in windows of 2048 points, 455 MB
// in windows of 1024 (the default).
TEST(GridWindows, TheMemoryEstimateFollowsTheWindows) {
  sweep_spec s = hundred_thousand_points();
  const double at_once = run::estimated_result_bytes(s, 2, 0);
  const double windowed = run::estimated_result_bytes(s, 2, run::run_plan{}.window_points);
  EXPECT_GT(at_once, 2.0e9);
  EXPECT_LT(windowed, 500.0e6);
  EXPECT_GT(windowed, 200.0e6);
}

// What the front ends check before they touch DIR (memory_window): the
// window when the grid will run in windows, else the whole grid. A grid that
// fits only in windows is accepted by that check (the CLI and Python once
// refused it with the whole grid's estimate), also for a shard; a runner
// that takes one spec only, a grid within one window and window_points = 0
// hold every point.
TEST(GridWindows, TheFrontEndsCheckTheMemoryOfWhatTheRunWillHold) {
  sweep_spec s = hundred_thousand_points();
  run::thread_runner threads(2);
  run::run_plan plan;
  EXPECT_EQ(run::memory_window(s, plan, threads), plan.window_points);
  class one_spec final : public run::runner {
   public:
    void run(const sweep_spec&, ordered_merger&, const sweep_hooks&) override {}
    [[nodiscard]] unsigned threads() const noexcept override { return 1; }
  } tied;
  EXPECT_EQ(run::memory_window(s, plan, tied), 0u);
  run::run_plan shard = plan;  // a shard runs in windows too
  shard.slice = run::parse_shard("1/2");
  EXPECT_EQ(run::memory_window(s, shard, threads), plan.window_points);
  // ... and keeps no finished point: its estimate is the window's alone
  // (counted with the finished points, a grid of 2 windows with observe
  // times came out above its whole-grid estimate).
  const double kept = run::estimated_result_bytes(s, 2, plan.window_points);
  const double shard_bytes = run::estimated_result_bytes(s, 2, plan.window_points, false);
  EXPECT_LT(shard_bytes, 0.25 * kept);
  EXPECT_GT(shard_bytes, 0.0);
  sweep_spec two_windows = s;
  two_windows.axes[1].values.resize(8);  // 400 x 8 = 3,200 points
  two_windows.observe_times = {1.0, 2.0, 3.0, 4.0};
  EXPECT_LT(run::estimated_result_bytes(two_windows, 2, plan.window_points, false),
            run::estimated_result_bytes(two_windows, 2, 0, false));
  run::run_plan whole = plan;
  whole.window_points = 0;
  EXPECT_EQ(run::memory_window(s, whole, threads), 0u);
  sweep_spec small = s;
  small.axes[0].values.resize(4);  // 1,000 points: one window
  EXPECT_EQ(run::memory_window(small, plan, threads), 0u);
  // With 200 bins and the family statistics (their joint histograms, 200^2
  // cells, while merged) the grid needs ~34 GB at once and ~1.4 GB in
  // windows: on a machine of up to ~42 GB (80 %) only the whole grid's
  // estimate refused it.
  s.histograms.bins = 200;
  s.statistics = parse_statistics_selection("statistics", "paper,X");
  apply_statistics_selection(s);
  ASSERT_TRUE(s.family_statistics);
  const double at_once = run::estimated_result_bytes(s, 2, 0);
  const double windowed = run::estimated_result_bytes(s, 2, run::memory_window(s, plan, threads));
  EXPECT_GT(at_once, 30.0e9);
  EXPECT_LT(windowed, 2.0e9);
  EXPECT_NO_THROW(run::check_result_memory(s, 2, run::memory_window(s, plan, threads)));
}

// What a windowed run's results hold on the heap (glibc's bytes in use and
// mmapped; one thread, so one arena) is within the estimate and not far
// below.
TEST(GridWindows, TheEstimateCoversWhatTheResultsHold) {
  sweep_spec s = grid();
  s.axes = {{"lambda", std::vector<double>(40)}, {"mu", std::vector<double>(30)}};
  for (std::size_t i = 0; i < 40; ++i) s.axes[0].values[i] = 0.2 + 0.1 * static_cast<double>(i);
  for (std::size_t i = 0; i < 30; ++i) s.axes[1].values[i] = 0.5 + 0.2 * static_cast<double>(i);
  s.realizations = 10;
  s.histograms.bins = 50;
  const auto dir = fresh("heap");
  const auto in_use = [] {
    const auto m = ::mallinfo2();
    return static_cast<double>(m.uordblks + m.hblkhd);
  };
  {
    // Sanitizer runtimes replace malloc, and glibc's counters then stay at
    // zero: a megabyte held must show before the counters are believed.
    const double empty = in_use();
    const std::vector<char> probe(1 << 20, 1);
    asm volatile("" : : "r"(probe.data()) : "memory");
    if (in_use() - empty < 0.5 * static_cast<double>(probe.size()))
      GTEST_SKIP() << "mallinfo2 does not see this allocator (sanitizer build)";
  }
  const double before = in_use();
  const auto out = run_in(s, dir, 120, 1);
  const double held = in_use() - before;
  ASSERT_TRUE(out.results);
  const double estimate = run::estimated_result_bytes(s, 1, 120);
  EXPECT_LE(held, estimate);
  EXPECT_GE(held, 0.5 * estimate);
  fs::remove_all(dir);
}

// A finished window's points are journaled when the window ends, checkpoint
// due or not: a later window's checkpoints do not hold them. Only the last
// window follows the checkpoint rule (no checkpoint due here: an interval of
// an hour), so the journal holds every earlier window's points whole.
TEST(GridWindows, EveryWindowButTheLastIsJournaledWhenItEnds) {
  const auto s = grid();
  const auto dir = fresh("window-ends");
  run::run_plan plan;
  plan.dir = dir.string();
  plan.window_points = 3;  // one slab (3 points) a window: 5 windows
  plan.checkpoint_interval = std::chrono::duration<double>(3600);
  plan.outputs_follow = true;  // as sweep_into: only the last window may skip its checkpoint
  run::thread_runner runner(2);
  const auto out = run::run_journaled(s, plan, io::run_metadata{"c", "f", "v", "g", "t"}, runner);
  ASSERT_TRUE(out.results);
  const auto j = io::read_journal(dir.string(), &s);
  EXPECT_EQ(j.damaged, 0u);
  for (std::size_t p = 0; p < 12; ++p) {  // the first four windows
    ASSERT_TRUE(j.prefixes.count(p)) << "point " << p << " of a finished window not journaled";
    EXPECT_EQ(j.prefixes.at(p).blocks, blocks_per_point(s)) << "point " << p;
  }
  for (std::size_t p = 12; p < point_count(s); ++p)  // the last window: no checkpoint due
    EXPECT_FALSE(j.prefixes.count(p)) << "point " << p;
  fs::remove_all(dir);
}
