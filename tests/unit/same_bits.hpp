// Bit-for-bit comparison of everything a work unit produces, for the tests
// that hold the engines (reference, fast, lanes) to identical results.
#pragma once
#include <bit>
#include <cstdint>

#include "stickslip/statistics.hpp"

namespace stickslip::testing_support {

inline bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}
inline bool same_bits(const mean_variance& a, const mean_variance& b) {
  return a.count() == b.count() && same_bits(a.mean(), b.mean()) &&
         same_bits(a.sum_sq_dev(), b.sum_sq_dev());
}
inline bool same_bits(const event_counts& a, const event_counts& b) {
  return a.belt_switches == b.belt_switches && a.stick_onsets == b.stick_onsets &&
         a.stick_breaks == b.stick_breaks && a.slip_reversals == b.slip_reversals;
}
inline bool same_bits(const point_statistics& a, const point_statistics& b) {
  bool ok = same_bits(a.stick_fraction, b.stick_fraction) &&
            same_bits(a.sticks_per_time, b.sticks_per_time) &&
            same_bits(a.slips_per_time, b.slips_per_time) &&
            same_bits(a.stick_duration, b.stick_duration) &&
            same_bits(a.first_stick_duration, b.first_stick_duration) &&
            same_bits(a.slip_duration, b.slip_duration) &&
            a.stick_fraction_hist == b.stick_fraction_hist &&
            a.stick_duration_hist == b.stick_duration_hist &&
            a.first_stick_duration_hist == b.first_stick_duration_hist &&
            a.slip_duration_hist == b.slip_duration_hist && a.realizations == b.realizations &&
            a.no_stick == b.no_stick && a.first_stick_censored == b.first_stick_censored &&
            same_bits(a.events, b.events) && a.convergence.size() == b.convergence.size();
  for (std::size_t i = 0; ok && i < a.convergence.size(); ++i) {
    const auto &x = a.convergence[i], &y = b.convergence[i];
    ok = x.realizations == y.realizations && same_bits(x.R_mean, y.R_mean) &&
         same_bits(x.R_ci95_half_width, y.R_ci95_half_width) &&
         same_bits(x.stick_duration_mean, y.stick_duration_mean) &&
         same_bits(x.stick_duration_ci95_half_width, y.stick_duration_ci95_half_width);
  }
  return ok;
}
inline bool same_bits(const realization_record& a, const realization_record& b) {
  return a.realization == b.realization && same_bits(a.x0, b.x0) && same_bits(a.xdot0, b.xdot0) &&
         a.belt_start == b.belt_start && a.sticks == b.sticks && a.slips == b.slips &&
         same_bits(a.stick_fraction, b.stick_fraction) &&
         same_bits(a.first_stick_start, b.first_stick_start) &&
         same_bits(a.first_stick_duration, b.first_stick_duration) &&
         a.first_stick_censored == b.first_stick_censored && same_bits(a.events, b.events);
}

}  // namespace stickslip::testing_support
