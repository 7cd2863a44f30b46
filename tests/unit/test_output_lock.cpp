// One writer per output directory (io/output_lock.hpp): a second lock on a
// locked directory is refused with exit code 2 naming the holder (pid, host,
// start time); a lock left by a killed process never blocks; the shards of
// one directory do not block each other, but block a whole run, and a whole
// run blocks them.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <optional>
#include <string>

#include "stickslip/error.hpp"
#include "stickslip/io/output_lock.hpp"

namespace stickslip::io {
namespace {

std::string fresh_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() /
                 ("stickslip-lock-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  return d.string();
}

// The message of the refusal, or nullopt when the lock was taken.
std::optional<std::string> refusal(const std::string& dir, const std::string& shard = "") {
  try {
    output_lock second(dir, "stickslip second", shard);
    return std::nullopt;
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::invalid_input);
    return std::string(e.what());
  }
}

TEST(OutputLock, ASecondWriterIsRefusedNamingTheFirst) {
  const std::string dir = fresh_dir("second");
  {
    output_lock first(dir, "stickslip sweep");
    const auto why = refusal(dir);
    ASSERT_TRUE(why.has_value());
    EXPECT_NE(why->find("stickslip sweep (pid " + std::to_string(::getpid()) + " on host "),
              std::string::npos)
        << *why;
    EXPECT_NE(why->find(" UTC)"), std::string::npos) << *why;
    EXPECT_NE(why->find(dir), std::string::npos) << *why;
  }
  EXPECT_FALSE(refusal(dir).has_value()) << "released when the first lock ends";
  std::filesystem::remove_all(dir);
}

TEST(OutputLock, AKilledHolderNeverBlocks) {
  const std::string dir = fresh_dir("killed");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    output_lock held(dir, "stickslip sweep");
    ::kill(::getpid(), SIGKILL);  // no destructor runs: the file keeps its line
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_TRUE(std::filesystem::exists(output_lock::path_of(dir)));
  EXPECT_FALSE(refusal(dir).has_value());
  std::filesystem::remove_all(dir);
}

TEST(OutputLock, ShardsShareADirectoryButNotWithAWholeRun) {
  const std::string dir = fresh_dir("shards");
  {
    output_lock s0(dir, "stickslip sweep --shard 0/2", "shard-0-of-2");
    output_lock s1(dir, "stickslip sweep --shard 1/2", "shard-1-of-2");  // no refusal
    const auto same = refusal(dir, "shard-1-of-2");
    ASSERT_TRUE(same.has_value());
    EXPECT_NE(same->find("--shard 1/2 (pid"), std::string::npos) << *same;
    const auto whole = refusal(dir);
    ASSERT_TRUE(whole.has_value());
    EXPECT_NE(whole->find("--shard 0/2 (pid"), std::string::npos) << *whole;
    EXPECT_NE(whole->find("--shard 1/2 (pid"), std::string::npos) << *whole;
  }
  {
    output_lock whole(dir, "stickslip merge");
    const auto shard = refusal(dir, "shard-0-of-2");
    ASSERT_TRUE(shard.has_value());
    EXPECT_NE(shard->find("stickslip merge (pid"), std::string::npos) << *shard;
  }
  EXPECT_FALSE(refusal(dir, "shard-0-of-2").has_value());
  EXPECT_TRUE(std::filesystem::exists(output_lock::path_of(dir, "shard-0-of-2")));
  EXPECT_FALSE(refusal(dir).has_value());
  // a whole run removes the shards' stale lock files, never its own
  EXPECT_FALSE(std::filesystem::exists(output_lock::path_of(dir, "shard-0-of-2")));
  EXPECT_TRUE(std::filesystem::exists(output_lock::path_of(dir)));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace stickslip::io
