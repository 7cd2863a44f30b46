#include "stickslip/statistics_groups.hpp"

#include <algorithm>

#include "stickslip/error.hpp"
#include "stickslip/statistics_schema.hpp"

namespace stickslip {
namespace {

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// The schema rows a name can select: the quantities, then the level rows.
// Their `name` is the canonical form (selection.rows).
struct row_ref {
  const char* name;
  bool family;  // in the family group (else paper)
  bool per_realization;  // one value per realization: means_only fills it
};
std::vector<row_ref> selectable_rows() {
  std::vector<row_ref> out;
  for (std::size_t i = 0; i < quantity_table.size(); ++i)
    out.push_back({quantity_table[i].name, i >= paper_quantity_count,
                   per_realization(quantity_table[i].sampled)});
  for (const auto& l : level_table) out.push_back({l.name, true, false});
  return out;
}
const char* row_name(std::string_view name) {
  for (const auto& q : quantity_table)
    if (name == q.name || name == q.summary_name || name == q.symbol) return q.name;
  for (const auto& l : level_table)
    if (name == l.name || name == l.summary_name || name == l.symbol) return l.name;
  return nullptr;
}
bool in_selected_group(const statistics_selection& s, const row_ref& r) {
  return r.family ? s.family : s.paper;
}

// Adds the group or row `name` to `s`.
void select(std::string_view key, std::string_view name, statistics_selection& s) {
  if (name == "all") {
    for (const auto& g : statistics_group_table) s.*g.flag = true;
    return;
  }
  if (name == "default") {
    s.paper = true;
    return;
  }
  for (const auto& g : statistics_group_table)
    if (name == g.name) {
      s.*g.flag = true;
      return;
    }
  if (const char* row = row_name(name)) {
    s.rows.emplace_back(row);
    return;
  }
  throw invalid_value(std::string(key), std::string(name),
                      "a comma list of " + statistics_group_names());
}

// Rows in table order, once, and none that a selected group already holds.
statistics_selection canonical(statistics_selection s) {
  std::vector<std::string> rows;
  for (const auto& r : selectable_rows())
    if (!in_selected_group(s, r) && std::find(s.rows.begin(), s.rows.end(), r.name) != s.rows.end())
      rows.emplace_back(r.name);
  s.rows = std::move(rows);
  return s;
}

}  // namespace

std::string statistics_group_names() {
  std::string out;
  for (const auto& g : statistics_group_table) out += std::string(g.name) + ", ";
  return out + "default, all, or statistics by name (" + mean_statistic_names() +
         ", stick_duration, slip_duration, stick_onset_position, belt_level_fraction)";
}

std::string statistics_group_descriptions() {
  std::string out;
  for (const auto& g : statistics_group_table)
    out += (out.empty() ? "" : "; ") + std::string(g.name) + " (" + g.description + ")";
  return out;
}

statistics_selection parse_statistics_selection(std::string_view key, std::string_view list) {
  return parse_statistics_selection(key, std::vector<std::string>{std::string(list)});
}

statistics_selection parse_statistics_selection(std::string_view key,
                                                const std::vector<std::string>& names) {
  if (names.empty()) return {};  // Python's statistics=None, TOML's []: the default
  statistics_selection s;
  s.paper = false;
  // Each name may itself be a comma list ("paper,survival" as one string).
  for (const std::string_view n : names) {
    std::size_t from = 0;
    while (true) {
      const auto comma = n.find(',', from);
      select(key, trimmed(n.substr(from, comma - from)), s);
      if (comma == std::string_view::npos) break;
      from = comma + 1;
    }
  }
  return canonical(std::move(s));
}

std::vector<std::string> selected_group_names(const statistics_selection& s) {
  std::vector<std::string> out;
  for (const auto& g : statistics_group_table)
    if (s.*g.flag) out.emplace_back(g.name);
  out.insert(out.end(), s.rows.begin(), s.rows.end());
  return out;
}

std::string to_string(const statistics_selection& s) {
  std::string out;
  for (const auto& n : selected_group_names(s)) out += (out.empty() ? "" : ",") + n;
  return out;
}

std::uint8_t to_bits(const statistics_selection& s) noexcept {
  std::uint8_t bits = 0;
  for (std::size_t i = 0; i < statistics_group_table.size(); ++i)
    if (s.*statistics_group_table[i].flag) bits |= static_cast<std::uint8_t>(1u << i);
  return bits;
}

bool from_bits(std::uint8_t bits, statistics_selection& s) noexcept {
  s = {};
  for (std::size_t i = 0; i < statistics_group_table.size(); ++i)
    s.*statistics_group_table[i].flag = (bits & (1u << i)) != 0;
  return to_bits(s) == bits;
}

bool canonical_rows(const statistics_selection& s) { return canonical(s) == s; }

namespace {
bool named(const statistics_selection& s, const char* name) noexcept {
  return std::find(s.rows.begin(), s.rows.end(), name) != s.rows.end();
}
}  // namespace

bool selects(const statistics_selection& s, const quantity_info& q) noexcept {
  const bool family = &q - quantity_table.data() >= static_cast<std::ptrdiff_t>(paper_quantity_count);
  return (family ? s.family : s.paper) || named(s, q.name);
}
bool selects(const statistics_selection& s, const level_quantity_info& l) noexcept {
  return s.family || named(s, l.name);
}
bool selects_joint_histograms(const statistics_selection& s) noexcept { return s.family; }
bool selects_derivatives(const statistics_selection& s) noexcept { return s.derivatives; }

bool needs_family_statistics(const statistics_selection& s) noexcept {
  if (s.family || s.derivatives) return true;
  for (const auto& r : selectable_rows())
    if (r.family && named(s, r.name)) return true;
  return false;
}

bool needs_means_only(const statistics_selection& s) noexcept {
  if (s.paper || s.survival || needs_family_statistics(s)) return false;
  for (const auto& r : selectable_rows())
    if (named(s, r.name) && !r.per_realization) return false;
  return true;
}

}  // namespace stickslip
