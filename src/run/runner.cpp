#include "stickslip/run/runner.hpp"

#include <algorithm>
#include <thread>

#include "stickslip/error.hpp"

namespace stickslip::run {

unsigned resolve_threads(unsigned threads) noexcept {
  return threads ? threads : std::max(1u, std::thread::hardware_concurrency());
}

thread_runner::thread_runner(unsigned threads) noexcept : threads_(resolve_threads(threads)) {}

void thread_runner::run(const sweep_spec& s, ordered_merger& merger, const sweep_hooks& hooks) {
  run_units(s, threads_, merger, hooks);
}

std::optional<result_set> run_unless_stopped(runner& r, const sweep_spec& s,
                                             const stop_token& stop) {
  ordered_merger merger(s);
  sweep_hooks hooks;
  hooks.wanted = [&stop](const work_unit&) { return !stop.requested(); };
  r.run(s, merger, hooks);
  if (stop.requested()) return std::nullopt;
  if (!merger.complete())
    throw error(exit_code::internal, "a sweep ended with units missing from the merge");
  return make_result_set(s, std::move(merger));
}

}  // namespace stickslip::run
