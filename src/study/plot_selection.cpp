// What `stickslip plot` draws, chosen in a result file (plot_selection.hpp).
#include "plot_selection.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "stickslip/accumulators/mean_variance.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/nearest_name.hpp"
#include "stickslip/statistics_schema.hpp"

namespace stickslip::study::detail {
namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// The first of `names` that is a variable of `f`, or "".
std::string first_present(const io::result_file& f, const std::vector<std::string>& names) {
  for (const auto& n : names)
    if (f.variable(n)) return n;
  return "";
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

std::string values_text(const std::vector<double>& v) {
  std::vector<std::string> t;
  for (std::size_t i = 0; i < v.size() && i < 8; ++i) t.push_back(short_number(v[i]));
  if (v.size() > 8) t.emplace_back("...");
  return joined(t);
}

}  // namespace

std::string statistic_list(const io::result_file& f) {
  std::vector<std::string> names;
  for (const auto& v : f.variables()) {
    if (!ends_with(v.name, "_mean") || v.text) continue;
    const std::string base = v.name.substr(0, v.name.size() - 5);
    names.push_back(v.symbol.empty() ? base : fmt::format("{} ({})", base, v.symbol));
  }
  return joined(names);
}

namespace {

// The names find_quantity takes for the variables over the dimension
// `along`: X for X_mean, else the variable's own name, leaving out the
// bands and spreads that go with them.
std::vector<std::string> names_along(const io::result_file& f, const std::string& along) {
  std::vector<std::string> names;
  for (const auto& v : f.variables()) {
    if (v.text || std::find(v.dims.begin(), v.dims.end(), along) == v.dims.end() ||
        v.dims == std::vector<std::string>{along})
      continue;
    if (ends_with(v.name, "_mean")) {
      names.push_back(v.name.substr(0, v.name.size() - 5));
      continue;
    }
    const bool band = ends_with(v.name, "_std_error") || ends_with(v.name, "_variance") ||
                      ends_with(v.name, "_ci95_half_width") || ends_with(v.name, "_ci95_low") ||
                      ends_with(v.name, "_ci95_high");
    if (!band) names.push_back(v.name);
  }
  return names;
}

// What a name can be, for a refusal: the symbols and X of every X_mean.
std::vector<std::string> statistic_names(const io::result_file& f) {
  std::vector<std::string> names;
  for (const auto& v : f.variables()) {
    if (!ends_with(v.name, "_mean") || v.text) continue;
    names.push_back(v.name.substr(0, v.name.size() - 5));
    if (!v.symbol.empty()) names.push_back(v.symbol);
  }
  return names;
}

}  // namespace

quantity find_quantity(const io::result_file& f, const std::string& flag, const std::string& name,
                       const std::string& along) {
  quantity q;
  q.asked = name;
  q.value = f.variable(name + "_mean");
  if (!q.value)
    for (const auto& v : f.variables())
      if (ends_with(v.name, "_mean") && !v.symbol.empty() && v.symbol == name) q.value = &v;
  if (!q.value) {
    const auto* v = f.variable(name);
    const bool coordinate = v && v->dims == std::vector<std::string>{name};
    if (v && !v->text && !coordinate && !v->dims.empty()) q.value = v;
  }
  if (!q.value) {
    // A statistic of the schema that the sweep did not select is named as
    // such, not taken for a typo of another.
    const auto& all = quantities();
    const bool known = std::any_of(all.begin(), all.end(), [&](const quantity_info& k) {
      return name == k.name || name == k.summary_name || name == std::string_view(k.symbol);
    });
    const auto names = along.empty() ? std::vector<std::string>{} : names_along(f, along);
    const std::string selected = f.attribute("statistics");
    const std::string hint =
        known ? fmt::format("; {} is a statistic this sweep did not select: rerun it with "
                            "--statistics {},{}",
                            name, selected.empty() ? "paper" : selected, name)
              : did_you_mean(nearest_name(name, along.empty() ? statistic_names(f) : names));
    if (!along.empty())
      throw invalid_value(flag, name,
                          fmt::format("a statistic of {} over {}: {}{}", f.path(), along,
                                      joined(names), hint));
    const std::string not_there =
        known ? "" : "; a statistic the sweep did not select is not there: rerun it with --statistics";
    throw invalid_value(flag, name,
                        fmt::format("a statistic of {}: {}; or another variable of it over the "
                                    "grid (ncdump -h lists them){}{}",
                                    f.path(), statistic_list(f), not_there, hint));
  }
  const std::string& var = q.value->name;
  const std::string base = ends_with(var, "_mean") ? var.substr(0, var.size() - 5) : var;
  q.low = first_present(f, {base + "_ci95_low", var + "_ci95_low"});
  q.high = first_present(f, {base + "_ci95_high", var + "_ci95_high"});
  if (q.low.empty() || q.high.empty()) {
    q.low.clear();
    q.high.clear();
    q.half_width = first_present(f, {base + "_ci95_half_width", var + "_ci95_half_width"});
    if (q.half_width.empty())
      q.std_error = first_present(f, {base + "_std_error", var + "_std_error"});
  }
  return q;
}

std::string quantity::band_text() const {
  if (!low.empty()) return low + ", " + high;
  return half_width.empty() ? std_error + " x 1.96" : half_width;
}

std::string axis_label(const io::result_variable& v) {
  const std::string name = v.long_name.empty() ? v.name : v.long_name;
  return v.units.empty() ? name : fmt::format("{} ({})", name, v.units);
}

bool log_spaced(const std::vector<double>& v) {
  if (v.size() < 3 || !(v.front() > 0)) return false;
  const double step = std::log(v[1] / v[0]);
  if (!(std::abs(step) > 1e-12)) return false;
  for (std::size_t i = 1; i < v.size(); ++i)
    if (!(v[i] > 0) || std::abs(std::log(v[i] / v[i - 1]) - step) > 1e-6 * std::abs(step))
      return false;
  return true;
}

axis axis_of(const io::result_file& f, const std::string& dim) {
  axis a;
  a.name = dim;
  a.values = f.coordinate(dim);
  const auto* v = f.variable(dim);
  a.label = v ? axis_label(*v) : dim + " (index)";
  a.log_spaced = log_spaced(a.values);
  return a;
}

at_set parse_at(const std::string& text) {
  at_set out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string part = text.substr(start, comma - start);
    const auto eq = part.find('=');
    if (eq == std::string::npos || eq == 0)
      throw invalid_value("--at", text, "NAME=VALUE[,NAME=VALUE...], e.g. lambda=3.8,mu=5");
    out.emplace_back(part.substr(0, eq),
                     io::parse_number("--at " + part.substr(0, eq), part.substr(eq + 1)));
    start = comma + 1;
  }
  return out;
}

