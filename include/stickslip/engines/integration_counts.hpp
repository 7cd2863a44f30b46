// How many realizations each scalar integrator has run, counted inside the
// integrator itself: simulate (integrator.hpp, the paper's model) and
// simulate_model (model/model_engine.hpp, every model). The lane engine runs
// neither (only its rerun after max_events does). Tests hold every engine to
// the integrator it should run (tests/unit/test_engine_choice.cpp): a choice
// made anywhere above an integrator, even inside an engine that was entered
// as expected, shows in these counts.
#pragma once
#include <cstddef>
#include <cstdint>

namespace stickslip {

enum class integrator : unsigned char { paper, model };
inline constexpr std::size_t integrator_count = 2;

namespace detail {
// Counted per thread and added to a process-wide total when the thread
// ends: integrations() is that total plus the calling thread's count, exact
// once the other threads that ran have been joined (a sweep's always are).
void count_integration(integrator i) noexcept;
[[nodiscard]] std::uint64_t integrations(integrator i) noexcept;
}  // namespace detail

}  // namespace stickslip
