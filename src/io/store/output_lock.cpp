// One writer per output directory (io/output_lock.hpp).
#include "stickslip/io/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "stickslip/error.hpp"
#include "stickslip/io/atomic_file.hpp"

namespace stickslip::io {
namespace {

std::string host_name() {
  char buf[256] = {};
  if (::gethostname(buf, sizeof buf - 1) != 0) return "?";
  return buf;
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S UTC", &tm);
  return buf;
}

// The holder's line, as it wrote it; empty when there is none.
std::string line_of(int fd) {
  char buf[512] = {};
  const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
  if (n <= 0) return "";
  std::string s(buf, static_cast<std::size_t>(n));
  while (!s.empty() && (s.back() == '\n' || s.back() == '\0')) s.pop_back();
  return s;
}

void describe_holder(int fd, const std::string& command) {
  const std::string line = fmt::format("{} (pid {} on host {}, started {})\n", command,
                                       static_cast<long>(::getpid()), host_name(), utc_now());
  // Best effort: without its line the lock still holds, and a second writer
  // is still refused (as "another stickslip process").
  if (::ftruncate(fd, 0) == 0) (void)!::pwrite(fd, line.data(), line.size(), 0);
}

int open_lock_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0)
    throw io_error(path, fmt::format("cannot create the lock file: {}", std::strerror(errno)));
  return fd;
}

// The lines of the shards that hold their locks in `dir` now.
std::vector<std::string> running_shards(const std::string& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(".stickslip-shard-", 0) != 0) continue;
    const int fd = ::open(entry.path().c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) continue;
    if (::flock(fd, LOCK_SH | LOCK_NB) == 0) {
      ::flock(fd, LOCK_UN);
    } else {
      const std::string line = line_of(fd);
      out.push_back(line.empty() ? name : line);
    }
    ::close(fd);
  }
  return out;
}

// Held exclusively, DIR has no shard running, and none can start (a shard
// takes the directory's lock shared before its own): the shards' lock files
// are stale and can go, so that a finished directory keeps only its own.
void remove_shard_lock_files(const std::string& dir) {
  std::error_code ec;
  std::vector<std::filesystem::path> stale;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec))
    if (entry.path().filename().string().rfind(".stickslip-shard-", 0) == 0)
      stale.push_back(entry.path());
  for (const auto& p : stale) std::filesystem::remove(p, ec);
}

[[noreturn]] void refuse(const std::string& dir, const std::string& holder) {
  throw error(exit_code::invalid_input,
              fmt::format("output directory '{}' is in use by {}: one writer at a time; wait for "
                          "it to finish (or stop it), or choose another -o DIR",
                          dir, holder.empty() ? std::string("another stickslip process") : holder));
}

// flock(fd, how | LOCK_NB): true when taken (or when the file system has no
// locks: a warning, and the run goes on unguarded, as before locks),
// false when another process holds it. Throws io_error otherwise.
bool try_lock(int fd, int how, const std::string& path) {
  if (::flock(fd, how | LOCK_NB) == 0) return true;
  const int e = errno;
  if (e == EWOULDBLOCK) return false;
  if (e == ENOSYS || e == ENOLCK || e == EOPNOTSUPP || e == EINVAL) {
    fmt::print(stderr,
               "stickslip: warning: '{}': this file system does not lock files ({}); nothing "
               "stops a second writer of this directory: run one at a time\n",
               path, std::strerror(e));
    return true;
  }
  throw io_error(path, fmt::format("cannot lock: {}", std::strerror(e)));
}

}  // namespace

std::string output_lock::path_of(const std::string& dir, const std::string& shard) {
  return (std::filesystem::path(dir) /
          (shard.empty() ? std::string(".stickslip.lock") : ".stickslip-" + shard + ".lock"))
      .string();
}

output_lock::output_lock(const std::string& dir, const std::string& command,
                         const std::string& shard) {
  (void)detail::create_directories(dir);
  try {
    take(dir, command, shard);
  } catch (...) {
    if (shard_fd_ >= 0) ::close(shard_fd_);
    if (run_fd_ >= 0) ::close(run_fd_);
    throw;
  }
}

void output_lock::take(const std::string& dir, const std::string& command,
                       const std::string& shard) {
  const std::string run_path = path_of(dir);
  run_fd_ = open_lock_file(run_path);
  if (shard.empty()) {
    if (!try_lock(run_fd_, LOCK_EX, run_path)) {
      // An exclusive holder wrote its line; shards (shared holders) leave it
      // empty and are named from their own lock files.
      std::string holder = line_of(run_fd_);
      if (holder.empty()) {
        const auto shards = running_shards(dir);
        if (!shards.empty()) holder = fmt::format("{}", fmt::join(shards, "; "));
      }
      refuse(dir, holder);
    }
    describe_holder(run_fd_, command);
    remove_shard_lock_files(dir);
    return;
  }
  if (!try_lock(run_fd_, LOCK_SH, run_path)) refuse(dir, line_of(run_fd_));
  // Held shared, nobody holds it exclusively: any line in it is stale (a
  // whole run that was killed); clear it so that it is never named.
  (void)!::ftruncate(run_fd_, 0);
  const std::string shard_path = path_of(dir, shard);
  shard_fd_ = open_lock_file(shard_path);
  if (!try_lock(shard_fd_, LOCK_EX, shard_path)) refuse(dir, line_of(shard_fd_));
  describe_holder(shard_fd_, command);
}

output_lock::~output_lock() {
  // An exclusive holder clears its line (the lock file stays): a later
  // refusal never names a finished run. Closing releases the flock.
  if (shard_fd_ >= 0) {
    (void)!::ftruncate(shard_fd_, 0);
    ::close(shard_fd_);
  } else if (run_fd_ >= 0) {
    (void)!::ftruncate(run_fd_, 0);
  }
  if (run_fd_ >= 0) ::close(run_fd_);
}

output_lock::output_lock(output_lock&& other) noexcept
    : run_fd_(other.run_fd_), shard_fd_(other.shard_fd_) {
  other.run_fd_ = other.shard_fd_ = -1;
}

}  // namespace stickslip::io
