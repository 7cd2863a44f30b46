// The one list of derived estimates: the numbers a point's accumulators give
// beyond the statistics themselves (and, for the common-random-number
// slopes, the records of its neighbours on an axis), each a value with a
// standard error and the 95 % interval value +- z95 x standard error. The
// writers only map its rows: results.nc (and so Python's Dataset, which is
// results.nc read back), summary.json and summary.csv iterate the table
// below, so they carry the same estimates; a new derived estimate is one row
// here (and its accumulator, if it needs one). No I/O.
//
// Each row is one kind of estimate, per quantity of the statistics schema
// (statistics_schema.hpp) that has it and, by the row's index, per belt rate
// r_j, per generator entry q_ij or per swept axis:
//   dmean_dlambda         likelihood-ratio d mean/d lambda (Poisson switching)
//   dmean_dlambda_causal  R's causal-score d mean/d lambda (Poisson switching)
//   control_variate       each mean with the belt switch count as control
//   dmean_drates          likelihood-ratio d mean/d r_j (a two-level belt
//                         given its own rates)
//   dmean_dgenerator      likelihood-ratio d mean/d q_ij (a belt given by its
//                         generator)
//   crn_slopes            common-random-number slope over each swept axis
//                         (--common-random-numbers with records)
// The estimators are derived in accumulators/score_moments.hpp,
// statistics_schema.hpp (belt_rate_derivative, belt_generator_derivative) and
// precision/crn_slopes.hpp; docs/precision.md.
//
// The 95 % interval of each statistic's mean (X_ci95_low/_high, "ci95") is
// mean_estimate below: it sits beside the statistic's std and count in every
// output, which the statistics schema lays out.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stickslip/accumulators/score_moments.hpp"
#include "stickslip/statistics_groups.hpp"
#include "stickslip/statistics_schema.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip {

// The mean of a statistic with its standard error std / sqrt(n): the normal
// approximation interval mean +- 1.959963984540054 std / sqrt(n) that every
// output gives beside a mean.
[[nodiscard]] inline estimate mean_estimate(const mean_variance& m) noexcept {
  return {m.mean(), m.std_error()};
}

// A common-random-number slope of a per-realization mean over a swept axis
// at one point (computed by precision::crn_slopes from the records).
struct crn_slope {
  std::size_t axis = 0;                  // index into spec.axes
  const quantity_info* quantity = nullptr;
  std::size_t from = 0, to = 0;          // the two points differenced
  estimate slope;                        // d mean / d axis
  std::uint64_t pairs = 0;               // realizations paired
};

// What an estimate runs over besides the quantity.
enum class estimate_index : unsigned char {
  none,             // one per quantity
  belt_rate,        // j = 0, 1: the rates r1, r2 of a two-level belt
  generator_entry,  // i n + j: the entry q_ij of the belt's n x n generator
  axis,             // k: each swept axis with at least two values
};

// A member some estimates carry beside the value, its error and interval.
enum class estimate_extra : unsigned char {
  none,
  variance_reduction,  // the control variate's Var(X) / residual variance
  pairs,               // the realizations a CRN slope paired
};

struct estimate_value {
  estimate value;
  double variance_reduction = NAN;  // estimate_extra::variance_reduction
  std::uint64_t pairs = 0;          // estimate_extra::pairs
};

// What an estimate is computed from: one point of a sweep and, with common
// random numbers and records, that point's CRN slopes (empty otherwise).
struct estimate_source {
  const sweep_spec& spec;
  const point_result& point;
  std::span<const crn_slope> crn_slopes;
};

