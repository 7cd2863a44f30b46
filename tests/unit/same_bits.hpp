// Bit-for-bit comparison of everything a work unit produces, for the tests
// that hold the engines (reference, fast, lanes) to identical results.
#pragma once
#include <bit>
#include <cstdint>
#include <type_traits>

#include "stickslip/record_schema.hpp"
#include "stickslip/statistics.hpp"
#include "stickslip/statistics_schema.hpp"

namespace stickslip::testing_support {

inline bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}
inline bool same_bits(const mean_variance& a, const mean_variance& b) {
  return a.count() == b.count() && same_bits(a.mean(), b.mean()) &&
         same_bits(a.sum_sq_dev(), b.sum_sq_dev());
}
// score_moments and causal_score_moments: the count and the five sums.
template <class Moments>
  requires requires(const Moments& m) { m.sum(0); }
inline bool same_bits(const Moments& a, const Moments& b) {
  bool ok = a.count() == b.count();
  for (int i = 0; i < 5; ++i) ok = ok && same_bits(a.sum(i), b.sum(i));
  return ok;
}
inline bool same_bits(const event_counts& a, const event_counts& b) {
  return a.belt_switches == b.belt_switches && a.stick_onsets == b.stick_onsets &&
         a.stick_breaks == b.stick_breaks && a.slip_reversals == b.slip_reversals &&
         same_bits(a.switch_time_sum, b.switch_time_sum);
}
// Every accumulator of the statistics schema, the realization count and the
// convergence trace.
inline bool same_bits(const point_statistics& a, const point_statistics& b) {
  bool ok = a.realizations == b.realizations && a.convergence.size() == b.convergence.size();
  for (const auto& q : quantities()) {
    ok = ok && same_bits(a.*q.moments, b.*q.moments);
    if (q.density) ok = ok && a.*q.density == b.*q.density;
    if (q.score) ok = ok && same_bits(a.*q.score, b.*q.score);
  }
  ok = ok && same_bits(a.expected_switches, b.expected_switches);
  ok = ok && same_bits(a.stick_fraction_causal_score, b.stick_fraction_causal_score);
  for (const auto& c : counters()) ok = ok && c.value(a) == c.value(b);
  for (const auto& l : level_quantities()) {
    ok = ok && (a.*l.moments).size() == (b.*l.moments).size();
    for (std::size_t i = 0; ok && i < (a.*l.moments).size(); ++i)
      ok = same_bits((a.*l.moments)[i], (b.*l.moments)[i]);
  }
  for (const auto& j : joint_histograms()) ok = ok && a.*j.counts == b.*j.counts;
  for (std::size_t i = 0; ok && i < a.convergence.size(); ++i) {
    const auto &x = a.convergence[i], &y = b.convergence[i];
    ok = x.realizations == y.realizations && same_bits(x.R_mean, y.R_mean) &&
         same_bits(x.R_ci95_half_width, y.R_ci95_half_width) &&
         same_bits(x.stick_duration_mean, y.stick_duration_mean) &&
         same_bits(x.stick_duration_ci95_half_width, y.stick_duration_ci95_half_width);
  }
  return ok;
}
// Every field of the record table (record_schema.hpp), bit for bit.
inline bool same_bits(const realization_record& a, const realization_record& b) {
  for (const auto& field : record_table) {
    const bool same = visit_field(field, a, [&](const auto& x) {
      return visit_field(field, b, [&](const auto& y) {
        if constexpr (std::is_same_v<decltype(x), decltype(y)>) {
          if constexpr (std::is_floating_point_v<std::remove_cvref_t<decltype(x)>>)
            return same_bits(x, y);
          else
            return x == y;
        } else {
          return false;
        }
      });
    });
    if (!same) return false;
  }
  return true;
}

}  // namespace stickslip::testing_support
