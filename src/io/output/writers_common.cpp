#include <fmt/format.h>

#include <algorithm>

#include "stickslip/error.hpp"
#include "writers_detail.hpp"

namespace stickslip::io::detail {

std::vector<std::string> swept_symbols(const sweep_spec& s) {
  std::vector<std::string> out;
  for (const auto& ax : s.axes) out.emplace_back(canonical_symbol(ax.name));
  return out;
}

std::vector<std::string> point_parameter_symbols(const sweep_spec& s) {
  std::vector<std::string> out{"lambda", "mu"};
  for (auto& sym : swept_symbols(s))
    if (sym != "lambda" && sym != "mu") out.push_back(sym);
  return out;
}

std::string parameter_variable_name(const std::string& symbol) {
  // vI and rI: belt_level_I, belt_rate_I.
  const std::string sym = canonical_symbol(symbol);
  if (sym != info_for(sym).symbol) {
    std::string n = std::string(info_for(sym).long_name) + "_" + sym.substr(1);
    std::replace(n.begin(), n.end(), '-', '_');
    return n;
  }
  std::string n = info_for(symbol).long_name;
  for (auto& c : n)
    if (c == '-') c = '_';
  return n;
}


void check_shape(const result_set& rs) {
  const auto n = point_count(rs.spec);
  if (rs.points.size() != n)
    throw error(exit_code::internal,
                fmt::format("result set holds {} points but its grid has {}", rs.points.size(), n));
  // Writers lay points out in this order (row-major over the axes).
  for (std::size_t i = 0; i < n; ++i)
    if (rs.points[i].index != point_index(rs.spec, i))
      throw error(exit_code::internal,
                  fmt::format("result set point {} is not at its grid position", i));
  if (rs.spec.keep_records && !rs.records.empty() && rs.records.size() != n)
    throw error(exit_code::internal,
                fmt::format("result set holds records of {} points but its grid has {}",
                            rs.records.size(), n));
}

}  // namespace stickslip::io::detail
