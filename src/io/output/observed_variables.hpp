// The variables of the ensemble at the observe times (sweep --observe-times;
// accumulators/time_statistics.hpp): the one list that results.nc and
// summary.json iterate, with each variable's name, units, long_name and
// description, so that the two writers (and Python, which reads results.nc)
// name and describe them the same way. docs/outputs.md, "Observe times".
//
// Every variable has values at each observe time t_j: one value (over the
// grid dimensions and `time`), one per belt level (`time`, `belt_level`) or
// one per quantile level of observed_quantile_levels (`time`, `quantile`).
// The state of a realization at t_j is that of the closed-form segment
// holding t_j (state_sampler.hpp): at an event time the state just after the
// event, and t_a belongs to the last segment.
#pragma once
#include <cmath>
#include <cstddef>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "stickslip/accumulators/time_statistics.hpp"

namespace stickslip::io::detail {

enum class observed_shape : unsigned char {
  one,           // one value per time
  per_level,     // one value per belt level per time
  per_quantile,  // one value per quantile level per time
};

struct observed_variable {
  std::string name, units, long_name, description;
  observed_shape shape = observed_shape::one;
  // The values at t_j, written to out[0 .. width(s.levels())).
  std::function<void(const time_statistics& s, std::size_t j, double* out)> values;

