#include "stickslip/statistics_groups.hpp"

#include "stickslip/error.hpp"

namespace stickslip {
namespace {

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// Adds the group `name` (or all of them) to `s`.
void select(std::string_view key, std::string_view name, statistics_selection& s) {
  if (name == "all") {
    for (const auto& g : statistics_group_table)
      if (g.flag) s.*g.flag = true;
    return;
  }
  for (const auto& g : statistics_group_table)
    if (name == g.name) {
      if (g.flag) s.*g.flag = true;
      return;
    }
  throw invalid_value(std::string(key), std::string(name),
                      "a comma list of " + statistics_group_names());
}

}  // namespace

std::string statistics_group_names() {
  std::string out;
  for (const auto& g : statistics_group_table) out += std::string(g.name) + ", ";
  return out + "all";
}

statistics_selection parse_statistics_selection(std::string_view key, std::string_view list) {
  statistics_selection s;
  std::size_t from = 0;
  while (true) {
    const auto comma = list.find(',', from);
    select(key, trimmed(list.substr(from, comma - from)), s);
    if (comma == std::string_view::npos) return s;
    from = comma + 1;
  }
}

statistics_selection parse_statistics_selection(std::string_view key,
                                                const std::vector<std::string>& names) {
  statistics_selection s;
  for (const auto& n : names) select(key, trimmed(n), s);
  return s;
}

std::vector<std::string> selected_group_names(const statistics_selection& s) {
  std::vector<std::string> out;
  for (const auto& g : statistics_group_table)
    if (!g.flag || s.*g.flag) out.emplace_back(g.name);
  return out;
}

std::string to_string(const statistics_selection& s) {
  std::string out;
  for (const auto& n : selected_group_names(s)) out += (out.empty() ? "" : ",") + n;
  return out;
}

std::uint8_t to_bits(const statistics_selection& s) noexcept {
  std::uint8_t bits = 0;
  for (std::size_t i = 1; i < statistics_group_table.size(); ++i)
    if (s.*statistics_group_table[i].flag) bits |= static_cast<std::uint8_t>(1u << (i - 1));
  return bits;
}

bool from_bits(std::uint8_t bits, statistics_selection& s) noexcept {
  s = {};
  for (std::size_t i = 1; i < statistics_group_table.size(); ++i)
    if (bits & (1u << (i - 1))) s.*statistics_group_table[i].flag = true;
  return to_bits(s) == bits;
}

}  // namespace stickslip
