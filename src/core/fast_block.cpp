// The fast engine: see include/stickslip/detail/fast_block.hpp.
#include "stickslip/detail/fast_block.hpp"

#include <atomic>

#include "stickslip/detail/fast_switches.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::detail {

namespace {
std::atomic<fast_variant> g_variant{fast_variant::lanes};
}
void set_fast_variant(fast_variant v) noexcept { g_variant.store(v, std::memory_order_relaxed); }
fast_variant get_fast_variant() noexcept { return g_variant.load(std::memory_order_relaxed); }

block_result simulate_block_fast(const sweep_spec& s, const work_unit& u) {
  return simulate_block_with<batched_poisson_switches>(s, u);
}

}  // namespace stickslip::detail