grid_choice choose_point(const io::result_file& f, const io::result_variable& var,
                         const std::vector<std::string>& free, const at_set& at) {
  grid_choice c;
  for (const auto& [name, wanted] : at) {
    const bool is_dim = std::find(var.dims.begin(), var.dims.end(), name) != var.dims.end();
    if (!is_dim || std::find(free.begin(), free.end(), name) != free.end()) {
      std::vector<std::string> fixable;
      for (const auto& d : var.dims)
        if (std::find(free.begin(), free.end(), d) == free.end()) fixable.push_back(d);
      const std::string drawn = joined(free) + (free.size() == 1 ? " is" : " are");
      std::string allowed;
      if (!fixable.empty())
        allowed = fmt::format("an axis of {} that is not drawn ({} drawn): {}", var.name, drawn,
                              joined(fixable));
      else if (!is_dim)
        allowed = fmt::format("none: {} is not an axis of {}, whose axes ({}) are all drawn",
                              name, var.name, joined(var.dims));
      else
        allowed = fmt::format("none: every axis of {} is drawn ({}); leave {} out of --at "
                              "(or, if it is --by, drop --by to draw that value alone)",
                              var.name, joined(free), name);
      throw invalid_value("--at", fmt::format("{}={}", name, short_number(wanted)), allowed);
    }
    if (c.index.count(name))
      throw invalid_value("--at", name, "each name once in one --at");
    const axis a = axis_of(f, name);
    const auto [lo, hi] = std::minmax_element(a.values.begin(), a.values.end());
    const double slack = 1e-9 * std::max(std::abs(*lo), std::abs(*hi));
    if (!(wanted >= *lo - slack && wanted <= *hi + slack))
      throw invalid_value("--at", fmt::format("{}={}", name, short_number(wanted)),
                          fmt::format("{} within the grid's range [{}, {}]", name,
                                      short_number(*lo), short_number(*hi)));
    const auto distance = [&](double v) {
      return a.log_spaced ? std::abs(std::log(v / wanted)) : std::abs(v - wanted);
    };
    std::size_t best = 0;
    for (std::size_t i = 1; i < a.values.size(); ++i)
      if (distance(a.values[i]) < distance(a.values[best])) best = i;
    c.index[name] = best;
    const double used = a.values[best];
    c.text += fmt::format("{}{} = {}", c.text.empty() ? "" : ", ", name, short_number(used));
    if (short_number(used) != short_number(wanted))
      c.text += fmt::format(" (nearest to {})", short_number(wanted));
    c.stem += fmt::format("{}{}{}", c.stem.empty() ? "" : "_", name, short_number(used));
  }
  return c;
}

