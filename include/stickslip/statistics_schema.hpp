// The one list of per-point statistics. Everything that handles statistics
// iterates over it: point_statistics (the histogram ranges, add, merge), the
// binary serialization (MPI messages, the journal), and every writer (NetCDF,
// JSON, CSV); the Python layer reads it too. A statistic of a value the
// realization record already holds is one row in the table below plus its
// accumulator member in point_accumulators (point_accumulators.hpp), and its tests; a
// new per-realization value also needs its field in realization_record and
// the observer line that computes it. The order of the rows is the order of
// the serialized accumulators and of the output columns.
// The estimates derived from these accumulators (likelihood-ratio
// derivatives, control variates, CRN slopes) are the rows of estimates.hpp.
// Outside the table, each written by hand: the causal score of R
// (point_accumulators::stick_fraction_causal_score; its estimate is a row of
// estimates.hpp), the observe-time
// statistics (point_accumulators::observed, accumulators/time_statistics.hpp)
// and the convergence trace.
//
// Five kinds of rows:
//   quantity  a value of a realization (R, S_T/t_a, S_L/t_a, D_i, D_1, H_i,
//             X_i, W_f, W_c), accumulated as mean/variance and, when binned,
//             as a histogram;
//   level quantity  one value per belt level of a realization (P_j),
//             accumulated as mean/variance per level (the dimension
//             belt_level of results.nc);
//   joint histogram  two binned per-stick quantities of the same sticks
//             (D_i, X_i), counted together in the binnings of their 1-D
//             histograms;
//   counter   an integer summed over realizations (no-stick realizations,
//             censored first sticks, events by kind);
//   survival law  the durations of the sticks or of the counted slips,
//             binned as ended or censored by t_a (the survival group, off
//             unless selected: sweep_spec::statistics).
// The paper's definitions are in statistics.hpp and docs/model.md.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stickslip/parameters.hpp"
#include "stickslip/point_accumulators.hpp"

