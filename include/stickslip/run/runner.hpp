// Runners execute the work units of a sweep and merge them (the SUNDIALS
// pattern: interchangeable backends behind one interface). The thread runner
// is here; the MPI runner is in backends/mpi (stickslip/mpi/mpi_runner.hpp).
// Every runner merges with ordered_merger, so results do not depend on the
// runner, the thread count or the rank count.
#pragma once
#include <optional>

#include "stickslip/run/stop.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::run {

class runner {
 public:
  virtual ~runner() = default;
  // Runs the units hooks.wanted selects into `merger`; hooks run serialized.
  virtual void run(const sweep_spec& s, ordered_merger& merger, const sweep_hooks& hooks) = 0;
  // What the outputs record: processes (MPI ranks) and threads per process.
  [[nodiscard]] virtual int ranks() const noexcept { return 1; }
  [[nodiscard]] virtual unsigned threads() const noexcept = 0;
  // Whether run() may be handed any spec, one after another (run_journaled
  // runs a large grid window by window). The thread runner and the MPI
  // runner (each run() broadcasts its spec) say yes; the default no is for
  // a runner tied to one spec (the tests' runners that fail or stop at a
  // given unit of it), whose grids run as one window.
  [[nodiscard]] virtual bool runs_any_spec() const noexcept { return false; }
};

// All units in this process on `threads` threads (0 = all cores): run_units.
class thread_runner final : public runner {
 public:
  explicit thread_runner(unsigned threads) noexcept;
  void run(const sweep_spec& s, ordered_merger& merger, const sweep_hooks& hooks) override;
  [[nodiscard]] unsigned threads() const noexcept override { return threads_; }
  [[nodiscard]] bool runs_any_spec() const noexcept override { return true; }

 private:
  unsigned threads_;
};

// One whole sweep on `r` that can be stopped: once `stop` is requested no
// unit starts any more, and the result is empty (never a partial result).
// Used where sweeps are run one after another under a stop request: the
// peak searches of `reproduce` and Python's stickslip.peak().
[[nodiscard]] std::optional<result_set> run_unless_stopped(runner& r, const sweep_spec& s,
                                                           const stop_token& stop);

// Threads that `threads` = 0 means on this machine (all cores, at least 1).
[[nodiscard]] unsigned resolve_threads(unsigned threads) noexcept;

}  // namespace stickslip::run
