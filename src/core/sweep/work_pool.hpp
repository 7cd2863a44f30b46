// The thread pool of a sweep: threads that share one range of work items
// and hand results to a single consumer. Model-free; the sweep's run_units
// (sweep.hpp) runs its units through it. Private to the core, where
// run_sweep is: the precision drivers and the paper study run sweeps through
// it and sit below or beside the run layer, and a library includes only
// the libraries below it (tests/package/layering.py).
#pragma once
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace stickslip::detail {

// The threads a run uses: `threads`, or one per core for 0.
[[nodiscard]] inline unsigned resolved_threads(unsigned threads) noexcept {
  return threads ? threads : std::max(1u, std::thread::hardware_concurrency());
}

// Runs the items [0, total) on resolved_threads(threads) threads, the
// calling thread among them. Each thread takes the next `batch` items
// [i0, i1) in turn and computes `compute(i0, i1)` without a lock, then hands
// the result to `deliver(result&)` under one lock: deliveries never overlap,
// and come in the order the batches finish. The first exception, from
// either, stops the hand-out (a batch finished after it is not delivered)
// and is rethrown once every thread has joined.
template <class Compute, class Deliver>
void run_in_batches(unsigned threads, std::uint64_t total, std::uint64_t batch, Compute compute,
                    Deliver deliver) {
  std::atomic<std::uint64_t> next{0};
  std::mutex mu;
  std::exception_ptr failure;
  auto worker = [&] {
    while (true) {
      const std::uint64_t i0 = next.fetch_add(batch);
      if (i0 >= total) return;
      const std::uint64_t i1 = std::min(total, i0 + batch);
      decltype(compute(i0, i1)) result;
      try {
        result = compute(i0, i1);
      } catch (...) {
        std::lock_guard lock(mu);
        if (!failure) failure = std::current_exception();
        next.store(total);
        return;
      }
      std::lock_guard lock(mu);
      if (failure) return;
      try {
        deliver(result);
      } catch (...) {
        failure = std::current_exception();
        next.store(total);
        return;
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < resolved_threads(threads); ++t) pool.emplace_back(worker);
  worker();
  for (auto& th : pool) th.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace stickslip::detail