namespace stickslip {

// Which values of one realization a quantity takes.
enum class sampling : unsigned char {
  per_realization,             // one value per realization: value(record, t_a)
  per_realization_with_stick,  // one value per realization with a stick: value(record, t_a)
  per_stick,                   // the duration of every stick, pooled over realizations
  per_counted_slip,            // the duration of every counted slip, pooled
  per_stick_onset,             // the onset position of every stick, pooled
};
// One value per realization (a mean over realizations), not pooled.
[[nodiscard]] constexpr bool per_realization(sampling s) noexcept {
  return s == sampling::per_realization || s == sampling::per_realization_with_stick;
}

// The interval a quantity's histogram bins, per grid point.
enum class histogram_range : unsigned char {
  none,            // not binned
  unit_interval,   // [0, 1]
  stick_duration,  // [0, d_max], d_max = 2 mu m g / (k V) (or histogram_spec::stick_duration_max)
  slip_duration,   // [0, min(t_a, 5 / lambda)] (or histogram_spec::slip_duration_max)
  stick_band,      // [-b, b], b = a_s + c max|v_i| / k: every x where a stick can start
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
  mean_variance point_accumulators::*moments;
  histogram point_accumulators::*density;  // nullptr when range == none
  histogram_range range;
  // Moments against the belt switch count (score derivative d mean/dlambda
  // and control-variate mean, accumulators/score_moments.hpp); nullptr for
  // the pooled and conditional quantities (not one value per realization).
  score_moments point_accumulators::*score = nullptr;
  // The same against the scores of a two-level belt's rates r1, r2.
  std::array<score_moments, 2> point_accumulators::*rate_score = nullptr;
  // The same against the scores of a generator's entries q_ij (n x n).
  std::vector<score_moments> point_accumulators::*generator_score = nullptr;
};

struct counter_info {
  const char* name;          // results.nc variable
  const char* summary_name;  // summary.json key and summary.csv column
  const char* group;         // summary.json object holding it ("events"), or nullptr
  const char* long_name;     // a few words, short enough for a plot label
  const char* description;
  // How much one realization adds.
  std::uint64_t (*increment)(const realization_record& r) noexcept;
  std::uint64_t& (*of)(point_accumulators& s) noexcept;
  [[nodiscard]] std::uint64_t value(const point_accumulators& s) const noexcept {
    return of(const_cast<point_accumulators&>(s));
  }
};

// A value per belt level of each realization.
struct level_quantity_info {
  const char* name;          // results.nc prefix: "<name>_mean" over (grid, belt_level), ...
  const char* summary_name;  // summary.json key (an array over levels), summary.csv prefix
  const char* symbol;
  const char* units;
  const char* long_name;
  const char* description;
  std::vector<mean_variance> point_accumulators::*moments;  // one per level
};

// A joint histogram of two binned quantities sampled per stick (indices into
// quantity_table), in their binnings.
struct joint_histogram_info {
  const char* name;          // results.nc "<name>_counts" over (grid, bin, bin_y)
  const char* summary_name;  // summary.json key (nested array [x bin][y bin])
  const char* long_name;
  const char* description;
  std::size_t x, y;           // rows of quantity_table
  sampling x_sampled, y_sampled;
  histogram2d point_accumulators::*counts;
};

// A duration law with right censoring (the survival group, --statistics
// survival): the counts of ended and censored episodes on the survival grid
// (survival_spec) and their Kaplan-Meier estimate (survival_estimate.hpp).
struct survival_info {
  const char* name;         // results.nc "<name>_survival", "<name>_at_risk", ...
  const char* coordinate;   // the duration coordinate and dimension of the curve
  const char* symbol;       // the paper's symbol of the duration
  const char* episodes;     // which episodes are counted
  sampling sampled;         // per_stick or per_counted_slip
  double survival_spec::*upper;  // the end of the grid
  survival_counts point_accumulators::*counts;
};

namespace detail::schema {
using ps = point_accumulators;
using rec = const realization_record&;

inline constexpr std::array<quantity_info, 9> quantity_table{{
    {"stick_fraction", "R", "R", "1", "stick fraction",
     "total stick time in [0, t_a] divided by t_a, one value per realization", "realizations",
     sampling::per_realization, [](rec r, double) noexcept { return r.stick_fraction; },
     &ps::stick_fraction, &ps::stick_fraction_hist, histogram_range::unit_interval,
     &ps::stick_fraction_score, &ps::stick_fraction_rate_score,
     &ps::stick_fraction_generator_score},
    {"sticks_per_time", "sticks_per_time", "S_T/t_a", "1/s", "stick rate",
     "number of sticks of positive length beginning in [0, t_a) (a stick cut off by t_a "
     "counts), divided by t_a, one value per realization",
     "realizations", sampling::per_realization,
     [](rec r, double window) noexcept { return r.sticks / window; }, &ps::sticks_per_time,
     nullptr, histogram_range::none, &ps::sticks_per_time_score, &ps::sticks_per_time_rate_score,
     &ps::sticks_per_time_generator_score},
    {"slips_per_time", "slips_per_time", "S_L/t_a", "1/s", "slip rate",
     "number of slips beginning after the first stick (the slip before the first stick is "
     "not counted), divided by t_a, one value per realization",
     "realizations", sampling::per_realization,
     [](rec r, double window) noexcept { return r.slips / window; }, &ps::slips_per_time,
     nullptr, histogram_range::none, &ps::slips_per_time_score, &ps::slips_per_time_rate_score,
     &ps::slips_per_time_generator_score},
    {"stick_duration", "stick_duration", "D", "s", "stick duration",
     "duration D_i of every stick, pooled over all sticks of all realizations (a stick cut "
     "off by t_a enters clipped)",
     "sticks, over all realizations", sampling::per_stick, nullptr, &ps::stick_duration,
     &ps::stick_duration_hist, histogram_range::stick_duration, nullptr},
    {"first_stick_duration", "first_stick_duration", "D_1", "s", "first stick duration",
     "duration of the first stick, over the realizations that have a stick (see "
     "no_stick_count); it may be censored by t_a (see first_stick_censored_count)",
     "realizations with at least one stick", sampling::per_realization_with_stick,
     [](rec r, double) noexcept { return r.first_stick_duration; }, &ps::first_stick_duration,
     &ps::first_stick_duration_hist, histogram_range::stick_duration, nullptr},
    {"slip_duration", "slip_duration", "H", "s", "slip duration",
     "duration H_i of every counted slip (those beginning after the first stick), pooled "
     "over all realizations",
     "counted slips, over all realizations", sampling::per_counted_slip, nullptr,
     &ps::slip_duration, &ps::slip_duration_hist, histogram_range::slip_duration, nullptr},
    {"stick_onset_position", "stick_onset_position", "X", "m", "stick-onset position",
     "position x of the mass at the start of every stick of positive length (a stick at "
     "t = 0 starts at x0), pooled over all sticks of all realizations; it lies in the stick "
     "band |x + c v / k| <= a_s",
     "sticks, over all realizations", sampling::per_stick_onset, nullptr,
     &ps::stick_onset_position, &ps::stick_onset_position_hist, histogram_range::stick_band},
    {"friction_power", "friction_power", "W_f", "W", "friction power",
     "energy dissipated by kinetic friction over [0, t_a] divided by t_a: (1/t_a) times the "
     "integral over the slips of mu_k m g |v - x'| dt, one value per realization",
     "realizations", sampling::per_realization,
     [](rec r, double) noexcept { return r.friction_power; }, &ps::friction_power, nullptr,
     histogram_range::none},
    {"damping_power", "damping_power", "W_c", "W", "damping power",
     "energy dissipated by viscous damping over [0, t_a] divided by t_a: (1/t_a) times the "
     "integral of c x'^2 dt (0 without damping), one value per realization",
     "realizations", sampling::per_realization,
     [](rec r, double) noexcept { return r.damping_power; }, &ps::damping_power, nullptr,
     histogram_range::none},
}};

// The row of quantity_table whose `name` is `name`: tables and code name
// rows, never number them. A name that is no row does not compile (the
// throw is not a constant expression).
consteval std::size_t quantity_row(std::string_view name) {
  for (std::size_t i = 0; i < quantity_table.size(); ++i)
    if (name == quantity_table[i].name) return i;
  throw "quantity_row: no row of quantity_table has this name";
}

inline constexpr std::array<level_quantity_info, 1> level_table{{
    {"belt_level_fraction", "belt_level_fraction", "P", "1", "level time fraction",
     "fraction of [0, t_a] that the belt spends at each level v_j, one value per level and "
     "realization (the values of a realization sum to 1)",
     &ps::level_fraction},
}};

inline constexpr std::array<joint_histogram_info, 1> joint_table{{
    {"stick_duration_onset", "stick_duration_onset_counts", "sticks by D and X",
     "joint counts of the stick duration D_i (first dimension, the bins of "
     "stick_duration) and the stick-onset position X_i (second dimension, the bins of "
     "stick_onset_position) of every stick",
     quantity_row("stick_duration"), quantity_row("stick_onset_position"), sampling::per_stick,
     sampling::per_stick_onset, &ps::stick_duration_onset},
}};

inline constexpr std::array<counter_info, 6> counter_table{{
    {"no_stick_count", "no_stick", nullptr, "no-stick realizations",
     "realizations with no stick of positive length in [0, t_a) (no D_1)",
     [](rec r) noexcept -> std::uint64_t { return !has_first_stick(r); },
     [](ps& s) noexcept -> std::uint64_t& { return s.no_stick; }},
    {"first_stick_censored_count", "first_stick_censored", nullptr, "censored first sticks",
     "realizations whose first stick was still going on at t_a (D_1 clipped)",
     [](rec r) noexcept -> std::uint64_t { return r.sticks > 0 && r.first_stick_censored; },
     [](ps& s) noexcept -> std::uint64_t& { return s.first_stick_censored; }},
    {"belt_switches", "belt_switches", "events", "belt switches",
     "belt direction switches, summed over realizations",
     [](rec r) noexcept { return r.events.belt_switches; },
     [](ps& s) noexcept -> std::uint64_t& { return s.events.belt_switches; }},
    {"stick_onsets", "stick_onsets", "events", "stick onsets",
     "transitions slip -> stick, summed over realizations",
     [](rec r) noexcept { return r.events.stick_onsets; },
     [](ps& s) noexcept -> std::uint64_t& { return s.events.stick_onsets; }},
    {"stick_breaks", "stick_breaks", "events", "stick breaks",
     "transitions stick -> slip, summed over realizations",
     [](rec r) noexcept { return r.events.stick_breaks; },
     [](ps& s) noexcept -> std::uint64_t& { return s.events.stick_breaks; }},
    {"slip_reversals", "slip_reversals", "events", "slip reversals",
     "reversals of the slip direction without sticking, summed over realizations",
     [](rec r) noexcept { return r.events.slip_reversals; },
     [](ps& s) noexcept -> std::uint64_t& { return s.events.slip_reversals; }},
}};

inline constexpr std::array<survival_info, 2> survival_table{{
    {"stick", "stick_duration", "D",
     "every stick of positive length (those of stick_duration); the stick still going on at "
     "t_a is censored at the duration it had reached",
     sampling::per_stick, &survival_spec::stick_duration_max, &ps::stick_survival},
    {"slip", "slip_duration", "H",
     "every counted slip (those of slip_duration: beginning after the first stick); the slip "
     "still going on at t_a is censored at the duration it had reached",
     sampling::per_counted_slip, &survival_spec::slip_duration_max, &ps::slip_survival},
}};

}  // namespace detail::schema

// The rows. The tables are constexpr so that point_statistics::add can
// iterate them at compile time (no indirect call per realization).
inline constexpr const auto& quantity_table = detail::schema::quantity_table;
inline constexpr const auto& counter_table = detail::schema::counter_table;
inline constexpr const auto& level_table = detail::schema::level_table;
using detail::schema::quantity_row;
// The first rows of quantity_table are the paper's; the family's
// (sweep_spec::family_statistics) begin at the stick-onset position, and the
// level and joint rows are the family's too.
inline constexpr std::size_t paper_quantity_count = quantity_row("stick_onset_position");
inline constexpr const auto& joint_table = detail::schema::joint_table;
static_assert(
    [] {
      for (const auto& j : joint_table)
        if (quantity_table[j.x].sampled != j.x_sampled ||
            quantity_table[j.y].sampled != j.y_sampled || !quantity_table[j.x].density ||
            !quantity_table[j.y].density)
          return false;
      return true;
    }(),
    "a joint histogram's two rows have histograms and are sampled as it says");
[[nodiscard]] inline std::span<const quantity_info> quantities() noexcept { return quantity_table; }
[[nodiscard]] inline std::span<const counter_info> counters() noexcept { return counter_table; }
[[nodiscard]] inline std::span<const level_quantity_info> level_quantities() noexcept {
  return level_table;
}
[[nodiscard]] inline std::span<const joint_histogram_info> joint_histograms() noexcept {
  return joint_table;
}
[[nodiscard]] inline std::span<const survival_info> survival_laws() noexcept {
  return detail::schema::survival_table;
}

// The statistics whose mean the precision tools aim at (`sweep --target-ci
// STAT:H`, `peak --statistic STAT`, Python's target_ci and statistic): the
// quantities with one value per realization (per_realization), in table
// order. One list, so that every command's help and errors name the same
// statistics: mean_statistic_names() is their summary names joined by ", "
// ("R, sticks_per_time, ..."), and find_mean_statistic() finds one by its
// summary name, name or symbol (nullptr if it is not in the list).
[[nodiscard]] std::string mean_statistic_names();
[[nodiscard]] const quantity_info* find_mean_statistic(std::string_view name) noexcept;

// A 64-bit identity of the schema (FNV-1a over every row's names, sampling
// and range, in order). Serialized data carries it (in serialize.hpp's
// layout_id), so data written with another list of statistics is refused
// instead of misread.
[[nodiscard]] std::uint64_t statistics_schema_id() noexcept;

// d mean/dr_j (j = 0: r1, 1: r2) of a quantity with rate scores, by the
// likelihood ratio of a two-level belt's own rates (belt_rate_scores,
// docs/precision.md); NaN where the point has no such rates, the family
// statistics were off, or a burn-in cut the window (the scores need the
// time at each level over all of [0, t_a]).
[[nodiscard]] estimate belt_rate_derivative(const point_accumulators& s, const quantity_info& q,
                                            std::size_t j) noexcept;
// d mean/dq_ij (i != j, 0-based levels) of a quantity with generator scores,
// by the likelihood ratio of the belt's generator (belt_generator_scores,
// docs/precision.md); NaN where the point's belt has no generator of its
// own, q_ij = 0, i = j, the family statistics were off, or a burn-in cut
// the window.
[[nodiscard]] estimate belt_generator_derivative(const point_accumulators& s,
                                                 const quantity_info& q, std::size_t i,
                                                 std::size_t j) noexcept;

// The ends of a quantity's histogram interval at a grid point (the lower end
// is 0 but for stick_band). Precondition: range != none.
[[nodiscard]] double histogram_lower(histogram_range range, const model_parameters& p,
                                     const histogram_spec& h) noexcept;
[[nodiscard]] double histogram_upper(histogram_range range, const model_parameters& p,
                                     const histogram_spec& h) noexcept;

}  // namespace stickslip
