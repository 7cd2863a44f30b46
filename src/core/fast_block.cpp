// The fast engine: see include/stickslip/detail/fast_block.hpp.
#include "stickslip/detail/fast_block.hpp"

#include <algorithm>
#include <atomic>

#include "stickslip/detail/fast_switches.hpp"
#include "stickslip/initial_conditions.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::detail {

namespace {
std::atomic<fast_variant> g_variant{fast_variant::lanes};
}
void set_fast_variant(fast_variant v) noexcept { g_variant.store(v, std::memory_order_relaxed); }
fast_variant get_fast_variant() noexcept { return g_variant.load(std::memory_order_relaxed); }

block_result simulate_block_fast(const sweep_spec& s, const work_unit& u) {
  const auto p = point_parameters(s, u.point);
  block_result out;
  out.stats = point_statistics(p, s.histograms);
  const std::uint64_t first = u.block * s.block_size;
  const std::uint64_t last = std::min(s.realizations, first + s.block_size);
  if (s.keep_records) out.records.reserve(last - first);
  const auto key = point_key(p);
  realization_observer obs(p.window);
  for (std::uint64_t r = first; r < last; ++r) {
    const auto ic = draw_initial_conditions(s.initial, s.seed, key, r);
    batched_poisson_switches sw(p.switch_rate, s.seed, key, r);
    obs.reset(r, ic.position, ic.velocity, ic.belt_direction);
    const auto counts = simulate(p, ic, sw, obs, s.max_events);
    obs.finish();
    obs.record().events = counts;
    out.stats.add(obs.record(), obs.stick_durations(), obs.slip_durations(), p.window);
    if (s.keep_records) out.records.push_back(obs.record());
  }
  return out;
}

}  // namespace stickslip::detail
