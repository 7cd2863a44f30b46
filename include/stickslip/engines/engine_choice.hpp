// Which engine simulates a point. engine_for is the one place that decides;
// the sweep's blocks, the lane engine's entry points and its rerun after
// max_events, replay (hence `stickslip simulate` and Python's
// stickslip.simulate) and the realizations of points with laws all ask it
// (src/core/engines/engine_choice.cpp).
#pragma once
#include <cstdint>

namespace stickslip {

struct model_parameters;
struct sweep_spec;

enum class point_engine : unsigned char {
  lanes,             // the lane engine (detail/fast_block.hpp), sweep_engine::fast
  paper_reference,   // simulate (integrator.hpp), one realization at a time
  family_reference,  // simulate_model (model/model_engine.hpp), one realization at a time
  uncertain,         // a point with laws (uncertainty/uncertain_realization.hpp)
  sensitivity,       // a sensitivity design (uncertainty/sensitivity_design.hpp)
};

[[nodiscard]] const char* to_string(point_engine e) noexcept;

// The engine of the point of `s` with parameters `p` (point_parameters):
// the sensitivity design or the laws' engine when `s` has them; else the
// lane engine with sweep_engine::fast for the models it runs (the paper's,
// and the undamped two-level models with mu_s >= mu_k); else the model's
// reference engine.
[[nodiscard]] point_engine engine_for(const sweep_spec& s, const model_parameters& p);

// The model's scalar reference engine, whatever the sweep asks: what
// engine_for gives with sweep_engine::reference and no laws, and what runs a
// single realization at given parameters (replay, a point with laws, the
// lane engine's rerun). Precondition: validate(p) passed.
[[nodiscard]] point_engine reference_engine(const model_parameters& p);

namespace detail {
// How many times each engine has been entered, process-wide: a block (or a
// run of blocks) of the sweep, a lane trace, a replay. Tests use it to hold
// every site to engine_for.
void count_engine_run(point_engine e) noexcept;
[[nodiscard]] std::uint64_t engine_runs(point_engine e) noexcept;
}  // namespace detail

}  // namespace stickslip
