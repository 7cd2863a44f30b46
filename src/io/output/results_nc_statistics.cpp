// results.nc's statistics of the schema (statistics_schema.hpp) and the
// estimates of the estimate table (estimates.hpp): means with their
// intervals, counts, estimates, histograms, level and joint statistics.
#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <optional>

#include "results_nc.hpp"
#include "stickslip/estimates.hpp"
#include "stickslip/precision/crn_slopes.hpp"
#include "stickslip/statistics_schema.hpp"

namespace stickslip::io::detail::results_nc {

namespace {

// The lower (side -1) or upper (+1) end of the 95% interval of a mean
// (mean_estimate: mean -+ 1.96 std / sqrt(count)).
double interval_end(const mean_variance& m, int side) {
  const auto e = mean_estimate(m);
  return side < 0 ? e.value - e.ci95_half_width() : e.value + e.ci95_half_width();
}

}  // namespace

void write_statistics(nc::NcFile& f, const layout_info& l, const result_set& rs) {
  for (const auto& q : quantities()) {
    if (!selects(rs.spec.statistics, q)) continue;
    const std::string n = q.name, sym = q.symbol;
    const auto mv = [&](const point_result& p) -> const mean_variance& { return p.stats.*q.moments; };
    auto mean = add_double(f, n + "_mean", l.grid, q.units, std::string("mean ") + q.long_name,
                           fmt::format("{} {}: {}", q.long_name, sym, q.description));
    if (defining()) mean.putAtt("symbol", sym);
    put_grid<double>(mean, rs, [&](const point_result& p) { return mv(p).mean(); });
    auto sd = add_double(f, n + "_std", l.grid, q.units, std::string("std ") + q.long_name,
                         "sample standard deviation (n - 1 in the denominator) of " + sym);
    put_grid<double>(sd, rs, [&](const point_result& p) { return mv(p).std_dev(); });
    auto lo = add_double(f, n + "_ci95_low", l.grid, q.units, "lower 95% CI of " + sym,
                         "lower end of the 95% confidence interval of the mean of " + sym +
                             ": mean - 1.959963984540054 std / sqrt(count) (normal "
                             "approximation)");
    put_grid<double>(lo, rs, [&](const point_result& p) { return interval_end(mv(p), -1); });
    auto hi = add_double(f, n + "_ci95_high", l.grid, q.units, "upper 95% CI of " + sym,
                         "upper end of the 95% confidence interval of the mean of " + sym +
                             ": mean + 1.959963984540054 std / sqrt(count) (normal "
                             "approximation)");
    put_grid<double>(hi, rs, [&](const point_result& p) { return interval_end(mv(p), 1); });
    auto count = add_count(f, n + "_count", l.grid, "samples of " + sym,
                           std::string("number of ") + q.counted);
    put_grid<long long>(count, rs, [&](const point_result& p) { return mv(p).count(); });
  }
}

void write_counts(nc::NcFile& f, const layout_info& l, const result_set& rs) {
  auto n = add_count(f, "realizations", l.grid, "realizations",
                     "independent realizations simulated at the point (with a precision "
                     "target, target_ci_*, the number its stop rule chose)");
  put_grid<long long>(n, rs, [](const point_result& p) { return p.stats.realizations; });
  for (const auto& c : counters()) {
    auto v = add_count(f, c.name, l.grid, c.long_name, c.description);
    put_grid<long long>(v, rs, [&](const point_result& p) { return c.value(p.stats); });
  }
}

namespace {

// The value (side 0) or an end of the interval (side -1, +1) of an
// estimate; NaN where it does not exist.
double estimate_end(const std::optional<estimate_value>& e, int side) {
  if (!e) return nan;
  const auto& v = e->value;
  if (side == 0) return v.value;
  return side < 0 ? v.value - v.ci95_half_width() : v.value + v.ci95_half_width();
}

// The variables of an estimate: the value (named with the row's
// value_suffix) and the two ends of its interval.
struct estimate_column {
  const char* suffix;
  int side;
};
std::array<estimate_column, 3> estimate_columns(const estimate_info& row) {
  return {{{row.value_suffix, 0}, {"_ci95_low", -1}, {"_ci95_high", 1}}};
}

// The estimates of quantity q at index i of `row` over the grid: the value,
// its interval and the row's extra; nothing when no point has the estimate.
void write_estimate(nc::NcFile& f, const layout_info& l, const result_set& rs,
                    std::span<const estimate_source> sources, const estimate_info& row,
                    const quantity_info& q, std::size_t i) {
  std::vector<std::optional<estimate_value>> at;
  at.reserve(sources.size());
  for (const auto& s : sources) at.push_back(row.at(s, q, i));
  if (std::none_of(at.begin(), at.end(), [](const auto& e) { return e.has_value(); })) return;
  const auto of = [&](const point_result& p) -> const std::optional<estimate_value>& {
    return at[static_cast<std::size_t>(&p - rs.points.data())];
  };
  const std::string index = estimate_index_name(row, rs.spec, i);
  const std::string name = estimate_variable(row, q.name, index);
  const std::string units = estimate_units(row, q, index);
  for (const auto& c : estimate_columns(row)) {
    auto v = add_double(f, name + c.suffix, l.grid, units,
                        estimate_long_name(row, q, index, c.side),
                        estimate_description(row, q, index, c.side));
    put_grid<double>(v, rs, [&](const point_result& p) { return estimate_end(of(p), c.side); });
  }
  const std::string extra = name + "_" + extra_name(row.extra);
  switch (row.extra) {
    case estimate_extra::none: break;
    case estimate_extra::variance_reduction: {
      auto v = add_double(f, extra, l.grid, "1", extra_long_name(row, q, index),
                          extra_description(row, q, index));
      put_grid<double>(v, rs, [&](const point_result& p) {
        return of(p) ? of(p)->variance_reduction : nan;
      });
      break;
    }
    case estimate_extra::pairs: {
      auto v = add_count(f, extra, l.grid, extra_long_name(row, q, index),
                         extra_description(row, q, index));
      put_grid<long long>(v, rs, [&](const point_result& p) {
        return of(p) ? static_cast<long long>(of(p)->pairs) : 0LL;
      });
      break;
    }
  }
}

// The estimates of quantity q over the generator's entries q_ij: one
// variable over (grid, belt_level, belt_level_to), NaN for i = j and where
// q_ij = 0.
void write_entry_estimates(nc::NcFile& f, const layout_info& l, const result_set& rs,
                           std::span<const estimate_source> sources, const estimate_info& row,
                           const quantity_info& q, const nc::NcDim& level_to) {
  const std::size_t n = l.levels;
  const auto dims = with(with(l.grid, l.level), level_to);
  const std::string index = estimate_index_name(row, rs.spec, 0);
  const std::string name = estimate_variable(row, q.name, index);
  const std::string units = estimate_units(row, q, index);
  for (const auto& c : estimate_columns(row)) {
    auto v = add_double(f, name + c.suffix, dims, units, estimate_long_name(row, q, index, c.side),
                        estimate_description(row, q, index, c.side));
    put_rows<double>(v, rs, n * n, [&](const point_result& p, std::vector<double>& values) {
      const auto& s = sources[static_cast<std::size_t>(&p - rs.points.data())];
      for (std::size_t ij = 0; ij < n * n; ++ij)
        values[ij] = estimate_end(row.at(s, q, ij), c.side);
    });
  }
}

}  // namespace

// The estimate table (estimates.hpp), row by row: for each selected quantity
// that has the row and each index, <variable> with <variable>_ci95_low and
// _ci95_high (and the row's extra), NaN at the points where the estimate
// does not exist, written only when some point has it (no variable is NaN
// everywhere). A generator's entries add the dimension belt_level_to.
void write_estimates(nc::NcFile& f, const layout_info& l, const result_set& rs) {
  const auto& sel = rs.spec.statistics;
  if (!selects_estimates(sel)) return;
  const auto slopes = precision::crn_slopes(rs);  // empty without CRN and records
  const auto sources = estimate_sources(rs, slopes);
  std::optional<nc::NcDim> level_to;
  for (const auto& row : estimate_kinds()) {
    if (!(sel.*row.group)) continue;
    if (row.index == estimate_index::generator_entry && !level_to &&
        std::any_of(sources.begin(), sources.end(), row.applies)) {
      level_to = f.addDim("belt_level_to", l.levels);
      auto number = f.addVar("belt_level_to", nc::ncInt, *level_to);
      describe(number, "1", "belt level number (to)",
               "number j = 1..n of the level a jump of the belt goes to");
      number.putVar(level_numbers(l.levels).data());
    }
    for (const auto& q : quantities()) {
      if (!selects(sel, row, q)) continue;
      if (row.index == estimate_index::generator_entry) {
        if (level_to) write_entry_estimates(f, l, rs, sources, row, q, *level_to);
        continue;
      }
      for (const auto i : estimate_indices(row, rs.spec))
        write_estimate(f, l, rs, sources, row, q, i);
    }
  }
}

namespace {

// Bin i of histogram h: [edge(h, i), edge(h, i + 1)], the last edge exactly hi.
double bin_edge(const histogram& h, std::size_t i) {
  return i == h.bins() ? h.hi()
                       : h.lo() + (h.hi() - h.lo()) * static_cast<double>(i) /
                                      static_cast<double>(h.bins());
}

}  // namespace

// Per binned quantity X: X_density and X_counts over (grid, bin), with the
// auxiliary coordinate X_bin (bin centres; CF `bounds` = X_bin_bounds over
// (grid, bin, nv)), so xarray plots a histogram against its own bins:
//   ds.X_density.sel(lambda=1, mu=5).plot(x="X_bin")
// X_bin_low and X_bin_high repeat the two ends of each bin as plain variables.
void write_histograms(nc::NcFile& f, const layout_info& l, const result_set& rs) {
  const auto dims = with(l.grid, l.bin);
  for (const auto& q : quantities()) {
    // (means_only fills no histogram)
    if (!q.density || rs.spec.means_only || !selects(rs.spec.statistics, q)) continue;
    const std::string n = q.name, sym = q.symbol;
    const std::string density_units =
        std::string(q.units) == "1" ? "1" : fmt::format("1/{}", q.units);
    const auto hist = [&](const point_result& p) -> const histogram& { return p.stats.*q.density; };
    const auto edges = [&](std::size_t shift) {
      return [&, shift](const point_result& p, std::vector<double>& row) {
        const auto& hh = hist(p);
        for (std::size_t i = 0; i < row.size(); ++i)
          row[i] = i < hh.bins() ? bin_edge(hh, i + shift) : nan;
      };
    };
    auto centre = add_double(f, n + "_bin", dims, q.units, q.long_name,
                             fmt::format("centre of each histogram bin of {} {}; the bin "
                                         "ranges differ between grid points",
                                         q.long_name, sym));
    if (defining()) centre.putAtt("bounds", n + "_bin_bounds");
    put_rows<double>(centre, rs, l.bins, [&](const point_result& p, std::vector<double>& row) {
      const auto& hh = hist(p);
      for (std::size_t i = 0; i < row.size(); ++i)
        row[i] = i < hh.bins() ? 0.5 * (bin_edge(hh, i) + bin_edge(hh, i + 1)) : nan;
    });
    auto bounds = add_double(f, n + "_bin_bounds", with(dims, l.bounds), q.units,
                             "bin bounds of " + sym, "lower and upper edge of each bin");
    put_rows<double>(bounds, rs, 2 * l.bins, [&](const point_result& p, std::vector<double>& row) {
      const auto& hh = hist(p);
      for (std::size_t i = 0; i < l.bins; ++i) {
        row[2 * i] = i < hh.bins() ? bin_edge(hh, i) : nan;
        row[2 * i + 1] = i < hh.bins() ? bin_edge(hh, i + 1) : nan;
      }
    });
    auto density = add_double(
        f, n + "_density", dims, density_units, "density of " + sym,
        fmt::format("probability density of {0} {1}: count / (total * bin width) on "
                    "[{2}_bin_low, {2}_bin_high); total includes {2}_underflow and "
                    "{2}_overflow, so the density integrates to the fraction of samples inside "
                    "the binned range. The last bin is closed on the right.",
                    q.long_name, sym, n));
    if (defining()) density.putAtt("coordinates", n + "_bin");
    put_rows<double>(density, rs, l.bins, [&](const point_result& p, std::vector<double>& row) {
      const auto& hh = hist(p);
      for (std::size_t i = 0; i < row.size(); ++i) row[i] = i < hh.bins() ? hh.density(i) : nan;
    });
    auto low = add_double(f, n + "_bin_low", dims, q.units, "lower bin edge of " + sym,
                          "lower edge of each histogram bin; bin ranges differ between grid "
                          "points");
    put_rows<double>(low, rs, l.bins, edges(0));
    auto high = add_double(f, n + "_bin_high", dims, q.units, "upper bin edge of " + sym,
                           "upper edge of each histogram bin; bin ranges differ between grid "
                           "points");
    put_rows<double>(high, rs, l.bins, edges(1));
    auto counts = add_count(f, n + "_counts", dims, "bin counts of " + sym, "samples in each bin");
    if (defining()) counts.putAtt("coordinates", n + "_bin");
    put_rows<long long>(counts, rs, l.bins, [&](const point_result& p, std::vector<long long>& row) {
      const auto& hh = hist(p);
      for (std::size_t i = 0; i < row.size(); ++i)
        row[i] = i < hh.bins() ? static_cast<long long>(hh.count(i)) : 0;
    });
    auto under = add_count(f, n + "_underflow", l.grid, "samples of " + sym + " below bins",
                           "samples below the lower edge of the first bin");
    put_grid<long long>(under, rs, [&](const point_result& p) { return hist(p).underflow(); });
    auto over = add_count(f, n + "_overflow", l.grid, "samples of " + sym + " above bins",
                          "samples above the upper edge of the last bin");
    put_grid<long long>(over, rs, [&](const point_result& p) { return hist(p).overflow(); });
  }
}

// Per level quantity P (schema level_table): P_mean, P_std, P_ci95_low,
// P_ci95_high, P_count over (grid, belt_level), and the level values
// belt_level_velocity over (grid, belt_level).
void write_level_statistics(nc::NcFile& f, const layout_info& l, const result_set& rs) {
  const auto dims = with(l.grid, l.level);
  auto vel = add_double(f, "belt_level_velocity", dims, "m/s", "belt level v_j",
                        "velocity v_j of each belt level at each grid point", false);
  put_rows<double>(vel, rs, l.levels, [&](const point_result& p, std::vector<double>& row) {
    const auto v = p.parameters.levels();
    for (std::size_t i = 0; i < row.size(); ++i) row[i] = i < v.size() ? v[i] : nan;
  });
  for (const auto& q : level_quantities()) {
    if (!selects(rs.spec.statistics, q)) continue;
    const std::string n = q.name, sym = q.symbol;
    const auto at = [&](const point_result& p, std::size_t i) -> const mean_variance& {
      return (p.stats.*q.moments)[i];
    };
    struct column {
      std::string suffix, long_name, description;
      double (*value)(const mean_variance&);
    };
    const column columns[] = {
        {"_mean", std::string("mean ") + q.long_name,
         fmt::format("{} {}: {}", q.long_name, sym, q.description),
         [](const mean_variance& m) { return m.mean(); }},
        {"_std", std::string("std ") + q.long_name,
         "sample standard deviation (n - 1 in the denominator) of " + sym + " at each level",
         [](const mean_variance& m) { return m.std_dev(); }},
        {"_ci95_low", "lower 95% CI of " + sym,
         "lower end of the 95% confidence interval of the mean of " + sym +
             ": mean - 1.959963984540054 std / sqrt(count) (normal approximation)",
         [](const mean_variance& m) { return interval_end(m, -1); }},
        {"_ci95_high", "upper 95% CI of " + sym,
         "upper end of the 95% confidence interval of the mean of " + sym +
             ": mean + 1.959963984540054 std / sqrt(count) (normal approximation)",
         [](const mean_variance& m) { return interval_end(m, 1); }},
    };
    for (const auto& c : columns) {
      auto v = add_double(f, n + c.suffix, dims, q.units, c.long_name, c.description);
      if (defining()) {
        if (c.suffix == "_mean") v.putAtt("symbol", sym);
        v.putAtt("coordinates", "belt_level_velocity");
      }
      put_rows<double>(v, rs, l.levels, [&](const point_result& p, std::vector<double>& row) {
        for (std::size_t i = 0; i < row.size(); ++i) row[i] = c.value(at(p, i));
      });
    }
    auto count = add_count(f, n + "_count", dims, "samples of " + sym, "number of realizations");
    put_rows<long long>(count, rs, l.levels, [&](const point_result& p, std::vector<long long>& row) {
      for (std::size_t i = 0; i < row.size(); ++i) row[i] = static_cast<long long>(at(p, i).count());
    });
  }
}

// Per joint histogram J of (X, Y) (schema joint_table): J_counts over (grid,
// bin, bin_y), the bins of X_bin and Y_bin; J_outside over the grid: samples
// outside either range (left out of J_counts).
void write_joint_histograms(nc::NcFile& f, const layout_info& l, const result_set& rs) {
  if (!selects_joint_histograms(rs.spec.statistics) || rs.spec.means_only) return;
  const auto dims = with(with(l.grid, l.bin), l.bin_y);
  for (const auto& j : joint_histograms()) {
    const std::string n = j.name, x = quantity_table[j.x].name, y = quantity_table[j.y].name;
    auto counts = add_count(f, n + "_counts", dims, j.long_name,
                            fmt::format("{}; bins: {}_bin_low/high (dimension bin), {}_bin_low/high "
                                        "(dimension bin_y); samples outside either range are in {}_outside",
                                        j.description, x, y, n));
    put_rows<long long>(counts, rs, l.bins * l.bins,
                        [&](const point_result& p, std::vector<long long>& row) {
                          const auto& h = p.stats.*j.counts;
                          for (std::size_t a = 0; a < l.bins; ++a)
                            for (std::size_t b = 0; b < l.bins; ++b)
                              row[a * l.bins + b] = a < h.x_binning().bins() && b < h.y_binning().bins()
                                                        ? static_cast<long long>(h.count(a, b))
                                                        : 0;
                        });
    auto outside = add_count(f, n + "_outside", l.grid, "sticks outside D-X bins",
                             "samples outside the range of either quantity (not in " + n + "_counts)");
    put_grid<long long>(outside, rs, [&](const point_result& p) { return (p.stats.*j.counts).outside(); });
  }
}

}  // namespace stickslip::io::detail::results_nc
