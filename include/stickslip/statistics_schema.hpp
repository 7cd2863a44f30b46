// The one list of per-point statistics. Everything that handles statistics
// iterates over it: point_statistics (the histogram ranges, add, merge), the
// binary serialization (MPI messages, the journal), and every writer (NetCDF,
// JSON, CSV); the Python layer reads it too. Adding a statistic is one entry
// in src/core/statistics_schema.cpp plus its accumulator member in
// point_statistics (statistics.hpp), and its tests.
//
// Two kinds of rows:
//   quantity  a value of a realization (R, S_T/t_a, S_L/t_a, D_i, D_1, H_i),
//             accumulated as mean/variance and, when binned, as a histogram;
//   counter   an integer summed over realizations (no-stick realizations,
//             censored first sticks, events by kind).
// The paper's definitions are in statistics.hpp and docs/model.md.
#pragma once
#include <cstdint>
#include <span>

#include "stickslip/statistics.hpp"

namespace stickslip {

// Which values of one realization a quantity takes.
enum class sampling : unsigned char {
  per_realization,             // one value per realization: value(record, t_a)
  per_realization_with_stick,  // one value per realization with a stick: value(record, t_a)
  per_stick,                   // the duration of every stick, pooled over realizations
  per_counted_slip,            // the duration of every counted slip, pooled
};

// The interval a quantity's histogram bins, per grid point.
enum class histogram_range : unsigned char {
  none,            // not binned
  unit_interval,   // [0, 1]
  stick_duration,  // [0, d_max], d_max = 2 mu m g / (k V) (or histogram_spec::stick_duration_max)
  slip_duration,   // [0, min(t_a, 5 / lambda)] (or histogram_spec::slip_duration_max)
};

struct quantity_info {
  const char* name;          // results.nc prefix: "<name>_mean", "<name>_density", ...
  const char* summary_name;  // summary.json key and summary.csv column prefix
  const char* symbol;        // the paper's symbol
  const char* units;         // UDUNITS ("1" for a pure number)
  const char* long_name;     // a few words, short enough for a plot label
  const char* description;   // the full definition
  const char* counted;       // what "<name>_count" counts
  sampling sampled;
  // The value of one realization, for the per_realization* samplings (else nullptr).
  double (*value)(const realization_record& r, double window) noexcept;
  mean_variance point_statistics::*moments;
  histogram point_statistics::*density;  // nullptr when range == none
  histogram_range range;
};

struct counter_info {
  const char* name;          // results.nc variable
  const char* summary_name;  // summary.json key and summary.csv column
  const char* group;         // summary.json object holding it ("events"), or nullptr
  const char* long_name;     // a few words, short enough for a plot label
  const char* description;
  // How much one realization adds.
  std::uint64_t (*increment)(const realization_record& r) noexcept;
  std::uint64_t& (*of)(point_statistics& s) noexcept;
  [[nodiscard]] std::uint64_t value(const point_statistics& s) const noexcept {
    return of(const_cast<point_statistics&>(s));
  }
};

[[nodiscard]] std::span<const quantity_info> quantities() noexcept;
[[nodiscard]] std::span<const counter_info> counters() noexcept;

// A 64-bit identity of the schema (FNV-1a over every row's names, sampling
// and range, in order). Serialized data carries it (in serialize.hpp's
// layout_id), so data written with another list of statistics is refused
// instead of misread.
[[nodiscard]] std::uint64_t statistics_schema_id() noexcept;

// The upper end of a quantity's histogram interval at a grid point (the lower
// end is 0). Precondition: range != none.
[[nodiscard]] double histogram_upper(histogram_range range, const model_parameters& p,
                                     const histogram_spec& h) noexcept;

}  // namespace stickslip
