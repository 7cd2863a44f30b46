// Where a command's sweeps run: on the MPI ranks when the process was started
// by mpirun/srun (rank 0 coordinates, the other ranks serve every sweep it
// hands out), else on this process's threads. One object per command.
#pragma once
#include <memory>

#include "stickslip/run/runner.hpp"

namespace stickslip::app {

class execution {
 public:
  explicit execution(unsigned threads);  // starts MPI when launched by an MPI launcher
  ~execution();                          // rank 0 releases the workers; MPI ends
  execution(const execution&) = delete;
  execution& operator=(const execution&) = delete;

  // A worker rank: call serve() and return; rank 0 does everything else.
  [[nodiscard]] bool is_worker() const noexcept;
  void serve();
  // Rank 0 (or the only process): the runner for every sweep of the command.
  [[nodiscard]] run::runner& runner() noexcept { return *runner_; }
  // Rank 0: lets the workers return (they wait for the next sweep). The
  // destructor does it too; call it before leaving with std::_Exit.
  void release() noexcept;

 private:
  struct mpi_state;
  std::unique_ptr<mpi_state> mpi_;
  std::unique_ptr<run::runner> runner_;
  unsigned threads_;
  bool released_ = false;
};

}  // namespace stickslip::app
