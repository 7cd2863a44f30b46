#include "stickslip/run/runner.hpp"

#include <algorithm>
#include <thread>

namespace stickslip::run {

unsigned resolve_threads(unsigned threads) noexcept {
  return threads ? threads : std::max(1u, std::thread::hardware_concurrency());
}

thread_runner::thread_runner(unsigned threads) noexcept : threads_(resolve_threads(threads)) {}

void thread_runner::run(const sweep_spec& s, ordered_merger& merger, const sweep_hooks& hooks) {
  run_units(s, threads_, merger, hooks);
}

}  // namespace stickslip::run
