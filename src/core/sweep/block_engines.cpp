// The engines a work unit runs on, chosen per point by engine_for
// (engines/engine_choice.hpp): the lane engine, the reference engine
// (simulate_model, for every model), and the scalar engines of points with
// laws and of sensitivity designs.
#include "stickslip/sweep.hpp"

#include <algorithm>
#include <stdexcept>

#include "stickslip/detail/fast_block.hpp"
#include "stickslip/engines/engine_choice.hpp"
#include "stickslip/model/model_realization.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"
#include "stickslip/uncertainty/uncertain_block.hpp"

namespace stickslip {
block_result simulate_block(const sweep_spec& s, const work_unit& u) {
  switch (engine_for(s, point_parameters(s, u.point))) {
    case point_engine::sensitivity: return simulate_block_sensitivity(s, u);
    case point_engine::uncertain: return simulate_block_uncertain(s, u);
    case point_engine::lanes: return detail::simulate_block_lanes(s, u);
    case point_engine::reference: return simulate_block_reference(s, u);
    case point_engine::paper_integrator: break;  // only a draw of a point with laws
  }
  throw std::logic_error("simulate_block: an engine without a block");
}

std::uint64_t units_per_batch(const sweep_spec& s) noexcept {
  // Points with laws (and sensitivity designs) run on the scalar engine:
  // one unit per batch, no lanes to keep busy, a finer grain for the stop
  // rules.
  if (!s.uncertain.empty()) return 1;
  return s.engine == sweep_engine::fast ? 20 : 1;  // 20 x 50 realizations
}

std::vector<block_result> simulate_units(const sweep_spec& s, const std::vector<work_unit>& units) {
  std::vector<block_result> results;
  results.reserve(units.size());
  for (std::size_t a = 0; a < units.size();) {
    std::size_t b = a + 1;  // units[a, b): consecutive blocks of one point
    while (b < units.size() && units[b].point == units[a].point &&
           units[b].block == units[b - 1].block + 1)
      ++b;
    if (engine_for(s, point_parameters(s, units[a].point)) == point_engine::lanes) {
      auto r = detail::simulate_blocks_lanes(s, units[a].point, units[a].block, b - a);
      for (auto& x : r) results.push_back(std::move(x));
    } else {
      for (std::size_t c = a; c < b; ++c) results.push_back(simulate_block(s, units[c]));
    }
    a = b;
  }
  return results;
}

namespace {
// A scalar engine's block: one realization at a time, into
// realization_observer and point_statistics::add in realization order.
// `simulate_one(r, obs, with_states)` resets the observer to realization r
// and simulates it into obs, or into with_states when it observes times.
template <class SimulateOne>
block_result simulate_block_scalar(const sweep_spec& s, const work_unit& u,
                                   const model_parameters& p, SimulateOne simulate_one) {
  block_result out;
  out.stats = block_statistics(s, p);
  const std::uint64_t first = u.block * s.block_size;
  const std::uint64_t last = std::min(s.realizations, first + s.block_size);
  if (s.keep_records) out.records.reserve(last - first);
  realization_observer obs(p, s.family_statistics, s.burn_in, &s.observe_times);
  state_sampling_observer with_states(obs);
  for (std::uint64_t r = first; r < last; ++r) {
    const event_counts counts = simulate_one(r, obs, with_states);
    obs.finish();
    obs.record().events = counts;
    if (!out.stats.keeps_causal_score()) drop_causal_score(obs.record());
    out.stats.add(obs.samples(), p.window);
    if (s.keep_records) out.records.push_back(obs.record());
  }
  return out;
}
}  // namespace

// The reference engine: simulate_model with the Markov belt
// (model/model_realization.hpp), for every model.
block_result simulate_block_reference(const sweep_spec& s, const work_unit& u) {
  detail::count_engine_run(point_engine::reference);
  const auto p = point_parameters(s, u.point);
  const family_point fp(p, stream_key(s, p));
  const std::size_t levels = fp.model.belt.level_count();
  return simulate_block_scalar(
      s, u, p,
      [&](std::uint64_t r, realization_observer& obs, state_sampling_observer& with_states) {
        const model_initial_state start = draw_model_initial_state(fp, s.initial, s.seed, r);
        obs.reset(r, start.position, start.velocity, recorded_belt_start(start.level, levels));
        return obs.observes_times()
                   ? simulate_family_realization(fp, start, s.seed, r, s.max_events, with_states)
                   : simulate_family_realization(fp, start, s.seed, r, s.max_events, obs);
      });
}

}  // namespace stickslip
