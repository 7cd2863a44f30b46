// A stop request for a running sweep. Anything may request it: a signal
// (stop_on_signals), a Python KeyboardInterrupt check, a test. No unit starts
// after it; the units in flight finish and are journaled, so --resume loses
// nothing. request() is async-signal-safe (a lock-free atomic store).
#pragma once
#include <atomic>
#include <csignal>
#include <string>

namespace stickslip::run {

class stop_token {
 public:
  // `reason` > 0: a signal number (the run then ends with exit code 128 + reason).
  void request(int reason) noexcept { reason_.store(reason, std::memory_order_relaxed); }
  [[nodiscard]] int reason() const noexcept { return reason_.load(std::memory_order_relaxed); }
  [[nodiscard]] bool requested() const noexcept { return reason() != 0; }
  void reset() noexcept { request(0); }

 private:
  std::atomic<int> reason_{0};
  static_assert(std::atomic<int>::is_always_lock_free);
};

// The signals that stop a run: SIGINT (Ctrl-C), SIGTERM (a scheduler's time
// limit) and SIGUSR1 (the one to use under mpirun, which forwards it to every
// rank; under SLURM `#SBATCH --signal=USR1@120`; docs/scaling.md).
inline constexpr int stop_signals[] = {SIGINT, SIGTERM, SIGUSR1};

// "signal 2 (SIGINT)": what the interruption messages say.
[[nodiscard]] std::string signal_text(int signal);

// For its lifetime, the stop signals request a stop on `token` (one object
// at a time per process); the previous handlers are restored afterwards.
class stop_on_signals {
 public:
  explicit stop_on_signals(stop_token& token);
  ~stop_on_signals();
  stop_on_signals(const stop_on_signals&) = delete;
  stop_on_signals& operator=(const stop_on_signals&) = delete;

 private:
  void (*old_[std::size(stop_signals)])(int) = {};
};

// Workers of an MPI run ignore the stop signals: rank 0 decides when to stop
// (a worker that died on the signal would make rank 0 abort instead).
void ignore_stop_signals() noexcept;

}  // namespace stickslip::run
