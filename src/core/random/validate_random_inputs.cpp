#include <fmt/format.h>

#include <cmath>
#include <string>

#include "stickslip/belt_switches.hpp"
#include "stickslip/error.hpp"
#include "stickslip/initial_conditions.hpp"

namespace stickslip {

void validate(const initial_condition_law& law) {
  auto finite = [](const char* name, double v) {
    if (!std::isfinite(v) || std::abs(v) > max_magnitude)
      throw invalid_parameter(name, v, "a finite number with |value| <= 1e60");
  };
  finite("x0 (initial position)", law.position_min);
  finite("x0 (initial position)", law.position_max);
  finite("xdot0 (initial velocity)", law.velocity_min);
  finite("xdot0 (initial velocity)", law.velocity_max);
  if (law.position_min > law.position_max)
    throw invalid_parameter("x0 range minimum", law.position_min,
                            fmt::format("<= maximum {}", law.position_max));
  if (law.velocity_min > law.velocity_max)
    throw invalid_parameter("xdot0 range minimum", law.velocity_min,
                            fmt::format("<= maximum {}", law.velocity_max));
  // The level count is checked with the model (sweep/validate_sweep.cpp): +1 / -1 on two
  // levels, 1..n on n levels.
  if (law.belt_start < -1)
    throw invalid_parameter("belt-start", law.belt_start,
                            "+1 (first level), -1 (second level), a level number, or stationary");
}

void validate_belt_start(int start, std::size_t levels, bool stationary_allowed) {
  const int lowest = levels == 2 ? -1 : 1;
  const bool ok = (start == 0 && stationary_allowed) ||
                  (start != 0 && start >= lowest && start <= (levels == 2 ? 1 : static_cast<int>(levels)));
  if (ok) return;
  const std::string stationary = stationary_allowed ? ", or stationary" : "";
  throw invalid_parameter("belt-start", start,
                          levels == 2 ? "+1 (first level), -1 (second level)" + stationary
                                      : fmt::format("a level number 1..{}{}", levels, stationary));
}

void validate(const initial_conditions& ic) {
  if (!std::isfinite(ic.position) || std::abs(ic.position) > max_magnitude)
    throw invalid_parameter("x0 (initial position)", ic.position,
                            "a finite number with |value| <= 1e60");
  if (!std::isfinite(ic.velocity) || std::abs(ic.velocity) > max_magnitude)
    throw invalid_parameter("xdot0 (initial velocity)", ic.velocity,
                            "a finite number with |value| <= 1e60");
  if (ic.belt_direction != 1 && ic.belt_direction != -1)
    throw invalid_parameter("belt-start", ic.belt_direction, "+1 or -1");
}

void validate_switch_times(std::span<const double> times) {
  for (std::size_t i = 0; i < times.size(); ++i) {
    const std::string name = "switch time #" + std::to_string(i + 1);
    if (!std::isfinite(times[i]) || times[i] < 0.0)
      throw invalid_parameter(name, times[i], "finite and >= 0");
    if (i > 0 && !(times[i] > times[i - 1]))
      throw invalid_parameter(name, times[i],
                              fmt::format("strictly greater than the previous one ({}): times must be sorted",
                                          times[i - 1]));
  }
}

}  // namespace stickslip
