// Common-random-number finite differences: the slope of a mean
// over any swept parameter, with an interval. With common random numbers,
// realization r of every grid point uses the same random numbers, so the
// difference X_r(b) - X_r(a) of two points a, b on one axis (all other axes
// equal) has a far smaller variance than independent points would give. The
// slope at a point is the central difference between its neighbours on the
// axis (the axis sorted by value; one-sided at the ends):
//   slope = mean_r (X_r(b) - X_r(a)) / (x_b - x_a),
//   SE    = sd_r(X_r(b) - X_r(a)) / (sqrt(n) |x_b - x_a|),
// over the realizations both points ran (the common prefix, with
// --target-ci). It estimates the slope of the secant from a to b: its bias
// from the derivative is O((x_b - x_a)^2) for a central difference, and is
// not in the interval. Needs the per-realization records (keep_records)
// and common_random_numbers; for the per-realization statistics R, S_T/t_a,
// S_L/t_a and the powers. No I/O.
#pragma once
#include <string>
#include <vector>

#include "stickslip/estimates.hpp"
#include "stickslip/statistics_schema.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::precision {

// One slope (its struct is the estimate table's input, estimates.hpp,
// whose crn_slopes row maps it into every output).
using stickslip::crn_slope;

// Whether crn_slopes has something to compute: common random numbers,
// records kept, and an axis with at least two values.
[[nodiscard]] bool has_crn_slopes(const result_set& rs) noexcept;

// Per point (in point order): one slope per axis with >= 2 values and per
// per-realization quantity (schema order). Empty when !has_crn_slopes.
[[nodiscard]] std::vector<std::vector<crn_slope>> crn_slopes(const result_set& rs);

}  // namespace stickslip::precision
