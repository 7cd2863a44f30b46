// Named parameter sets. The founding paper prints k = 4 N/m, but its figures
// were computed with k = 40 N/m (docs/reproduction.md); new users copy the
// printed defaults without knowing. A preset names a whole set at once:
//   paper-printed   m = 1 kg, k = 4 N/m, g = 9.81 m/s^2, V = 1 m/s, t_a = 50 s
//                   (the values printed in the paper; also the defaults)
//   paper-figures   the same with k = 40 N/m (what the published figures used)
// mu and lambda keep their defaults (5 and 1 1/s): they are what a study sweeps.
#pragma once
#include <span>
#include <string>

#include "stickslip/parameters.hpp"

namespace stickslip {

struct parameter_preset {
  const char* name;
  const char* description;
  model_parameters parameters;
};

[[nodiscard]] std::span<const parameter_preset> parameter_presets() noexcept;

// The preset called `name`; throws stickslip::error (invalid input) naming
// the known presets otherwise. `key` names the flag or key in the message.
[[nodiscard]] const parameter_preset& find_preset(const std::string& key, const std::string& name);

}  // namespace stickslip
