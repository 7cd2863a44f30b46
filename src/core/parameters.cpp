#include "stickslip/parameters.hpp"

#include <array>

#include "stickslip/error.hpp"

namespace stickslip {
namespace {

constexpr std::array<parameter_info, 7> infos{{
    {"m", "mass", "mass of the oscillator", "kg"},
    {"k", "stiffness", "spring stiffness", "N/m"},
    {"g", "gravity", "acceleration of gravity", "m/s^2"},
    {"mu", "friction-coefficient", "Coulomb friction coefficient", "1"},
    {"V", "belt-speed", "belt speed magnitude", "m/s"},
    {"lambda", "switch-rate", "Poisson rate of belt direction switches", "1/s"},
    {"ta", "window", "analysis window t_a", "s"},
}};

void require_positive_finite(const char* name, double value) {
  if (!std::isfinite(value) || value <= 0.0)
    throw invalid_parameter(name, value, "finite and > 0");
}

}  // namespace

void validate(const model_parameters& p) {
  require_positive_finite("m (mass)", p.mass);
  require_positive_finite("k (stiffness)", p.stiffness);
  require_positive_finite("g (gravity)", p.gravity);
  require_positive_finite("mu (friction coefficient)", p.friction_coefficient);
  require_positive_finite("V (belt speed)", p.belt_speed);
  require_positive_finite("lambda (switch rate)", p.switch_rate);
  require_positive_finite("ta (window)", p.window);
  // Derived quantities can still overflow or underflow (e.g. mu*m*g = inf).
  require_positive_finite("a = mu m g / k (band half-width)", p.band_half_width());
  require_positive_finite("omega = sqrt(k/m) (natural frequency)", p.natural_frequency());
  require_positive_finite("d_max = 2a/V (max stick duration)", p.max_stick_duration());
}

const parameter_info& info_for(const std::string& symbol) {
  for (const auto& i : infos)
    if (symbol == i.symbol || symbol == i.long_name) return i;
  throw invalid_value("parameter name", symbol, "m, k, g, mu, V, lambda, ta");
}

double& parameter_by_name(model_parameters& p, const std::string& name) {
  const std::string s = info_for(name).symbol;
  if (s == "m") return p.mass;
  if (s == "k") return p.stiffness;
  if (s == "g") return p.gravity;
  if (s == "mu") return p.friction_coefficient;
  if (s == "V") return p.belt_speed;
  if (s == "lambda") return p.switch_rate;
  return p.window;
}

double parameter_by_name(const model_parameters& p, const std::string& name) {
  return parameter_by_name(const_cast<model_parameters&>(p), name);
}

}  // namespace stickslip