// One row. Texts may hold {sym} (the quantity's symbol) and {i} (the
// index's name: r1, an axis symbol); results.nc's names hold {q} (the
// quantity's results.nc name) and {i}.
struct estimate_info {
  const char* name;          // summary.json key of the estimates of this kind
  // results.nc: the estimate is "<variable><value_suffix>" ("{q}_cv" +
  // "_mean"), its interval "<variable>_ci95_low" and "_ci95_high", its extra
  // "<variable>_<extra>". A generator entry's estimates are one variable
  // over (grid, belt_level, belt_level_to).
  const char* variable;
  const char* value_suffix;
  const char* value_member;  // summary.json member of the value: "value" or "mean"
  estimate_index index;
  estimate_extra extra;
  bool statistics_selection::*group;  // the selection group that enables it
  // long_name: "<label> <sym><tail>", "<label> low <sym><tail>", ...
  // (within xarray's 30 characters for the schema's symbols).
  const char* label;
  const char* tail;
  // description: "<value_intro><definition>" for the value and
  // "<value_member> -/+ 1.96 x <error>; <definition>" for the interval.
  const char* value_intro;
  const char* error;
  const char* definition;
  // The units of the estimate of q; `per` is the units of the index (of the
  // axis for CRN slopes, 1/s otherwise).
  std::string (*units)(const quantity_info& q, std::string_view per);
  // Which quantities have it (before the selection).
  bool (*has)(const quantity_info& q) noexcept;
  // Whether the point has estimates of this kind (e.g. Poisson switching).
  bool (*applies)(const estimate_source& s) noexcept;
  // The estimate of q at index i of the point, or nothing where it does not
  // exist (the row does not apply at the point, q_ii, q_ij = 0, no slope of
  // q over that axis). Precondition: has(q).
  std::optional<estimate_value> (*at)(const estimate_source& s, const quantity_info& q,
                                      std::size_t i) noexcept;
};

[[nodiscard]] std::span<const estimate_info> estimate_kinds() noexcept;
// The source of every point of rs, in point order; `slopes` is
// precision::crn_slopes(rs) (one list per point, or empty without CRN).
[[nodiscard]] std::vector<estimate_source> estimate_sources(
    const result_set& rs, const std::vector<std::vector<crn_slope>>& slopes);
// The row named `name` (throws std::out_of_range for none).
[[nodiscard]] const estimate_info& estimate_kind(std::string_view name);

// Whether the selection enables some row (the group of each row).
[[nodiscard]] bool selects_estimates(const statistics_selection& s) noexcept;
// Whether `row` is written for quantity q under the selection s: the row's
// group and q are selected, and q has the row.
[[nodiscard]] bool selects(const statistics_selection& s, const estimate_info& row,
                           const quantity_info& q) noexcept;

// The indices of `row` over the spec (generator entries: all n x n of the
// base's belt, at() leaves out i = j and q_ij = 0).
[[nodiscard]] std::vector<std::size_t> estimate_indices(const estimate_info& row,
                                                        const sweep_spec& spec);
// The name of index i: "r1", "r2", an axis's symbol, "q_ij"; "" for none.
[[nodiscard]] std::string estimate_index_name(const estimate_info& row, const sweep_spec& spec,
                                              std::size_t i);

// The name of the estimate of a quantity at index name `index`, the
// quantity named as the output names it (results.nc: its name,
// "stick_fraction_dmean_dr1"; summary.csv: its summary name, "R_dmean_dr1").
[[nodiscard]] std::string estimate_variable(const estimate_info& row, std::string_view quantity,
                                            std::string_view index);
// Texts of the estimate of q at index name `index`. `side` is 0 for the
// value, -1 and +1 for the ends of the interval.
[[nodiscard]] std::string estimate_long_name(const estimate_info& row, const quantity_info& q,
                                             std::string_view index, int side);
[[nodiscard]] std::string estimate_description(const estimate_info& row, const quantity_info& q,
                                               std::string_view index, int side);
[[nodiscard]] std::string estimate_units(const estimate_info& row, const quantity_info& q,
                                         std::string_view index);

// The extra's results.nc suffix ("_variance_reduction", "_pairs") and
// summary.json member ("variance_reduction", "pairs"), its long_name and
// description; "" for none.
[[nodiscard]] const char* extra_name(estimate_extra e) noexcept;
[[nodiscard]] std::string extra_long_name(const estimate_info& row, const quantity_info& q,
                                          std::string_view index);
[[nodiscard]] std::string extra_description(const estimate_info& row, const quantity_info& q,
                                            std::string_view index);

}  // namespace stickslip
