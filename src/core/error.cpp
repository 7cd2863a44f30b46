#include "stickslip/error.hpp"

#include <fmt/format.h>

namespace stickslip {

error invalid_parameter(const std::string& name, double value, const std::string& allowed) {
  return {exit_code::invalid_input,
          fmt::format("invalid {}: {} (allowed: {})", name, value, allowed)};
}

error invalid_value(const std::string& name, const std::string& value,
                    const std::string& allowed) {
  return {exit_code::invalid_input,
          fmt::format("invalid {}: '{}' (allowed: {})", name, value, allowed)};
}

error io_error(const std::string& path, const std::string& what) {
  return {exit_code::io_failure, fmt::format("cannot write or read '{}': {}", path, what)};
}

error work_bound_exceeded(long long events, double time, double window) {
  return {exit_code::work_bound,
          fmt::format("realization stopped after {} events at t = {} of t_a = {}: the bound "
                      "on events per realization was hit (raise --max-events, or check that "
                      "lambda * t_a is what you meant)",
                      events, time, window)};
}

}  // namespace stickslip
