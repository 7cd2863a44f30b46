// The groups of statistics a sweep can compute (`sweep --statistics LIST`,
// TOML `[sweep] statistics = [...]`, Python `statistics=[...]`). `default`
// is what every sweep computes and is always on; each other group adds
// accumulators and outputs. The selection is part of a run's identity
// (sweep_spec::statistics: serialized, journaled, written to every output).
// One table of groups: parsing, messages and writers iterate it, so a new
// group (paper, family, derivatives) is one row and one flag.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace stickslip {

struct statistics_selection {
  // Kaplan-Meier survival of the stick and slip durations, with the episode
  // cut by t_a right-censored (survival_estimate.hpp).
  bool survival = false;
  friend bool operator==(const statistics_selection&, const statistics_selection&) = default;
};

struct statistics_group_info {
  const char* name;
  const char* description;
  bool statistics_selection::*flag;  // nullptr: always on (default)
};

inline constexpr std::array<statistics_group_info, 2> statistics_group_table{{
    {"default", "the statistics every sweep computes (always on)", nullptr},
    {"survival",
     "Kaplan-Meier survival of stick and slip durations with censoring at t_a",
     &statistics_selection::survival},
}};

// "default, survival, all": the names a list may hold.
[[nodiscard]] std::string statistics_group_names();
// A comma list of group names ("survival", "default,survival", "all"; spaces
// around names are ignored). Throws invalid_value naming `key`, the
// offending name and statistics_group_names() for an unknown or empty name.
[[nodiscard]] statistics_selection parse_statistics_selection(std::string_view key,
                                                              std::string_view list);
// The same for a list of names (TOML arrays, Python lists).
[[nodiscard]] statistics_selection parse_statistics_selection(
    std::string_view key, const std::vector<std::string>& names);
// The selected groups in table order: {"default"} or {"default", "survival"}.
[[nodiscard]] std::vector<std::string> selected_group_names(const statistics_selection& s);
// Those names joined by "," ("default,survival"): the form the outputs record.
[[nodiscard]] std::string to_string(const statistics_selection& s);
// As one byte (bit i = row i + 1 of the table) for serialization; from_bits
// returns false for bits that name no group.
[[nodiscard]] std::uint8_t to_bits(const statistics_selection& s) noexcept;
[[nodiscard]] bool from_bits(std::uint8_t bits, statistics_selection& s) noexcept;

}  // namespace stickslip