  [[nodiscard]] std::size_t width(std::size_t levels) const noexcept {
    return shape == observed_shape::one         ? 1
           : shape == observed_shape::per_level ? levels
                                                : std::size(observed_quantile_levels);
  }
};

namespace observed_schema {

// The state variables whose mean and variance are kept at each time.
struct moment_row {
  const char* name;        // results.nc prefix: <name>_mean, _variance, _ci95_half_width
  const char* short_name;  // for a long_name: "mean <short_name>"
  const char* units;       // of the value; the variance has these squared
  const char* variance_units;
  const char* definition;
  mean_variance time_point_statistics::*moments;
};

inline constexpr moment_row moment_rows[] = {
    {"position", "position", "m", "m2", "position x of the mass", &time_point_statistics::position},
    {"velocity", "velocity", "m/s", "m2 s-2", "velocity x' of the mass",
     &time_point_statistics::velocity},
    {"relative_velocity", "rel. velocity", "m/s", "m2 s-2",
     "velocity of the mass relative to the belt, x' - v (0 while sticking)",
     &time_point_statistics::relative_velocity},
    {"energy", "energy", "J", "J2",
     "mechanical energy m x'^2 / 2 + k x^2 / 2 (kinetic plus spring; in the frame of the "
     "ground)",
     &time_point_statistics::energy},
};

struct quantile_row {
  const char* name;        // results.nc <name> over (grid, time, quantile)
  const char* long_name;
  const char* units;
  const char* definition;
  quantile_sketch time_point_statistics::*sketch;
};

inline constexpr quantile_row quantile_rows[] = {
    {"position_quantile", "quantiles of position", "m", "position x of the mass",
     &time_point_statistics::position_quantiles},
    {"velocity_quantile", "quantiles of velocity", "m/s", "velocity x' of the mass",
     &time_point_statistics::velocity_quantiles},
};

inline const std::string at_each_time =
    " at each observe time t (each realization's state from the closed-form segment holding t: "
    "at an event time the state just after the event; t = t_a belongs to the last segment)";

// "2^-5 (3.1 %) of its magnitude, and |value| < 2^-40 counts as 0": the
// accuracy of quantile_sketch, from its constants.
inline std::string sketch_accuracy() {
  const int bits = quantile_sketch::mantissa_bits + 1;
  const double percent = 100.0 * quantile_sketch::relative_accuracy;
  const int rounded_tenths = static_cast<int>(percent * 10.0 + 0.5);
  return "2^-" + std::to_string(bits) + " (" + std::to_string(rounded_tenths / 10) + "." +
         std::to_string(rounded_tenths % 10) + " %) of its magnitude, and |value| < 2^" +
         std::to_string(std::ilogb(quantile_sketch::zero_threshold)) + " counts as 0";
}

inline std::vector<observed_variable> build() {
  using shape = observed_shape;
  std::vector<observed_variable> out;
  out.push_back({"stick_probability", "1", "stick probability",
                 "fraction of the realizations sticking (x' = v, held by static friction)" +
                     at_each_time,
                 shape::one, [](const time_statistics& s, std::size_t j, double* v) {
                   v[0] = s.stick_probability(j);
                 }});
  out.push_back({"stick_probability_std_error", "1", "std error of stick probability",
                 "binomial standard error sqrt(p (1 - p) / n) of stick_probability p over n "
                 "realizations; 95% interval p +- 1.959963984540054 x this",
                 shape::one, [](const time_statistics& s, std::size_t j, double* v) {
                   v[0] = s.stick_probability_std_error(j);
                 }});
  for (const auto& m : moment_rows) {
    const auto of = [mv = m.moments](const time_statistics& s, std::size_t j) -> const mean_variance& {
      return s.at(j).*mv;
    };
    const std::string what = std::string(m.definition) + at_each_time;
    out.push_back({std::string(m.name) + "_mean", m.units, std::string("mean ") + m.short_name,
                   "mean over the realizations of the " + what, shape::one,
                   [of](const time_statistics& s, std::size_t j, double* v) { v[0] = of(s, j).mean(); }});
    out.push_back({std::string(m.name) + "_variance", m.variance_units,
                   std::string("variance of ") + m.short_name,
                   "sample variance (n - 1 in the denominator) over the realizations of the " + what, shape::one,
                   [of](const time_statistics& s, std::size_t j, double* v) {
                     v[0] = of(s, j).variance();
                   }});
    out.push_back({std::string(m.name) + "_ci95_half_width", m.units,
                   std::string("CI half-width, ") + m.short_name,
                   "half-width of the 95% confidence interval of " + std::string(m.name) +
                       "_mean: 1.959963984540054 sqrt(variance / n) (normal approximation)",
                   shape::one, [of](const time_statistics& s, std::size_t j, double* v) {
                     v[0] = of(s, j).ci95_half_width();
                   }});
  }
  out.push_back({"level_occupancy", "1", "belt level occupancy",
                 "fraction of the realizations whose belt is at level v_j (dimension "
                 "belt_level)" + at_each_time + "; sums to 1 over belt_level",
                 shape::per_level, [](const time_statistics& s, std::size_t j, double* v) {
                   for (std::size_t l = 0; l < s.levels(); ++l) v[l] = s.level_occupancy(j, l);
                 }});
  for (const auto& q : quantile_rows) {
    out.push_back(
        {q.name, q.units, q.long_name,
         "sample quantiles over the realizations of the " + std::string(q.definition) + at_each_time +
             ", at the levels q of the quantile coordinate: the k-th smallest value, k = max(1, "
             "ceil(q n)), from a streaming log-binned sketch: within " + sketch_accuracy(),
         shape::per_quantile, [sk = q.sketch](const time_statistics& s, std::size_t j, double* v) {
           s.quantiles(j, sk, v);
         }});
  }
  return out;
}

}  // namespace observed_schema

// The variables, in output order.
[[nodiscard]] inline const std::vector<observed_variable>& observed_variables() {
  static const std::vector<observed_variable> list = observed_schema::build();
  return list;
}

// All the values of `v` at a point: width values per time, time-major (the
// layout of results.nc's last dimensions).
[[nodiscard]] inline std::vector<double> observed_values(const observed_variable& v,
                                                         const time_statistics& s) {
  const std::size_t w = v.width(s.levels());
  std::vector<double> out(s.times().size() * w);
  for (std::size_t j = 0; j < s.times().size(); ++j) v.values(s, j, out.data() + j * w);
  return out;
}

}  // namespace stickslip::io::detail
