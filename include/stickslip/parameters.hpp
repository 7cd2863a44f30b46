// Model parameters of the stick-slip oscillator  m x'' + k x = f  on a belt
// whose velocity is a telegraph process (+V / -V, sign flips at Poisson times
// of rate lambda). Friction is Coulomb: |f| <= mu m g while sticking,
// f = mu m g sgn(v - x') while slipping. See docs/model.md.
#pragma once
#include <cmath>
#include <string>

namespace stickslip {

struct model_parameters {
  double mass = 1.0;                  // m   [kg]
  double stiffness = 4.0;             // k   [N/m]
  double gravity = 9.81;              // g   [m/s^2]
  double friction_coefficient = 5.0;  // mu  [-]
  double belt_speed = 1.0;            // V   [m/s]
  double switch_rate = 1.0;           // lambda [1/s]
  double window = 50.0;               // t_a [s]

  // a = mu m g / k: the stick band is |x| <= a (spring force within max friction).
  [[nodiscard]] double band_half_width() const noexcept {
    return friction_coefficient * mass * gravity / stiffness;
  }
  // omega = sqrt(k/m).
  [[nodiscard]] double natural_frequency() const noexcept { return std::sqrt(stiffness / mass); }
  // d_max = 2a/V: a stick that starts at one band edge and runs to the other.
  [[nodiscard]] double max_stick_duration() const noexcept {
    return 2.0 * band_half_width() / belt_speed;
  }
  friend bool operator==(const model_parameters&, const model_parameters&) = default;
};

// Magnitudes the closed form handles without overflow in its squares.
inline constexpr double min_magnitude = 1e-60, max_magnitude = 1e60;

// Throws stickslip::error naming the first invalid parameter: every value must
// be finite and > 0, and it and the derived scales (a, omega, d_max, omega a,
// V/omega) must lie in [min_magnitude, max_magnitude].
void validate(const model_parameters& p);

// Names of the parameters as they appear on the command line, in config files
// and as NetCDF coordinates (the paper's symbols).
inline constexpr const char* parameter_names[] = {"m", "k", "g", "mu", "V", "lambda", "ta"};

// Access by symbol ("m", "k", "g", "mu", "V", "lambda", "ta"); throws on an unknown name.
double& parameter_by_name(model_parameters& p, const std::string& name);
double parameter_by_name(const model_parameters& p, const std::string& name);

// Long, descriptive aliases and units of each symbol.
struct parameter_info {
  const char* symbol;
  const char* long_name;   // e.g. "friction-coefficient"
  const char* description;
  const char* units;
};
const parameter_info& info_for(const std::string& symbol);

}  // namespace stickslip
