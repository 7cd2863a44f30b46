// A sensitivity result as bars (plot_sensitivity.hpp): one group per index
// variable over `input` (by default first_order and total_order), one bar
// per uncertain input, whiskers from the variable's _ci95_low/_high.
#include "plot_sensitivity.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "plot_selection.hpp"
#include "stickslip/error.hpp"

namespace stickslip::study::detail {
namespace {

// The index variables of the file: over (input), with both interval ends.
std::vector<std::string> index_variables(const io::result_file& f) {
  std::vector<std::string> out;
  for (const auto& v : f.variables())
    if (!v.text && v.dims == std::vector<std::string>{"input"} &&
        f.variable(v.name + "_ci95_low") && f.variable(v.name + "_ci95_high"))
      out.push_back(v.name);
  return out;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t comma = std::min(s.find(',', start), s.size());
    out.push_back(s.substr(start, comma - start));
    start = comma + 1;
  }
  return out;
}

void refuse_grid_flags(const plot_request& r, const std::string& path) {
  const auto refuse = [&](const char* flag, const std::string& value) {
    throw invalid_value(flag, value,
                        fmt::format("nothing: {} is a sensitivity result, without a grid; "
                                    "`stickslip plot DIR` draws its indices as bars "
                                    "(--y chooses which)",
                                    path));
  };
  if (!r.x.empty()) refuse("--x", r.x);
  if (!r.by.empty()) refuse("--by", r.by);
  if (!r.at.empty()) refuse("--at", r.at.front());
  if (!r.histogram.empty()) refuse("--histogram", r.histogram);
  if (!r.survival.empty()) refuse("--survival", r.survival);
  if (r.time) refuse("--time", "(given)");
  if (r.map) refuse("--map", "(given)");
}

std::string words(std::string s) {
  for (auto& c : s)
    if (c == '_') c = ' ';
  return s;
}

}  // namespace

bar_plot plan_sensitivity_bars(const io::result_file& f, const plot_request& r) {
  refuse_grid_flags(r, f.path());
  const auto available = index_variables(f);
  std::string allowed;
  for (const auto& n : available) allowed += (allowed.empty() ? "" : ", ") + n;
  bar_plot p;
  p.categories = f.strings("input");
  const auto names = split(r.y.empty() ? std::string("first_order,total_order") : r.y);
  for (const auto& name : names) {
    if (std::find(available.begin(), available.end(), name) == available.end())
      throw invalid_value("--y", name, "indices of " + f.path() + ", comma-separated: " + allowed);
    p.groups.push_back({words(name), f.values(name), f.values(name + "_ci95_low"),
                        f.values(name + "_ci95_high")});
    // Undefined indices (a statistic constant over the design) have no bars:
    // refused before anything is written (gnuplot failed on them, leaving
    // its files: a review).
    const auto& v = p.groups.back().value;
    if (!v.empty() && std::all_of(v.begin(), v.end(), [](double x) { return std::isnan(x); })) {
      const std::string why = f.attribute("warning");
      throw error(exit_code::invalid_input,
                  fmt::format("cannot plot {} of {}: every value is NaN (undefined){}", name,
                              f.path(), why.empty() ? "" : ": " + why));
    }
  }
  const auto& first = *f.variable(names.front());
  const std::string statistic = f.attribute("statistic");
  p.text.stem = stem_text(fmt::format("sensitivity_{}", fmt::join(names, "_")));
  p.text.title = f.attribute("title").empty() ? "Sobol' indices" : f.attribute("title");
  p.text.xlabel = axis_label(*f.variable("input"));
  p.text.ylabel = fmt::format("index ({})", first.units.empty() ? "1" : first.units);
  p.text.caption = fmt::format("{} of {}, per uncertain input, with 95 % intervals, from {}",
                               fmt::join(names, ", "), statistic.empty() ? "the statistic" : statistic,
                               f.path());
  return p;
}

}  // namespace stickslip::study::detail
