// The codecs of the pieces that serialize.cpp's messages are made of. Each
// type has a put() that writes it and a get_...() that reads it back and
// refuses (detail::corrupt) any bytes its put() never writes, so that a
// decoded value serializes to the very bytes it was read from.
#pragma once
#include <cstdint>
#include <string_view>
#include <vector>

#include "stickslip/serial_bytes.hpp"
#include "stickslip/statistics.hpp"
#include "stickslip/sweep.hpp"  // the bounds a decoded statistic must meet

namespace stickslip::serial {

using detail::corrupt;
using writer = detail::byte_writer;
using reader = detail::byte_reader;

// ---- lists (accumulator_codec.cpp) ----
// A list of doubles: its length, then each value.
void put_values(writer& w, const std::vector<double>& v);
[[nodiscard]] std::vector<double> get_values(reader& r, std::string_view what);

// The next index of a sparse list (the entries with a count, in index
// order): below `size` and, after the first (k > 0), above `last`, which it
// becomes. Throws "WHAT: NOUN I out of order or range" otherwise.
std::uint64_t sparse_index(std::uint64_t i, std::uint64_t size, std::uint64_t k,
                           std::uint64_t& last, std::string_view what, std::string_view noun);

// ---- accumulators (accumulator_codec.cpp) ----
// The count, the mean (0 when empty: mean() is NaN then) and M2.
void put(writer& w, const mean_variance& m);
[[nodiscard]] mean_variance get_mean_variance(reader& r);
// The mean and M2 alone, where the count is written once for several.
void put_mean_m2(writer& w, const mean_variance& m);
void put(writer& w, const histogram& h);
[[nodiscard]] histogram get_histogram(reader& r);
// score_moments and causal_score_moments (accumulators/score_moments.hpp):
// the count, then the five sums in their fixed order; 48 bytes.
inline constexpr std::size_t five_sums_bytes = 8 + 5 * 8;
template <class Moments>
void put(writer& w, const five_sums<Moments>& m) {
  w.u64(m.count());
  for (int i = 0; i < 5; ++i) w.f64(m.sum(i));
}
template <class Moments>
Moments get_five_sums(reader& r, std::string_view what) {
  const auto count = r.u64(what);
  double sums[5];
  for (double& x : sums) x = r.f64(what);
  return Moments::from_raw(count, sums);
}
void put(writer& w, const sobol_moments& m);
[[nodiscard]] sobol_moments get_sobol_moments(reader& r);
void put(writer& w, const survival_counts& c);
[[nodiscard]] survival_counts get_survival_counts(reader& r, std::string_view name);

// ---- observe-time statistics (time_statistics_codec.cpp) ----
void put(writer& w, const time_statistics& t);
[[nodiscard]] time_statistics get_time_statistics(reader& r);

// ---- a point's statistics (statistics_codec.cpp) ----
void put(writer& w, const point_statistics& s);
[[nodiscard]] point_statistics get_statistics(reader& r);

// ---- a realization's record (record_codec.cpp) ----
// The fewest bytes a record takes (no drawn values): its table's fields
// and the count of drawn values.
[[nodiscard]] std::size_t record_bytes() noexcept;
void put(writer& w, const realization_record& x);
[[nodiscard]] realization_record get_record(reader& r);

}  // namespace stickslip::serial
