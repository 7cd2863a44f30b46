// The engines by name, the engine of a drawn realization, and the count of
// engine runs (engines/point_engine.hpp).
#include "stickslip/engines/point_engine.hpp"

#include <atomic>

#include "stickslip/parameters.hpp"

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

namespace {
std::atomic<std::uint64_t> g_engine_runs[point_engine_count] = {};  // by point_engine
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

}  // namespace stickslip
