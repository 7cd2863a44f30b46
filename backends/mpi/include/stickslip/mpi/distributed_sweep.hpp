// MPI backend of the sweep: rank 0 hands out work units on request (dynamic
// load balancing: a unit's cost varies ~300x across lambda), every rank
// computes units on its own threads, workers send serialized block results
// back, and rank 0 merges them with ordered_merger. Merging per point in
// block order makes the result bit-identical to a single-process run for
// any number of ranks and threads.
//
// Protocol (tags in distributed_sweep.cpp):
//   rank 0 broadcasts the serialized spec (length 0 = "nothing to do, leave");
//   worker -> 0  request(n)      ask for up to n more units
//   0 -> worker  work(indices)   unit indices; an empty list means "stop"
//   worker -> 0  result(bytes)   serialize(unit, block_result)
//   worker -> 0  failure(code, message)   the worker stops after sending it
// Rank 0 keeps answering until every worker was told to stop (or failed),
// so an error anywhere ends all ranks cleanly and rank 0 reports it.
#pragma once
#include "stickslip/sweep.hpp"

namespace stickslip::mpi {

// True when this process was started by an MPI launcher (mpirun/mpiexec of
// Open MPI or MPICH, srun with PMI/PMIx), so plain runs need no mpirun.
[[nodiscard]] bool launched_by_mpi() noexcept;

// MPI_Init_thread (funneled) ... MPI_Finalize, for the lifetime of the object.
class session {
 public:
  session();
  ~session();
  session(const session&) = delete;
  session& operator=(const session&) = delete;
  [[nodiscard]] int rank() const noexcept { return rank_; }
  [[nodiscard]] int size() const noexcept { return size_; }
  [[nodiscard]] bool is_root() const noexcept { return rank_ == 0; }

 private:
  int rank_ = 0, size_ = 1;
};

// Rank 0: broadcast `s`, run the units that hooks.wanted selects on this
// rank's `threads` threads and on all workers, and merge every result into
// `merger` (hooks.unit_done and hooks.progress run on rank 0 for every unit,
// serialized). Throws the first error of any rank, after all workers stopped.
void coordinate(const session& ses, const sweep_spec& s, unsigned threads,
                ordered_merger& merger, const sweep_hooks& hooks = {});

// Ranks > 0: receive the spec of one sweep and compute its units until told
// to stop. Returns true after a sweep (also after sending a failure), false
// when rank 0 released the workers (see cancel) instead of sending a sweep.
// An error outside the compute threads is thrown after they are joined.
// Test-only: STICKSLIP_FAULT_INJECT=mpi_worker_throw_after_units:N makes it
// throw once it has sent N results (tests/faults/fault_table.sh, mpi_throw).
bool serve(const session& ses, unsigned threads);
// Ranks > 0: serve every sweep rank 0 coordinates (a command may run several,
// as `reproduce` does) until rank 0 releases the workers.
void serve_all(const session& ses, unsigned threads);

// Rank 0, when it has no more sweeps (finished, or failed before or between
// them): releases the workers from serve / serve_all.
void cancel(const session& ses);

}  // namespace stickslip::mpi
