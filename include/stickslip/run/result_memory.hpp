// The memory a sweep's results need, estimated before it runs, so that an
// absurd grid or bin count is refused with a clear error (exit 2) instead of
// ending in std::bad_alloc or the OOM killer. run_journaled calls it for
// every front end (sweep, reproduce, sensitivity, Python); `stickslip sweep`
// also calls it before it touches the output directory.
#pragma once
#include "stickslip/sweep.hpp"

namespace stickslip::run {

// Bytes held at once by a sweep run on `threads` threads (0 = all cores):
// per grid point the accumulators, four histograms of `bins` counts, the
// joint (D, X) histograms of bins^2 counts each (allocated for every point,
// also when the family's statistics are off) and the convergence trace
// (every block up to 64, then 32 entries per doubling:
// records_convergence_after), plus the raw records when kept, all twice (the
// writers hold about as much again); and one point's statistics per block in
// flight (a batch per thread, at most every unit).
[[nodiscard]] double estimated_result_bytes(const sweep_spec& spec, unsigned threads) noexcept;

// Throws invalid_input (exit 2) when estimated_result_bytes exceeds 80 % of
// this machine's RAM, naming both.
void check_result_memory(const sweep_spec& spec, unsigned threads);

}  // namespace stickslip::run
