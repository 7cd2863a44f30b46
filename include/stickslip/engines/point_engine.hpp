// Which engine simulates a point. engine_for is the one place that decides;
// the sweep's blocks and simulate_units ask it, and the lane engine's entry
// points run only the points it sends there. Everything that runs one
// realization at given parameters (replay, hence `stickslip simulate` and
// Python's stickslip.simulate; the lane engine's rerun after max_events)
// runs the reference engine, simulate_model, for every model: the paper's
// model is its undamped two-level case, with the same bits as simulate
// (tests/unit/test_model_paper_case.cpp). Declarations only: the laws'
// headers use them, and their definitions (src/core/engines/engine_choice.cpp)
// read the sweep_spec those headers take.
#pragma once
#include <cstdint>

namespace stickslip {

struct model_parameters;
struct sweep_spec;

enum class point_engine : unsigned char {
  lanes,            // the lane engine (detail/fast_block.hpp), sweep_engine::fast
  reference,        // simulate_model (model/model_engine.hpp), one realization at a
                    // time, for every model: sweep_engine::reference
  uncertain,        // a point with laws (uncertainty/uncertain_realization.hpp)
  sensitivity,      // a sensitivity design (uncertainty/sensitivity_design.hpp)
  paper_integrator  // simulate (integrator.hpp): a point with laws runs each draw
                    // of the paper's model on it (draw_engine)
};

[[nodiscard]] const char* to_string(point_engine e) noexcept;

// The engine of the point of `s` with parameters `p` (point_parameters):
// the sensitivity design or the laws' engine when `s` has them; else the
// lane engine with sweep_engine::fast for the models it runs (the paper's,
// and the undamped two-level models with mu_s >= mu_k); else the reference
// engine.
[[nodiscard]] point_engine engine_for(const sweep_spec& s, const model_parameters& p);

// The engine of one realization of a point with laws at its drawn
// parameters: paper_integrator for a draw of the paper's model (the same
// bits as the reference engine, and about 13 % less time there: no belt
// chain to build per realization), else the reference engine.
[[nodiscard]] point_engine draw_engine(const model_parameters& drawn);

namespace detail {
// How many times each engine has been entered, process-wide: a block (or a
// run of blocks) of the sweep, a lane trace, a replay. Tests use it to hold
// every site to engine_for.
void count_engine_run(point_engine e) noexcept;
[[nodiscard]] std::uint64_t engine_runs(point_engine e) noexcept;
}  // namespace detail

}  // namespace stickslip
