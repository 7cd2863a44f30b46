#include "stickslip/presets.hpp"

#include <array>

#include "stickslip/error.hpp"

namespace stickslip {
namespace {

constexpr model_parameters paper(double stiffness) {
  model_parameters p;
  p.mass = 1.0;
  p.stiffness = stiffness;
  p.gravity = 9.81;
  p.belt_speed = 1.0;
  p.window = 50.0;
  return p;
}

constexpr std::array presets{
    parameter_preset{"paper-printed",
                     "the paper's printed values: m = 1 kg, k = 4 N/m, g = 9.81 m/s^2, "
                     "V = 1 m/s, t_a = 50 s",
                     paper(4.0)},
    parameter_preset{"paper-figures",
                     "what the paper's figures used: the printed values with k = 40 N/m",
                     paper(40.0)},
};

}  // namespace

std::span<const parameter_preset> parameter_presets() noexcept { return presets; }

const parameter_preset& find_preset(const std::string& key, const std::string& name) {
  std::string names;
  for (const auto& p : presets) {
    if (name == p.name) return p;
    names += (names.empty() ? "" : " or ") + std::string(p.name);
  }
  throw invalid_value(key, name, names);
}

}  // namespace stickslip
