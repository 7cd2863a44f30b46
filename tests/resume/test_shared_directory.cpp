// The shards of a job array share one output directory and its journal: a
// shard that fails with a deterministic error (work bound, bad input) must
// remove nothing, since the other shards' segments are in the same files. A
// whole run that fails removes only what it created.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "stickslip/error.hpp"
#include "stickslip/io/journal.hpp"
#include "stickslip/run/journaled_run.hpp"
#include "stickslip/run/runner.hpp"

using namespace stickslip;
namespace fs = std::filesystem;

namespace {

sweep_spec small() {
  sweep_spec s;
  s.axes = {{"lambda", {0.5, 3.8}}};
  s.base.window = 10.0;
  s.realizations = 100;
  s.block_size = 10;
  return s;
}

// While shard 1 "runs", shard 0 journals its units into the same directory
// (as another process of the job array would), then shard 1 fails.
class shard_zero_then_failure final : public run::runner {
 public:
  shard_zero_then_failure(const sweep_spec& s, const std::string& dir) : spec_(s), dir_(dir) {}
  void run(const sweep_spec&, ordered_merger&, const sweep_hooks&) override {
    run::run_plan plan;
    plan.dir = dir_;
    plan.slice = run::shard{0, 2};
    plan.resume = true;
    run::thread_runner inner(1);
    (void)run::sweep_into(spec_, plan, io::run_metadata{"cmd", "cfg", "v", "g", "t"}, inner, false);
    throw error(exit_code::work_bound, "a realization of shard 1 hit the event bound");
  }
  [[nodiscard]] unsigned threads() const noexcept override { return 1; }

 private:
  sweep_spec spec_;
  std::string dir_;
};

}  // namespace

TEST(SharedDirectory, AFailedShardRemovesNoneOfTheOthersWork) {
  const auto s = small();
  const auto dir = fs::temp_directory_path() / ("stickslip-shared-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  run::run_plan plan;
  plan.dir = dir.string();
  plan.slice = run::shard{1, 2};
  plan.resume = true;
  shard_zero_then_failure runner(s, dir.string());
  EXPECT_THROW((void)run::sweep_into(s, plan, io::run_metadata{"cmd", "cfg", "v", "g", "t"}, runner, false),
               error);
  ASSERT_TRUE(io::journal_exists(dir.string())) << "shard 0's journal was removed";
  const auto j = io::read_journal(dir.string(), &s);
  EXPECT_EQ(j.units.size(), unit_count(s) / 2) << "shard 0's units are all there";
  fs::remove_all(dir);
}

TEST(SharedDirectory, AFailedWholeRunRemovesTheDirectoryItCreated) {
  const auto s = small();
  const auto dir = fs::temp_directory_path() / ("stickslip-whole-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  class failing final : public run::runner {
   public:
    void run(const sweep_spec&, ordered_merger&, const sweep_hooks&) override {
      throw error(exit_code::work_bound, "event bound");
    }
    [[nodiscard]] unsigned threads() const noexcept override { return 1; }
  } runner;
  run::run_plan plan;
  plan.dir = dir.string();
  EXPECT_THROW((void)run::sweep_into(s, plan, io::run_metadata{}, runner, false), error);
  EXPECT_FALSE(fs::exists(dir));
}
