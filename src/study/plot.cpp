// The figure a `stickslip plot` request asks for (study/plot.hpp): every
// kind is a set of curves of one variable along one dimension at chosen
// points, except the heat map and the sensitivity bars.
#include "stickslip/study/plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <optional>

#include "plot_selection.hpp"
#include "plot_sensitivity.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/journal.hpp"
#include "stickslip/nearest_name.hpp"

namespace stickslip::study {
namespace {

using detail::at_set;
using detail::grid_choice;
using detail::quantity;

// Curves of `q` along `x_dim`: one per --at point and --by value.
struct curve_request {
  quantity q;
  std::string x_dim, by_dim;
  std::string x_var;  // the variable holding x at each point ("": the coordinate of x_dim)
  std::vector<at_set> at;
  curve_style style = curve_style::points;
  bool logx = false;
};

bool has_dim(const io::result_variable& v, const std::string& d) {
  return std::find(v.dims.begin(), v.dims.end(), d) != v.dims.end();
}

std::string dims_text(const io::result_variable& v) {
  std::string s;
  for (const auto& d : v.dims) s += (s.empty() ? "" : ", ") + d;
  return s;
}

void require_dim(const io::result_variable& v, const std::string& flag, const std::string& dim) {
  if (!has_dim(v, dim))
    throw invalid_value(flag, dim, fmt::format("a dimension of {}: {}", v.name, dims_text(v)));
}

std::vector<at_set> parse_all(const std::vector<std::string>& at) {
  std::vector<at_set> out;
  for (const auto& a : at) out.push_back(detail::parse_at(a));
  return out;
}

std::vector<grid_choice> choose_points(const io::result_file& f, const io::result_variable& v,
                                       const std::vector<std::string>& free,
                                       const std::vector<at_set>& at) {
  std::vector<grid_choice> out;
  for (const auto& a : at.empty() ? std::vector<at_set>{{}} : at) {
    out.push_back(detail::choose_point(f, v, free, a));
    detail::complete_point(f, v, free, out.back());
  }
  return out;
}

// "_at_lambda3.718_mu5" for each chosen point that says something.
std::string at_stem(const std::vector<grid_choice>& points) {
  std::string s;
  for (const auto& p : points)
    if (!p.stem.empty()) s += "_at_" + p.stem;
  return s;
}

std::string series_label(const std::vector<grid_choice>& points, const grid_choice& p,
                          const std::string& by_text, const std::string& fallback) {
  std::string l = points.size() > 1 ? p.text : "";
  if (!by_text.empty()) l += (l.empty() ? "" : ", ") + by_text;
  return l.empty() ? fallback : l;
}

curve_plot build_curves(const io::result_file& f, const curve_request& r, figure_text text) {
  const auto& v = *r.q.value;
  std::vector<std::string> free{r.x_dim};
  if (!r.by_dim.empty()) free.push_back(r.by_dim);
  const auto points = choose_points(f, v, free, r.at);
  std::optional<detail::axis> by;
  if (!r.by_dim.empty()) by = detail::axis_of(f, r.by_dim);
  curve_plot p;
  p.style = r.style;
  p.logx = r.logx;
  for (const auto& pt : points) {
    for (std::size_t j = 0; j < (by ? by->values.size() : 1); ++j) {
      auto index = pt.index;
      std::string by_text;
      if (by) {
        index[by->name] = j;
        by_text = fmt::format("{} = {}", by->name, detail::short_number(by->values[j]));
      }
      auto s = detail::slice(f, r.q, r.x_dim, index);
      plot_series series;
      series.label = series_label(points, pt, by_text, r.q.asked);
      series.x = r.x_var.empty() ? f.coordinate(r.x_dim) : detail::slice(f, r.x_var, r.x_dim, index);
      series.y = std::move(s.y);
      series.low = std::move(s.low);
      series.high = std::move(s.high);
      p.series.push_back(std::move(series));
    }
  }
  if (points.size() == 1 && !points.front().text.empty())
    text.title += " at " + points.front().text;
  text.stem = detail::stem_text(text.stem + (by ? "_by_" + by->name : std::string()) +
                                at_stem(points));
  text.caption = fmt::format(
      "{} ({}) against {}{}{}, from {}", v.long_name, v.name, r.x_dim,
      by ? ", one curve per value of " + by->name : std::string(),
      r.q.has_band() ? fmt::format(", with 95 % intervals ({})", r.q.band_text())
                     : std::string(", no interval in the file"),
      f.path());
  if (points.size() == 1 && !points.front().text.empty())
    text.caption += "; at the grid point " + points.front().text;
  p.text = std::move(text);
  return p;
}

// The swept dimensions of `v` with more than one value, not fixed by --at.
std::vector<std::string> open_dims(const io::result_file& f, const io::result_variable& v,
                                   const std::vector<at_set>& at) {
  std::vector<std::string> out;
  for (const auto& d : v.dims) {
    bool fixed = false;
    for (const auto& a : at)
      for (const auto& [name, value] : a) fixed = fixed || name == d;
    if (!fixed && f.dimension(d)->size > 1) out.push_back(d);
  }
  return out;
}

quantity default_statistic(const io::result_file& f, const plot_request& r) {
  return detail::find_quantity(f, "--y", r.y.empty() ? std::string("R") : r.y);
}

// --x and --by given or, when not, the open dimensions in order.
std::pair<std::string, std::string> choose_axes(const io::result_file& f, const quantity& q,
                                                const plot_request& r,
                                                const std::vector<at_set>& at, bool need_by) {
  auto open = open_dims(f, *q.value, at);
  std::string x = r.x, by = r.by;
  std::erase(open, by);
  if (x.empty()) {
    if (open.empty())
      throw invalid_value("--x", "(not given)",
                          fmt::format("a dimension of {} with several values: {}", q.value->name,
                                      dims_text(*q.value)));
    x = open.front();
  }
  std::erase(open, x);
  if (by.empty() && (need_by || open.size() == 1) && !open.empty()) by = open.front();
  require_dim(*q.value, "--x", x);
  if (!by.empty()) require_dim(*q.value, "--by", by);
  if (need_by && by.empty())
    throw invalid_value("--by", "(not given)",
                        fmt::format("a second dimension of {} for the map: {}", q.value->name,
                                    dims_text(*q.value)));
  if (by == x) throw invalid_value("--by", by, "a dimension other than --x " + x);
  return {x, by};
}

curve_plot plan_curves(const io::result_file& f, const plot_request& r) {
  const auto at = parse_all(r.at);
  curve_request c;
  c.q = default_statistic(f, r);
  std::tie(c.x_dim, c.by_dim) = choose_axes(f, c.q, r, at, false);
  c.at = at;
  const auto x = detail::axis_of(f, c.x_dim);
  c.logx = r.logx || x.log_spaced;
  figure_text t;
  t.stem = fmt::format("{}_vs_{}", c.q.asked, c.x_dim);
  t.title = c.q.value->long_name;
  t.xlabel = x.label;
  t.ylabel = detail::axis_label(*c.q.value);
  return build_curves(f, c, std::move(t));
}

map_plot plan_map(const io::result_file& f, const plot_request& r) {
  const auto at = parse_all(r.at);
  if (at.size() > 1) throw invalid_value("--at", r.at[1], "one --at with --map (one map)");
  const auto q = default_statistic(f, r);
  const auto [x_dim, by_dim] = choose_axes(f, q, r, at, true);
  auto point = detail::choose_point(f, *q.value, {x_dim, by_dim}, at.empty() ? at_set{} : at[0]);
  detail::complete_point(f, *q.value, {x_dim, by_dim}, point);
  const auto x = detail::axis_of(f, x_dim), y = detail::axis_of(f, by_dim);
  map_plot m;
  m.x = x.values;
  m.y = y.values;
  m.logx = r.logx || x.log_spaced;
  m.logy = y.log_spaced;
  for (std::size_t i = 0; i < x.values.size(); ++i) {
    auto index = point.index;
    index[x_dim] = i;
    const auto column = detail::slice(f, q.value->name, by_dim, index);
    m.z.insert(m.z.end(), column.begin(), column.end());
  }
  m.zlabel = detail::axis_label(*q.value);
  m.text.stem = detail::stem_text(fmt::format("{}_map_{}_{}{}", q.asked, x_dim, by_dim,
                                              point.stem.empty() ? "" : "_at_" + point.stem));
  m.text.title = q.value->long_name + (point.text.empty() ? "" : " at " + point.text);
  m.text.xlabel = x.label;
  m.text.ylabel = y.label;
  m.text.caption = fmt::format("{} ({}) over {} and {}, from {}", q.value->long_name,
                               q.value->name, x_dim, by_dim, f.path());
  return m;
}

// NAME's histogram: NAME_density, NAME being a statistic or its symbol.
const io::result_variable& histogram_of(const io::result_file& f, const std::string& name) {
  if (const auto* d = f.variable(name + "_density")) return *d;
  for (const auto& v : f.variables())
    if (v.symbol == name && v.name.size() > 5 && v.name.ends_with("_mean"))
      if (const auto* d = f.variable(v.name.substr(0, v.name.size() - 5) + "_density")) return *d;
  std::string names;
  std::vector<std::string> candidates;  // for "did you mean": the names and the symbols
  for (const auto& v : f.variables())
    if (v.name.ends_with("_density")) {
      const std::string base = v.name.substr(0, v.name.size() - 8);
      const auto* mean = f.variable(base + "_mean");
      names += fmt::format("{}{}{}", names.empty() ? "" : ", ", base,
                           mean && !mean->symbol.empty() ? " (" + mean->symbol + ")" : "");
      candidates.push_back(base);
      if (mean && !mean->symbol.empty()) candidates.push_back(mean->symbol);
    }
  const auto guess = nearest_name(name, candidates);
  throw invalid_value("--histogram", name,
                      "a statistic with a histogram in " + f.path() + ": " + names +
                          did_you_mean(guess));
}

// Curves of `q` along its own dimension `x_dim` (time, bins, durations) at
// each --at point and --by value, titled and labelled from the variables.
std::pair<curve_request, figure_text> along(const io::result_file& f, const quantity& q,
                                            const std::string& x_dim, const plot_request& r,
                                            curve_style style) {
  curve_request c;
  c.q = q;
  c.x_dim = x_dim;
  c.at = parse_all(r.at);
  c.by_dim = r.by;
  if (c.by_dim.empty()) {  // the remaining dimension, when exactly one is left (plot.md)
    auto open = open_dims(f, *q.value, c.at);
    std::erase(open, x_dim);
    if (open.size() == 1) c.by_dim = open.front();
  }
  if (!c.by_dim.empty()) require_dim(*q.value, "--by", c.by_dim);
  c.style = style;
  c.logx = r.logx;
  figure_text t;
  t.title = q.value->long_name;
  t.xlabel = detail::axis_of(f, x_dim).label;
  t.ylabel = detail::axis_label(*q.value);
  return {std::move(c), std::move(t)};
}

curve_plot plan_histogram(const io::result_file& f, const plot_request& r) {
  const auto& density = histogram_of(f, r.histogram);
  auto [c, t] = along(f, quantity{r.histogram, &density, "", "", "", ""}, density.dims.back(), r,
                      curve_style::histogram);
  if (const auto* bins = f.variable(density.coordinates); bins && bins->dims == density.dims) {
    c.x_var = bins->name;
    t.xlabel = detail::axis_label(*bins);
  }
  t.stem = r.histogram + "_histogram";
  return build_curves(f, c, std::move(t));
}

curve_plot plan_time(const io::result_file& f, const plot_request& r) {
  if (!f.dimension("time"))
    throw error(exit_code::invalid_input,
                fmt::format("cannot plot --time: {} has no 'time' dimension; time-resolved "
                            "statistics are written by `stickslip sweep --observe-times GRID`",
                            f.path()));
  const auto q = detail::find_quantity(f, "--y", r.y.empty() ? "stick_probability" : r.y, "time");
  require_dim(*q.value, "--y", "time");
  auto [c, t] = along(f, q, "time", r, curve_style::lines);
  t.stem = q.asked + "_vs_time";
  return build_curves(f, c, std::move(t));
}

curve_plot plan_survival(const io::result_file& f, const plot_request& r) {
  const std::string var = r.survival + "_survival";
  if (!f.variable(var)) {
    std::string present;
    for (const auto& v : f.variables())
      if (v.name.ends_with("_survival"))
        present += (present.empty() ? "" : ", ") + v.name.substr(0, v.name.size() - 9);
    if (!present.empty()) throw invalid_value("--survival", r.survival, present);
    throw error(exit_code::invalid_input,
                fmt::format("cannot plot --survival {}: {} has no '{}' variable; survival "
                            "curves are written by `stickslip sweep --statistics survival`",
                            r.survival, f.path(), var));
  }
  const auto q = detail::find_quantity(f, "--survival", var);
  auto [c, t] = along(f, q, q.value->dims.back(), r, curve_style::steps);
  t.stem = var;
  return build_curves(f, c, std::move(t));
}

}  // namespace

std::string find_result_file(const std::string& dir) {
  namespace fs = std::filesystem;
  for (const char* name : {"results.nc", "sensitivity.nc"})
    if (fs::is_regular_file(fs::path(dir) / name)) return (fs::path(dir) / name).string();
  // An interrupted run leaves its journal and no results yet: say so.
  const std::string unfinished =
      io::journal_exists(dir)
          ? fmt::format("; {} holds the journal of an unfinished run: finish it with the same "
                        "command and --resume, then plot",
                        dir)
          : "";
  throw invalid_value("DIR", dir,
                      "a directory holding results.nc (from stickslip sweep -o DIR) or "
                      "sensitivity.nc (from stickslip sensitivity -o DIR)" + unfinished);
}

plot_figure plan_plot(const io::result_file& f, const plot_request& r) {
  std::vector<std::string> kinds;
  if (r.map) kinds.emplace_back("--map");
  if (!r.histogram.empty()) kinds.push_back("--histogram " + r.histogram);
  if (r.time) kinds.emplace_back("--time");
  if (!r.survival.empty()) kinds.push_back("--survival " + r.survival);
  if (kinds.size() > 1)
    throw invalid_value(kinds[1].substr(0, kinds[1].find(' ')), kinds[1] + " with " + kinds[0],
                        "one figure kind at a time: --map, --histogram, --time or --survival");
  if (f.dimension("input") && f.variable("first_order")) return detail::plan_sensitivity_bars(f, r);
  if (!r.histogram.empty()) return plan_histogram(f, r);
  if (!r.survival.empty()) return plan_survival(f, r);
  if (r.time) return plan_time(f, r);
  if (r.map) return plan_map(f, r);
  return plan_curves(f, r);
}

}  // namespace stickslip::study
