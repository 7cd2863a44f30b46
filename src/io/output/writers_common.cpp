#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "stickslip/error.hpp"
#include "stickslip/uncertainty/uncertain_draws.hpp"
#include "json_emitter.hpp"
#include "writers_detail.hpp"

namespace stickslip::io::detail {

std::vector<std::string> swept_symbols(const sweep_spec& s) {
  std::vector<std::string> out;
  for (const auto& ax : s.axes) out.emplace_back(canonical_symbol(ax.name));
  return out;
}

bool defines_model(const model_parameters& p, std::string_view symbol) {
  const std::string sym = canonical_symbol(symbol);
  // mu only where every refinement of it (mu_s, mu_k) resolves to it.
  const parameter_info& info = info_for(sym);
  for (const auto& row : scalar_parameters)
    if (refines(row, info) && resolved_value(p, row) != resolved_value(p, info)) return false;
  if (sym == "V") return p.belt_levels.empty();
  if (sym == "lambda") return has_poisson_switching(p);
  return true;
}

namespace {

// The recorded parameters that are not swept (those a grid-wide fact is
// asked of).
std::vector<std::string> unswept_recorded(const sweep_spec& s) {
  const auto swept = swept_symbols(s);
  std::vector<std::string> out;
  for (const char* sym : recorded_parameter_names)
    if (std::find(swept.begin(), swept.end(), sym) == swept.end()) out.emplace_back(sym);
  return out;
}

}  // namespace

std::vector<std::string> meaningless_parameters(const result_set& rs) {
  const auto candidates = unswept_recorded(rs.spec);
  std::vector<char> everywhere(candidates.size(), 1);
  for_each_point_model(rs, [&](const model_parameters& p) {
    for (std::size_t i = 0; i < candidates.size(); ++i)
      everywhere[i] = everywhere[i] && defines_model(p, candidates[i]);
  });
  std::vector<std::string> out;
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (!everywhere[i]) out.push_back(candidates[i]);
  return out;
}

std::vector<std::string> varying_parameters(const result_set& rs) {
  const model_parameters first = resolved_base(rs);
  const auto candidates = unswept_recorded(rs.spec);
  std::vector<double> values;
  for (const auto& sym : candidates) values.push_back(parameter_value(first, sym));
  std::vector<char> varies(candidates.size(), 0);
  for_each_point_model(rs, [&](const model_parameters& p) {
    for (std::size_t i = 0; i < candidates.size(); ++i)
      varies[i] = varies[i] || parameter_value(p, candidates[i]) != values[i];
  });
  std::vector<std::string> out;
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (varies[i]) out.push_back(candidates[i]);
  return out;
}

model_parameters resolved_base(const result_set& rs) {
  return holds_every_point(rs) ? rs.points.front().parameters : point_parameters(rs.spec, 0);
}

belt_sameness same_belt_everywhere(const result_set& rs) {
  belt_sameness same;
  const model_parameters first = resolved_base(rs);
  const auto levels = first.levels();
  const auto generator = first.generator();
  for_each_point_model(rs, [&](const model_parameters& p) {
    same.levels = same.levels && p.levels() == levels;
    same.generator = same.generator && p.generator() == generator;
  });
  // A law: does its parameter move the belt? (At another value than the
  // median the first point holds: v + 1 + |v| > v for every finite v; 2 v + 1
  // missed a median of -1, the default v2.)
  for (const auto& sym : symbols_set_by_laws(rs.spec.uncertain)) {
    model_parameters moved = first;
    const double v = parameter_value(first, sym);
    set_parameter(moved, sym, v + 1.0 + std::abs(v));
    same.levels = same.levels && moved.levels() == levels;
    same.generator = same.generator && moved.generator() == generator;
  }
  return same;
}

void emit_base(json_emitter& j, const result_set& rs, std::vector<std::string> without_value) {
  for (auto& sym : varying_parameters(rs)) without_value.push_back(std::move(sym));
  j.key("base");
  j.begin_object();
  const auto belt = same_belt_everywhere(rs);
  emit_model_members(j, resolved_base(rs), without_value, meaningless_parameters(rs), belt.levels,
                     belt.generator);
  j.end_object();
}

std::vector<std::string> point_parameter_symbols(const result_set& rs) {
  const auto omitted = meaningless_parameters(rs);
  std::vector<std::string> out;
  // The leading axes (lambda, mu) always, unless meaningless; then the
  // other swept ones in the grid's order.
  for (std::size_t i = 0; i < leading_axis_count; ++i)
    if (std::find(omitted.begin(), omitted.end(), default_axis_order[i]) == omitted.end())
      out.emplace_back(default_axis_order[i]);
  for (auto& sym : swept_symbols(rs.spec))
    if (axis_rank(sym) >= leading_axis_count) out.push_back(sym);
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

namespace {

// Points [0, rs.points.size()) of rs are the grid's points first, first + 1,
// ... in row-major order, each with the spec's observe times.
void check_points(const result_set& rs, std::size_t first) {
  for (std::size_t i = 0; i < rs.points.size(); ++i) {
    // Writers lay points out in this order (row-major over the axes).
    if (rs.points[i].index != point_index(rs.spec, first + i))
      throw error(exit_code::internal,
                  fmt::format("result set point {} is not at its grid position", first + i));
    // The ensemble at the observe times: every point holds the spec's times.
    if (rs.points[i].stats.observed.times() != rs.spec.observe_times)
      throw error(exit_code::internal,
                  fmt::format("result set point {} holds {} observe times, its spec {}",
                              first + i, rs.points[i].stats.observed.times().size(),
                              rs.spec.observe_times.size()));
  }
}

}  // namespace

void check_shape(const result_set& rs) {
  const auto n = point_count(rs.spec);
  if (rs.points.size() != n)
    throw error(exit_code::internal,
                fmt::format("result set holds {} points but its grid has {}", rs.points.size(), n));
  check_points(rs, 0);
  if (rs.spec.keep_records && !rs.records.empty() && rs.records.size() != n)
    throw error(exit_code::internal,
                fmt::format("result set holds records of {} points but its grid has {}",
                            rs.records.size(), n));
}

void check_slab(const result_set& slab, std::size_t first) {
  const auto n = point_count(slab.spec);
  const std::size_t row = slab.spec.axes.empty() ? n : n / slab.spec.axes.front().values.size();
  if (slab.points.empty() || first % row != 0 || slab.points.size() % row != 0 ||
      first + slab.points.size() > n)
    throw error(exit_code::internal,
                fmt::format("a slab of points {} .. {} is not whole rows of the grid's {} points "
                            "(rows of {})",
                            first, first + slab.points.size(), n, row));
  check_points(slab, first);
}

}  // namespace stickslip::io::detail
