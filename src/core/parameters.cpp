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

// The closed form squares products such as (omega y)^2 and x'^2: magnitudes
// beyond this range overflow or underflow to inf/0 and would yield NaN event
// times (found by fuzz_simulator). No physical study comes near it.
void require_representable(const char* name, double value) {
  require_positive_finite(name, value);
  if (value < min_magnitude || value > max_magnitude)
    throw invalid_parameter(name, value, "between 1e-60 and 1e60");
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
  require_representable("m (mass)", p.mass);
  require_representable("k (stiffness)", p.stiffness);
  require_representable("g (gravity)", p.gravity);
  require_representable("mu (friction coefficient)", p.friction_coefficient);
  require_representable("V (belt speed)", p.belt_speed);
  require_representable("lambda (switch rate)", p.switch_rate);
  require_representable("ta (window)", p.window);
  // Derived quantities can still overflow or underflow (e.g. mu*m*g = inf).
  const double a = p.band_half_width(), w = p.natural_frequency();
  require_representable("a = mu m g / k (band half-width)", a);
  require_representable("omega = sqrt(k/m) (natural frequency)", w);
  require_representable("d_max = 2a/V (max stick duration)", p.max_stick_duration());
  require_representable("omega a (speed scale of the band)", w * a);
  require_representable("V / omega (slip amplitude scale)", p.belt_speed / w);
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
