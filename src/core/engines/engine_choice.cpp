// The choice of engine for a point of a sweep (engines/engine_choice.hpp).
#include "stickslip/engines/engine_choice.hpp"

#include "stickslip/detail/fast_block.hpp"
#include "stickslip/model/oscillator_model.hpp"
#include "stickslip/parameters.hpp"
#include "stickslip/sweep_spec.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"

namespace stickslip {

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

point_engine engine_for(const sweep_spec& s, const model_parameters& p) {
  if (is_sensitivity(s)) return point_engine::sensitivity;
  if (!s.uncertain.empty()) return point_engine::uncertain;
  if (s.engine == sweep_engine::fast && detail::runs_in_lanes(p)) return point_engine::lanes;
  return point_engine::reference;
}

}  // namespace stickslip