void complete_point(const io::result_file& f, const io::result_variable& var,
                    const std::vector<std::string>& free, grid_choice& c) {
  for (const auto& d : var.dims) {
    if (c.index.count(d) || std::find(free.begin(), free.end(), d) != free.end()) continue;
    const auto values = f.coordinate(d);
    if (values.size() == 1) {
      c.index[d] = 0;
      continue;
    }
    throw invalid_value(
        "--at", "(no value for " + d + ")",
        fmt::format("{} varies over {} ({} values: {}): draw one curve per value with --by {}, "
                    "or choose one with --at {}=VALUE",
                    var.name, d, values.size(), values_text(values), d, d));
  }
}

std::vector<double> slice(const io::result_file& f, const std::string& var, const std::string& dim,
                          const std::map<std::string, std::size_t>& fixed) {
  const auto* v = f.variable(var);
  const auto all = f.values(var);
  std::size_t offset = 0, stride = 0, length = 0, step = 1;
  for (auto d = v->dims.rbegin(); d != v->dims.rend(); ++d) {
    const std::size_t size = f.dimension(*d)->size;
    if (*d == dim) {
      stride = step;
      length = size;
    } else {
      offset += fixed.at(*d) * step;
    }
    step *= size;
  }
  std::vector<double> out(length);
  for (std::size_t i = 0; i < length; ++i) out[i] = all[offset + i * stride];
  return out;
}

quantity_slice slice(const io::result_file& f, const quantity& q, const std::string& dim,
                     const std::map<std::string, std::size_t>& fixed) {
  quantity_slice s;
  s.y = slice(f, q.value->name, dim, fixed);
  if (!q.low.empty()) {
    s.low = slice(f, q.low, dim, fixed);
    s.high = slice(f, q.high, dim, fixed);
  } else if (!q.half_width.empty() || !q.std_error.empty()) {
    const bool se = q.half_width.empty();
    const auto half = slice(f, se ? q.std_error : q.half_width, dim, fixed);
    for (std::size_t i = 0; i < half.size(); ++i) {
      const double h = se ? z95 * half[i] : half[i];
      s.low.push_back(s.y[i] - h);
      s.high.push_back(s.y[i] + h);
    }
  }
  return s;
}

std::string short_number(double x) { return fmt::format("{:.4g}", x); }

std::string stem_text(const std::string& s) {
  std::string out;
  for (char c : s) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_';
    out += keep ? c : '_';
  }
  return out;
}

}  // namespace stickslip::study::detail
