// One writer per output directory: advisory flock(2) locks on files inside
// DIR, held from before a command looks at DIR until its outputs are written
// (or it stops). A second writer is refused at once (exit 2) with a message
// naming the holder: its command, pid, host and start time, which the holder
// writes into its lock file. The kernel releases a flock when its process
// dies, so a lock left by a killed run (kill -9, a node failure) never
// blocks: the file may stay, the lock does not. On a file system without
// locks (flock fails with ENOSYS, ENOLCK, EOPNOTSUPP or EINVAL: some
// network file systems) a warning is printed and the run goes on unguarded.
// The directory's lock file is never removed (that would let two writers
// lock two different files of one name).
//
// A whole run (sweep, merge, reproduce, Python's sweep(output=))
// holds DIR/.stickslip.lock exclusively. The shards of a job array (--shard
// i/n) write their own journal segments into one DIR: each holds
// .stickslip.lock shared (so no whole run can start beside them) and its own
// .stickslip-shard-i-of-n.lock exclusively (so the same shard cannot run
// twice), and shards do not block each other. A whole run, once it holds
// the directory, removes the shards' lock files: no shard can hold or take
// one then.
#pragma once
#include <string>

namespace stickslip::io {

class output_lock {
 public:
  // Locks `dir` (created if missing) for `command` (e.g. "stickslip sweep");
  // `shard` is the shard's name ("shard-3-of-16"), empty for a whole run.
  // Throws stickslip::error: invalid_input (2) when another process holds
  // the lock, io_failure (3) when a lock file cannot be created.
  output_lock(const std::string& dir, const std::string& command, const std::string& shard = "");
  ~output_lock();
  output_lock(output_lock&& other) noexcept;
  output_lock& operator=(output_lock&&) = delete;
  output_lock(const output_lock&) = delete;
  output_lock& operator=(const output_lock&) = delete;

  // The lock file's path for `dir` and a shard's name (empty: the whole run's).
  [[nodiscard]] static std::string path_of(const std::string& dir, const std::string& shard = "");

 private:
  void take(const std::string& dir, const std::string& command, const std::string& shard);
  int run_fd_ = -1, shard_fd_ = -1;
};

}  // namespace stickslip::io
