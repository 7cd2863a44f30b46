// The one list of the fields of a realization's record (realization_record,
// point_accumulators.hpp). Everything that writes a record iterates over it, in this
// order: the record columns of records.csv, the "statistics" object of
// `simulate --format json`, the `record` dict of Python's Realization, and
// the journal's record layout. A new per-realization value is its field in
// realization_record, one row here, and the observer line that computes it.
// The per-point statistics built from these values are the rows of
// statistics_schema.hpp.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <variant>

#include "stickslip/point_accumulators.hpp"

namespace stickslip {

// Which outputs carry a field.
enum class record_role : unsigned char {
  // Which realization it is and the state it started from: records.csv;
  // simulate and Python report them as the initial conditions instead.
  identity,
  // What the realization did: records.csv, simulate's and Python's record.
  outcome,
  // Sums that only the estimates merge (the causal score's moments, the
  // switch-time sum): the journal only.
  internal,
};

// The field itself: a member of the record or of its event counts.
using record_member =
    std::variant<std::uint64_t realization_record::*, std::uint32_t realization_record::*,
                 int realization_record::*, double realization_record::*,
                 bool realization_record::*, std::uint64_t event_counts::*,
                 double event_counts::*>;

struct record_field {
  const char* name;         // records.csv column, simulate JSON and Python record key
  const char* symbol;       // the paper's symbol ("" if none); Python reads the field by it too
  const char* units;        // UDUNITS ("1" for a pure number or an index)
  const char* description;  // the full definition
  record_role role;
  record_member member;
  // Computed only with the family statistics (pieces of motion): records.csv
  // writes nan for it when the sweep did not compute them.
  bool needs_family = false;
  // Whether the realization has the value (nullptr: always). simulate's JSON
  // writes null where it has not; records.csv and Python keep the stored
  // marker (-1).
  bool (*exists)(const realization_record& r) noexcept = nullptr;
};

// The field `member` of record r (const or not).
template <class Record, class T>
constexpr auto& field_of(Record& r, T realization_record::*member) noexcept {
  return r.*member;
}
template <class Record, class T>
constexpr auto& field_of(Record& r, T event_counts::*member) noexcept {
  return r.events.*member;
}

// Calls f with a reference to the field `field` of record r (const or not),
// of the member's own type.
template <class Record, class F>
constexpr decltype(auto) visit_field(const record_field& field, Record& r, F&& f) {
  return std::visit([&](auto member) -> decltype(auto) { return f(field_of(r, member)); },
                    field.member);
}

namespace detail::record_rows {
using rr = realization_record;
using ec = event_counts;
inline bool first_stick(const realization_record& r) noexcept { return has_first_stick(r); }
}  // namespace detail::record_rows

// In the order of the journal's record layout (so that the table reproduces
// its bytes). A new row goes at the end: a last column of records.csv, a
// last field of the journal's records. Nothing else to bump: the layout id
// of every journal and message (layout_id, serial_bytes.hpp) hashes this
// table (record_layout_id), so older journals are recomputed, not misread.
inline constexpr std::array<record_field, 19> record_table{{
    {"realization", "r", "1", "index of the realization at its grid point, from 0",
     record_role::identity, &detail::record_rows::rr::realization},
    {"x0", "x_0", "m", "initial position x(0)", record_role::identity,
     &detail::record_rows::rr::x0},
    {"xdot0", "x'_0", "m/s", "initial velocity x'(0)", record_role::identity,
     &detail::record_rows::rr::xdot0},
    {"belt_start", "", "1",
     "the belt level at t = 0: +1 / -1 (first / second level) on a two-level belt, the level "
     "number 1..n on more",
     record_role::identity, &detail::record_rows::rr::belt_start},
    {"sticks", "S_T", "1",
     "number of sticks of positive length beginning in the window (a stick cut off by t_a "
     "counts)",
     record_role::outcome, &detail::record_rows::rr::sticks},
    {"slips", "S_L", "1",
     "number of slips beginning after the first stick (the slip before the first stick is "
     "not counted)",
     record_role::outcome, &detail::record_rows::rr::slips},
    {"stick_fraction", "R", "1", "total stick time in the window divided by its length",
     record_role::outcome, &detail::record_rows::rr::stick_fraction},
    {"first_stick_start", "T_1", "s", "start of the first stick; -1 when there is none",
     record_role::outcome, &detail::record_rows::rr::first_stick_start, false,
     &detail::record_rows::first_stick},
    {"first_stick_duration", "D_1", "s",
     "duration of the first stick (clipped by t_a when censored); -1 when there is none",
     record_role::outcome, &detail::record_rows::rr::first_stick_duration, false,
     &detail::record_rows::first_stick},
    {"first_stick_censored", "", "1", "whether the first stick is cut off by t_a",
     record_role::outcome, &detail::record_rows::rr::first_stick_censored},
    {"friction_power", "W_f", "W",
     "energy dissipated by kinetic friction in the window divided by its length",
     record_role::outcome, &detail::record_rows::rr::friction_power, true},
    {"damping_power", "W_c", "W",
     "energy dissipated by viscous damping in the window divided by its length",
     record_role::outcome, &detail::record_rows::rr::damping_power, true},
    {"stick_switch_moment", "", "s",
     "sum over the sticks of N(start) D_i: the integral of the switch count over the sticks",
     record_role::internal, &detail::record_rows::rr::stick_switch_moment},
    {"stick_time_moment", "", "s2",
     "sum over the sticks of (start + end)/2 D_i: the integral of t over the sticks",
     record_role::internal, &detail::record_rows::rr::stick_time_moment},
    {"belt_switches", "N", "1", "number of belt switches in [0, t_a]", record_role::outcome,
     &detail::record_rows::ec::belt_switches},
    {"stick_onsets", "", "1", "number of transitions slip -> stick in [0, t_a]",
     record_role::outcome, &detail::record_rows::ec::stick_onsets},
    {"stick_breaks", "", "1", "number of transitions stick -> slip in [0, t_a]", record_role::outcome,
     &detail::record_rows::ec::stick_breaks},
    {"slip_reversals", "", "1", "number of reversals of the slip direction without sticking in [0, t_a]", record_role::outcome,
     &detail::record_rows::ec::slip_reversals},
    {"switch_time_sum", "", "s", "sum of the belt switch times in [0, t_a]",
     record_role::internal, &detail::record_rows::ec::switch_time_sum},
}};

// A 64-bit identity of a record layout: FNV-1a over each field's name and
// its member's type (and whether it is one of the event counts), in order.
// The serialized layout's identity (serial_bytes.hpp, layout_id) includes
// record_table's, so journal records laid out by another table are refused
// instead of misread.
[[nodiscard]] std::uint64_t record_layout_id(std::span<const record_field> fields) noexcept;

// The rows of one role, in table order.
template <class F>
void for_each_record_field(record_role role, F&& f) {
  for (const auto& field : record_table)
    if (field.role == role) f(field);
}

// The field whose name or symbol is `key`; nullptr if none.
[[nodiscard]] inline const record_field* find_record_field(std::string_view key) noexcept {
  for (const auto& field : record_table)
    if (key == field.name || (*field.symbol && key == field.symbol)) return &field;
  return nullptr;
}

}  // namespace stickslip
