// The MPI backend behind the run layer's runner interface: rank 0 runs
// coordinate() for every sweep; the other ranks run serve_all().
#pragma once
#include "stickslip/mpi/distributed_sweep.hpp"
#include "stickslip/run/runner.hpp"

namespace stickslip::mpi {

class runner final : public run::runner {
 public:
  // `threads` per rank (0 = all cores of each rank's machine).
  runner(const session& ses, unsigned threads) noexcept
      : ses_(ses), threads_(run::resolve_threads(threads)), requested_threads_(threads) {}
  void run(const sweep_spec& s, ordered_merger& merger, const sweep_hooks& hooks) override {
    coordinate(ses_, s, requested_threads_, merger, hooks);
  }
  [[nodiscard]] int ranks() const noexcept override { return ses_.size(); }
  [[nodiscard]] unsigned threads() const noexcept override { return threads_; }
  // Every run() broadcasts its own spec, and the other ranks serve one spec
  // after another until rank 0 cancels (serve_all): so a large grid can run
  // window by window here too, with the same bits (tests/mpi).
  [[nodiscard]] bool runs_any_spec() const noexcept override { return true; }

 private:
  const session& ses_;
  unsigned threads_, requested_threads_;
};

}  // namespace stickslip::mpi
