// The choice of engine for a point (engines/point_engine.hpp).
#include "stickslip/engines/point_engine.hpp"

#include <atomic>
#include <cstddef>

#include "stickslip/detail/fast_block.hpp"
#include "stickslip/model/oscillator_model.hpp"
#include "stickslip/parameters.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"

namespace stickslip {

const char* to_string(point_engine e) noexcept {
  switch (e) {
    case point_engine::lanes: return "lanes";
    case point_engine::reference: return "reference";
    case point_engine::uncertain: return "uncertain";
    case point_engine::sensitivity: return "sensitivity";
    case point_engine::paper_integrator: return "paper_integrator";
  }
  return "?";
}

// The lane engine runs the paper's model and the family's undamped
// two-level models with mu_s >= mu_k (any levels, 0 included, any rates):
// the same episodes, events and statistics as simulate_model
// (tests/unit/test_fast_path_family.cpp).
bool detail::runs_in_lanes(const model_parameters& p) {
  if (p.is_paper_model()) return true;
  const oscillator_model m = model_of(p);
  return m.damping == 0.0 && m.belt.level_count() == 2 &&
         m.static_friction >= m.kinetic_friction;
}

namespace {
std::atomic<std::uint64_t> g_engine_runs[5] = {};  // by point_engine
}
void detail::count_engine_run(point_engine e) noexcept {
  g_engine_runs[static_cast<std::size_t>(e)].fetch_add(1, std::memory_order_relaxed);
}
std::uint64_t detail::engine_runs(point_engine e) noexcept {
  return g_engine_runs[static_cast<std::size_t>(e)].load(std::memory_order_relaxed);
}

point_engine draw_engine(const model_parameters& drawn) {
  return drawn.is_paper_model() ? point_engine::paper_integrator : point_engine::reference;
}

point_engine engine_for(const sweep_spec& s, const model_parameters& p) {
  if (is_sensitivity(s)) return point_engine::sensitivity;
  if (!s.uncertain.empty()) return point_engine::uncertain;
  if (s.engine == sweep_engine::fast && detail::runs_in_lanes(p)) return point_engine::lanes;
  return point_engine::reference;
}

}  // namespace stickslip
