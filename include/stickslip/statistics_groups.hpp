// What a sweep computes and writes (`sweep --statistics LIST`, TOML
// `[sweep] statistics = [...]`, Python `statistics=[...]`): groups of the
// statistics schema (statistics_schema.hpp), and single rows by name.
//   paper        R, S_T/t_a, S_L/t_a, D, D_1, H: moments and histograms
//   family       X, the joint (D, X) histogram, P_j, W_f, W_c
//   derivatives  the likelihood-ratio derivatives (d/dlambda, d/dr_j,
//                d/dq_ij, the causal score of R) and the control variates
//   survival     Kaplan-Meier of the stick and slip durations
//   default      paper (what a sweep computes without the flag)
//   all          every group
// and any row by name or symbol (R, stick_duration, D, ...): its moments,
// and its histogram when the engine fills histograms. The counters (no-stick
// realizations, censored first sticks, events) are always written.
// The selection decides the engine's work (apply_statistics_selection in
// sweep.hpp): unselected family statistics and histograms cost nothing in
// the lanes. It is part of a run's identity (serialized, journaled, written
// to every output). One table of groups: parsing, messages and writers
// iterate it.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace stickslip {

struct quantity_info;
struct level_quantity_info;

struct statistics_selection {
  bool paper = true;
  bool family = false;
  bool derivatives = false;
  // Kaplan-Meier survival of the stick and slip durations, with the episode
  // cut by t_a right-censored (survival_estimate.hpp).
  bool survival = false;
  // Rows selected one by one (their schema `name`: stick_fraction,
  // belt_level_fraction, ...), in table order, none in a selected group.
  std::vector<std::string> rows;
  friend bool operator==(const statistics_selection&, const statistics_selection&) = default;
};

struct statistics_group_info {
  const char* name;
  const char* description;
  bool statistics_selection::*flag;
};

inline constexpr std::array<statistics_group_info, 4> statistics_group_table{{
    {"paper", "R, S_T/t_a, S_L/t_a, D, D_1, H: means, CIs and histograms",
     &statistics_selection::paper},
    {"family", "X, the joint (D, X) histogram, the belt level fractions P_j, W_f, W_c",
     &statistics_selection::family},
    {"derivatives",
     "likelihood-ratio derivatives of the means (d/dlambda, d/dr_j, d/dq_ij, causal) and "
     "control-variate means",
     &statistics_selection::derivatives},
    {"survival", "Kaplan-Meier survival of stick and slip durations with censoring at t_a",
     &statistics_selection::survival},
}};

// "paper, family, derivatives, survival, default, all, or statistics by name
// (R, ...)": what a list may hold, for messages.
[[nodiscard]] std::string statistics_group_names();
// "paper (R, ...), family (...), ...": each group with its description.
[[nodiscard]] std::string statistics_group_descriptions();
// A comma list of group and row names ("paper,survival", "R", "all"; spaces
// around names are ignored). Throws invalid_value naming `key`, the
// offending name and what is allowed, for an unknown or empty name.
[[nodiscard]] statistics_selection parse_statistics_selection(std::string_view key,
                                                              std::string_view list);
// The same for a list of names (TOML arrays, Python lists), each of which may
// be a comma list itself; an empty list is the default selection.
[[nodiscard]] statistics_selection parse_statistics_selection(
    std::string_view key, const std::vector<std::string>& names);
// The selected groups in table order, then the rows: {"paper"},
// {"paper", "survival"}, {"stick_fraction"}.
[[nodiscard]] std::vector<std::string> selected_group_names(const statistics_selection& s);
// Those names joined by "," ("paper,survival"): the form the outputs record.
[[nodiscard]] std::string to_string(const statistics_selection& s);
// The groups as one byte (bit i = row i of the table) for serialization;
// from_bits returns false for bits that name no group.
[[nodiscard]] std::uint8_t to_bits(const statistics_selection& s) noexcept;
[[nodiscard]] bool from_bits(std::uint8_t bits, statistics_selection& s) noexcept;
// Whether `rows` is a canonical row list (known names, table order, none in
// a selected group): the deserializer's check.
[[nodiscard]] bool canonical_rows(const statistics_selection& s);

// What the writers write: a quantity's moments (and histogram, when filled),
// the level fractions, the joint histogram, the derivative estimates.
[[nodiscard]] bool selects(const statistics_selection& s, const quantity_info& q) noexcept;
[[nodiscard]] bool selects(const statistics_selection& s, const level_quantity_info& l) noexcept;
[[nodiscard]] bool selects_joint_histograms(const statistics_selection& s) noexcept;
[[nodiscard]] bool selects_derivatives(const statistics_selection& s) noexcept;

// What the engines must compute for it: the family statistics (onset
// positions, pieces of motion, the causal score), and whether the means of
// the per-realization quantities are all that is asked (no pooled
// durations, no histograms).
[[nodiscard]] bool needs_family_statistics(const statistics_selection& s) noexcept;
[[nodiscard]] bool needs_means_only(const statistics_selection& s) noexcept;

}  // namespace stickslip
