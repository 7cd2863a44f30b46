// Which engine simulates a point of a sweep: engine_for is the one place
// that decides. The sweep's blocks and simulate_units ask it, and the lane
// engine's entry points run only the points it sends there
// (engines/point_engine.hpp names the engines).
#pragma once
#include "stickslip/engines/point_engine.hpp"

namespace stickslip {

struct sweep_spec;

// The engine of the point of `s` with parameters `p` (point_parameters):
// the sensitivity design or the laws' engine when `s` has them; else the
// lane engine with sweep_engine::fast for the models it runs (the paper's,
// and the undamped two-level models with mu_s >= mu_k,
// detail::runs_in_lanes); else the reference engine.
[[nodiscard]] point_engine engine_for(const sweep_spec& s, const model_parameters& p);

}  // namespace stickslip
