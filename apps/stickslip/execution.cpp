#include "execution.hpp"

#include <optional>

#include "stickslip/run/stop.hpp"
#ifdef STICKSLIP_HAVE_MPI
#include "stickslip/mpi/mpi_runner.hpp"
#endif

namespace stickslip::app {

#ifdef STICKSLIP_HAVE_MPI
struct execution::mpi_state {
  mpi::session session;
};
#else
struct execution::mpi_state {};
#endif

execution::execution(unsigned threads) : threads_(threads) {
#ifdef STICKSLIP_HAVE_MPI
  if (mpi::launched_by_mpi()) {
    mpi_ = std::make_unique<mpi_state>();
    runner_ = std::make_unique<mpi::runner>(mpi_->session, threads);
    return;
  }
#endif
  runner_ = std::make_unique<run::thread_runner>(threads);
}

execution::~execution() { release(); }

void execution::release() noexcept {
  if (released_) return;
  released_ = true;
#ifdef STICKSLIP_HAVE_MPI
  if (mpi_ && mpi_->session.is_root()) mpi::cancel(mpi_->session);
#endif
}

bool execution::is_worker() const noexcept {
#ifdef STICKSLIP_HAVE_MPI
  return mpi_ && !mpi_->session.is_root();
#else
  return false;
#endif
}

void execution::serve() {
#ifdef STICKSLIP_HAVE_MPI
  // Rank 0 decides when to stop (mpirun forwards SIGUSR1 to every rank): it
  // hands out no more units and lets the workers finish the ones they hold.
  run::ignore_stop_signals();
  mpi::serve_all(mpi_->session, threads_);
#endif
}

}  // namespace stickslip::app
