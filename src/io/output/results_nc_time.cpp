// results.nc's time-resolved variables: the survival curves, the ensemble
// at the observe times and the convergence traces.
#include <fmt/format.h>

#include "observed_variables.hpp"
#include "results_nc.hpp"
#include "stickslip/survival_estimate.hpp"

namespace stickslip::io::detail::results_nc {

// The survival group: per law (stick, slip) a duration coordinate (the edges
// of the survival grid, shared by all points), the Kaplan-Meier curve with
// its interval and the numbers at risk over it, and the restricted mean.
void write_survival(nc::NcFile& f, const layout_info& l, const result_set& rs) {
  if (!rs.spec.statistics.survival) return;
  const auto& g = rs.spec.survival;
  for (const auto& law : survival_laws()) {
    const std::string name = law.name, coordinate = law.coordinate;
    const auto edges = survival_edges(g.*law.upper, g.bins);
    const auto dim = dimension(f, coordinate, edges.size());
    std::string words = coordinate;
    std::replace(words.begin(), words.end(), '_', ' ');
    if (defining()) {
      auto c = f.addVar(coordinate, nc::ncDouble, dim);
      describe(c, "s", words,
               fmt::format("{} {}: the edges of the survival grid, {} bins on [0, {}] s, at "
                           "which the survival curve is evaluated",
                           words, law.symbol, g.bins, g.*law.upper));
      c.putVar(edges.data());
    }
    const auto dims = with(l.grid, dim);
    // One Kaplan-Meier curve per point and variable: O(bins) each.
    auto curve_of = [&](const point_result& p) { return kaplan_meier(p.stats.*law.counts); };
    for (const auto& col : survival_curve_columns) {
      auto v = add_double(f, name + col.suffix, dims, "1", name + " " + col.long_name,
                          fmt::format("{}; episodes: {}", col.description, law.episodes));
      put_rows<double>(v, rs, edges.size(), [&](const point_result& p, std::vector<double>& row) {
        row = curve_of(p).*col.values;
      });
    }
    auto at_risk = add_count(f, name + "_at_risk", dims, name + "s at risk",
                             fmt::format("episodes at risk at each edge e: those of duration "
                                         ">= e, ended or censored; episodes: {}",
                                         law.episodes));
    put_rows<long long>(at_risk, rs, edges.size(),
                        [&](const point_result& p, std::vector<long long>& row) {
                          const auto k = curve_of(p);
                          for (std::size_t j = 0; j < row.size(); ++j)
                            row[j] = static_cast<long long>(k.at_risk[j]);
                        });
    auto mean = add_double(f, name + "_restricted_mean", l.grid, "s",
                           "restricted mean " + words,
                           fmt::format("integral of {}_survival over [0, {}] s: the mean of "
                                       "min({}, {} s)",
                                       name, g.*law.upper, law.symbol, g.*law.upper));
    put_grid<double>(mean, rs, [&](const point_result& p) { return curve_of(p).restricted_mean; });
  }
}

// The ensemble at the observe times (sweep --observe-times): the coordinate
// `time` after the grid dimensions, `quantile` (the levels of the quantile
// variables), and every variable of observed_variables() over (grid, time),
// (grid, time, belt_level) or (grid, time, quantile).
void write_observed(nc::NcFile& f, const layout_info& l, const result_set& rs) {
  const auto& times = rs.spec.observe_times;
  if (times.empty()) return;
  const auto time = dimension(f, "time", times.size());
  if (defining()) {
    auto t = f.addVar("time", nc::ncDouble, time);
    describe(t, "s", "observation time",
             "the observe times t of sweep --observe-times, at which the state of every "
             "realization is taken from its closed-form motion (no interpolation)");
    t.putAtt("axis", "T");
    t.putVar(times.data());
  }
  const std::size_t quantiles = std::size(observed_quantile_levels);
  const auto quantile = dimension(f, "quantile", quantiles);
  if (defining()) {
    auto q = f.addVar("quantile", nc::ncDouble, quantile);
    describe(q, "1", "quantile level", "the levels q of the quantile variables");
    q.putVar(observed_quantile_levels);
  }
  for (const auto& v : observed_variables()) {
    auto dims = with(l.grid, time);
    if (v.shape == observed_shape::per_level) dims.push_back(l.level);
    if (v.shape == observed_shape::per_quantile) dims.push_back(quantile);
    // The moments and the stick probability of single realizations' states
    // deflate only to ~80 % of their size, for a third of the time the
    // results.nc write takes after the last unit: they are stored as they
    // are. The quantiles (~10 %) and the level occupancies (~47 %) stay
    // deflated.
    const bool deflate = v.shape != observed_shape::one;
    auto var = add_double(f, v.name, dims, v.units, v.long_name, v.description, true, deflate);
    const std::size_t width = v.width(l.levels);
    put_rows<double>(var, rs, times.size() * width,
                     [&](const point_result& p, std::vector<double>& row) {
                       row = observed_values(v, p.stats.observed);
                     });
  }
}

void write_convergence(nc::NcFile& f, const layout_info& l, const result_set& rs) {
  const auto dims = with(l.grid, l.trace);
  const std::string when = fmt::format(
      "recorded after each block of block_size = {} realizations was merged, in block order",
      rs.spec.block_size);
  // No _FillValue, so that xarray keeps it an integer: every point of a
  // complete sweep has the same trace length, and 0 would mark an entry past
  // a shorter trace.
  auto n = add_count(f, "convergence_realizations", dims, "realizations merged",
                     when + "; 0 past the end of a point's trace (the double-valued traces "
                            "hold NaN there)");
  put_rows<long long>(n, rs, l.trace_length, [](const point_result& p, std::vector<long long>& row) {
    const auto& c = p.stats.convergence;
    for (std::size_t i = 0; i < row.size(); ++i)
      row[i] = i < c.size() ? static_cast<long long>(c[i].realizations) : 0;
  });
  struct item {
    const char* name;
    const char* units;
    const char* long_name;
    const char* description;
    double convergence_point::*member;
  };
  static const item items[] = {
      {"convergence_R_mean", "1", "running mean of R", "running mean of the stick fraction R",
       &convergence_point::R_mean},
      {"convergence_R_ci95_half_width", "1", "running CI half-width, R",
       "running half-width of the 95% confidence interval of the mean of R",
       &convergence_point::R_ci95_half_width},
      {"convergence_stick_duration_mean", "s", "running mean of D",
       "running mean of the stick duration D", &convergence_point::stick_duration_mean},
      {"convergence_stick_duration_ci95_half_width", "s", "running CI half-width, D",
       "running half-width of the 95% confidence interval of the mean of D",
       &convergence_point::stick_duration_ci95_half_width},
  };
  for (const auto& it : items) {
    auto v = add_double(f, it.name, dims, it.units, it.long_name,
                        std::string(it.description) + "; " + when);
    put_rows<double>(v, rs, l.trace_length, [&](const point_result& p, std::vector<double>& row) {
      const auto& c = p.stats.convergence;
      for (std::size_t i = 0; i < row.size(); ++i) row[i] = i < c.size() ? c[i].*it.member : nan;
    });
  }
}

}  // namespace stickslip::io::detail::results_nc
