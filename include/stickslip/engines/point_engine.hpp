// The engines that can simulate a point, by name (point_engine), the engine
// of one drawn realization of a point with laws (draw_engine), and the
// count of engine runs the tests hold every site to. Which engine runs a
// point of a sweep is decided in one place, engine_for
// (engines/engine_choice.hpp). Everything that runs one realization at
// given parameters (replay, hence `stickslip simulate` and Python's
// stickslip.simulate; the lane engine's rerun after max_events) runs the
// reference engine, simulate_model, for every model: the paper's model is
// its undamped two-level case, with the same bits as simulate
// (tests/unit/test_model_paper_case.cpp). simulate_realization (sweep.hpp)
// runs simulate itself: the paper study's figures use it as their oracle.
#pragma once
#include <cstddef>
#include <cstdint>

namespace stickslip {

struct model_parameters;

enum class point_engine : unsigned char {
  lanes,            // the lane engine (detail/fast_block.hpp), sweep_engine::fast
  reference,        // simulate_model (model/model_engine.hpp), one realization at a
                    // time, for every model: sweep_engine::reference
  uncertain,        // a point with laws (uncertainty/uncertain_realization.hpp)
  sensitivity,      // a sensitivity design (uncertainty/sensitivity_design.hpp)
  paper_integrator  // simulate (integrator.hpp): a point with laws runs each draw
                    // of the paper's model on it (draw_engine)
};
inline constexpr std::size_t point_engine_count =
    static_cast<std::size_t>(point_engine::paper_integrator) + 1;

[[nodiscard]] const char* to_string(point_engine e) noexcept;

// The engine of one realization of a point with laws at its drawn
// parameters: paper_integrator for a draw of the paper's model (the same
// bits as the reference engine, and about 12 % less CPU there: no belt
// chain to build per realization), else the reference engine.
[[nodiscard]] point_engine draw_engine(const model_parameters& drawn);

namespace detail {
// How many times each engine has been entered, process-wide: a block (or a
// run of blocks) of the sweep, a lane trace, a replay. Tests use it to hold
// every site to engine_for (engines/engine_choice.hpp).
void count_engine_run(point_engine e) noexcept;
[[nodiscard]] std::uint64_t engine_runs(point_engine e) noexcept;
}  // namespace detail

}  // namespace stickslip
