// The realizations each integrator ran (engines/integration_counts.hpp).
#include "stickslip/engines/integration_counts.hpp"

#include <atomic>

namespace stickslip {
namespace {

std::atomic<std::uint64_t> g_integrations[integrator_count] = {};
// This thread's counts, added to g_integrations when it ends (an atomic
// per realization would make the threads of a sweep share one cache line).
struct thread_integrations {
  std::uint64_t n[integrator_count] = {};
  ~thread_integrations() {
    for (std::size_t i = 0; i < integrator_count; ++i)
      g_integrations[i].fetch_add(n[i], std::memory_order_relaxed);
  }
};
thread_local thread_integrations t_integrations;

}  // namespace

void detail::count_integration(integrator i) noexcept {
  ++t_integrations.n[static_cast<std::size_t>(i)];
}

std::uint64_t detail::integrations(integrator i) noexcept {
  const auto k = static_cast<std::size_t>(i);
  return g_integrations[k].load(std::memory_order_relaxed) + t_integrations.n[k];
}

}  // namespace stickslip
