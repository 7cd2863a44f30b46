// results.nc: NetCDF-4 (HDF5) file, self-describing (CF-1.8 conventions).
// Dimensions: one per swept axis, in the spec's axis order and named after
// the parameter symbol (or `point` of length 1 when nothing is swept), then
// `bin` (histogram bins), `nv` (the 2 ends of a bin) and `trace` (convergence
// trace entries).
// Point i of the result set sits at rs.points[i].index on the grid dims,
// which is row-major order of the dims (first axis outermost).
// The statistics come from the schema (statistics_schema.hpp), the derived
// estimates from the estimate table (estimates.hpp). long_name
// values stay within the 30 characters xarray puts on one line of a plot
// label (with " [units]"); the full definition is in `description`.
#include <netcdf>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <span>

#include "stickslip/error.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/survival_estimate.hpp"
#include "stickslip/uncertainty/uncertain_draws.hpp"
#include "stickslip/estimates.hpp"
#include "stickslip/precision/crn_slopes.hpp"
#include "observed_variables.hpp"
#include "writers_detail.hpp"

namespace stickslip::io {
namespace detail {
namespace {

namespace nc = netCDF;
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

struct layout_info {
  std::vector<nc::NcDim> grid;  // grid dims
  nc::NcDim bin, bin_y, bounds, trace, level;
  std::size_t bins = 0, trace_length = 0, levels = 0;
};

void describe(const nc::NcVar& v, const std::string& units, const std::string& long_name,
              const std::string& description) {
  v.putAtt("units", units);
  v.putAtt("long_name", long_name);
  if (!description.empty()) v.putAtt("description", description);
}

// The level numbers 1..n (the coordinate of belt_level and belt_level_to).
std::vector<int> level_numbers(std::size_t n) {
  std::vector<int> numbers(n);
  for (std::size_t i = 0; i < n; ++i) numbers[i] = static_cast<int>(i + 1);
  return numbers;
}

std::vector<nc::NcDim> with(std::vector<nc::NcDim> dims, const nc::NcDim& last) {
  dims.push_back(last);
  return dims;
}

// `fill`: NaN marks values that do not exist (a mean without samples, a
// convergence entry past the trace's end); variables that always exist
// (parameters) carry no _FillValue.
// Variables of 4096 values or more are stored deflated (level 1) with the
// byte shuffle filter: statistics of neighbouring grid points share exponents
// and leading bytes, so a paper grid's file shrinks several times for a few
// percent of the write time; readers decompress transparently (xarray,
// ncdump, netCDF4). Smaller ones stay contiguous: a chunked variable's index
// costs more than deflate saves on them (a 1-point sweep's file grew from
// 162 KB to 513 KB).
// The chunks are chosen here, not by netCDF: each is a run of whole rows in
// row-major order (chunk_shape, at most 4 MiB), and put_rows writes one
// chunk per call, so every chunk is compressed once. With netCDF's default chunks (which span
// many slabs of the first axis) the slab-wise writes of a 400 x 250 grid
// decompressed and recompressed the same chunks over and over: hours
// instead of seconds.
void compress(nc::NcVar& v, const std::vector<nc::NcDim>& dims) {
  std::vector<std::size_t> shape;
  for (const auto& d : dims) shape.push_back(d.getSize());
  std::size_t values = 1;
  for (auto n : shape) values *= n;
  if (dims.empty() || values < 4096) return;
  auto chunks = chunk_shape(shape, netcdf_chunk_values);
  v.setChunking(nc::NcVar::nc_CHUNKED, chunks);
  v.setCompression(true, true, 1);
}

// Once a variable is written: its chunk cache emptied (the chunks it holds
// compressed and written now, not when the file is closed). netCDF keeps
// every variable open with a cache of at least one chunk (up to 10), so the
// last chunks of each variable stayed in memory, uncompressed, until
// close: 54 of the 172 MB peak of a 4,000-point sweep, ~400 MB on the
// 100,000-point grid. Setting the cache in data mode reopens the dataset,
// which adds a few dozen bytes of HDF5 metadata: variables of at most 2^15
// values (256 KiB of doubles: all of the paper grid's) keep their cache, at
// most ~40 MB over a file's ~150 variables. (Keeping the 100,000-point
// grid's 800 KB variables cached took its peak from 469 to 523 MB.)
void release_chunks(const nc::NcVar& v) {
  constexpr std::size_t cached_values = std::size_t{1} << 15;
  std::size_t values = 1;
  for (const auto& d : v.getDims()) values *= d.getSize();
  if (values <= cached_values) return;
  nc::NcVar::ChunkMode mode{};
  std::vector<std::size_t> sizes;
  v.getChunkingParameters(mode, sizes);
  if (mode == nc::NcVar::nc_CHUNKED) v.setChunkCache(0, 0, 1.0f);
}

nc::NcVar add_double(nc::NcFile& f, const std::string& name, const std::vector<nc::NcDim>& dims,
                     const std::string& units, const std::string& long_name,
                     const std::string& description, bool fill = true, bool deflate = true) {
  auto v = f.addVar(name, nc::ncDouble, dims);
  if (deflate) compress(v, dims);
  if (fill) v.setFill(true, nan);
  describe(v, units, long_name, description);
  return v;
}

nc::NcVar add_count(nc::NcFile& f, const std::string& name, const std::vector<nc::NcDim>& dims,
                    const std::string& long_name, const std::string& description) {
  auto v = f.addVar(name, nc::ncInt64, dims);
  compress(v, dims);
  describe(v, "1", long_name, description);
  return v;
}

// A parameter's long_name: its long alias in words and its symbol
// ("switch rate lambda").
std::string parameter_long_name(const parameter_info& info, const std::string& symbol) {
  std::string n = info.long_name;
  std::replace(n.begin(), n.end(), '-', ' ');
  return n + " " + symbol;
}

// One value per grid point, computed by `value(point)`.
template <class T, class F>
void put_grid(const nc::NcVar& v, const result_set& rs, F value) {
  std::vector<T> data;
  data.reserve(rs.points.size());
  for (const auto& p : rs.points) data.push_back(static_cast<T>(value(p)));
  v.putVar(data.data());
  release_chunks(v);
}

// A row of `len` values per grid point (the dimensions after the grid's).
// Written one chunk at a time (chunk_shape of the variable's shape, also for
// a contiguous variable): each call covers whole chunks, so each is
// compressed once, and the buffer holds at most one chunk (or one row, if a
// row alone is longer than a chunk). Relies on rs.points being in row-major
// grid order (check_shape verifies it).
template <class T>
void put_rows(const nc::NcVar& v, const result_set& rs, std::size_t len,
              const std::function<void(const point_result&, std::vector<T>&)>& row) {
  const auto dims = v.getDims();
  std::vector<std::size_t> shape;
  for (const auto& d : dims) shape.push_back(d.getSize());
  const std::size_t grid_rank = std::max<std::size_t>(1, rs.spec.axes.size());
  const auto chunk = chunk_shape(shape, netcdf_chunk_values);
  const auto runs = row_runs(std::vector<std::size_t>(shape.begin(), shape.begin() + grid_rank),
                             std::vector<std::size_t>(chunk.begin(), chunk.begin() + grid_rank));
  std::vector<T> buf, one(len);
  for (const auto& run : runs) {
    buf.resize(run.points * len);
    for (std::size_t i = 0; i < run.points; ++i) {
      row(rs.points[run.first + i], one);
      std::copy(one.begin(), one.end(), buf.begin() + static_cast<std::ptrdiff_t>(i * len));
    }
    auto start = run.start, count = run.count;
    start.resize(shape.size(), 0);
    for (std::size_t d = grid_rank; d < shape.size(); ++d) count.push_back(shape[d]);
    v.putVar(start, count, buf.data());
  }
  release_chunks(v);
}

layout_info define_dimensions(nc::NcFile& f, const result_set& rs) {
  layout_info l;
  const auto& spec = rs.spec;
  if (spec.axes.empty()) {
    l.grid.push_back(f.addDim("point", 1));
  } else {
    for (const auto& ax : spec.axes) {
      const std::string sym = canonical_symbol(ax.name);
      const auto& info = info_for(sym);
      auto dim = f.addDim(sym, ax.values.size());
      l.grid.push_back(dim);
      auto v = f.addVar(sym, nc::ncDouble, dim);
      describe(v, info.units, parameter_long_name(info, sym),
               fmt::format("swept model parameter {}: {}", sym, info.description));
      v.putVar(ax.values.data());
    }
  }
  l.bins = std::max<std::size_t>(1, spec.histograms.bins);
  l.bin = f.addDim("bin", l.bins);
  l.bounds = f.addDim("nv", 2);
  for (const auto& p : rs.points) l.trace_length = std::max(l.trace_length, p.stats.convergence.size());
  l.trace_length = std::max<std::size_t>(1, l.trace_length);
  l.trace = f.addDim("trace", l.trace_length);
  // The belt levels: their number cannot be swept, so one dimension fits all
  // points; the level values (which can) are belt_level_velocity over the grid.
  l.levels = rs.spec.base.levels().size();
  l.level = f.addDim("belt_level", l.levels);
  auto level_index = f.addVar("belt_level", nc::ncInt, l.level);
  describe(level_index, "1", "belt level number", "number j = 1..n of the belt level v_j");
  level_index.putVar(level_numbers(l.levels).data());
  // The second bin dimension of the joint histograms (the same length as bin).
  if (!joint_histograms().empty()) l.bin_y = f.addDim("bin_y", l.bins);
  return l;
}

void write_parameters(nc::NcFile& f, const layout_info& l, const result_set& rs) {
  // Every recorded scalar that defines the model (meaningless_parameters),
  // then the swept belt levels and rates (vI, rI).
  const auto omitted = meaningless_parameters(rs);
  std::vector<std::string> symbols;
  for (const char* sym : recorded_parameter_names)
    if (std::find(omitted.begin(), omitted.end(), sym) == omitted.end()) symbols.emplace_back(sym);
  for (const auto& sym : swept_symbols(rs.spec))
    if (std::find(symbols.begin(), symbols.end(), sym) == symbols.end()) symbols.push_back(sym);
  // A parameter set by a law has no one value: the variable holds its law's
  // median (what the point's ETA and derived scales use) and says so.
  const auto by_laws = symbols_set_by_laws(rs.spec.uncertain);
  for (const auto& sym : symbols) {
    const auto& info = info_for(sym);
    const bool uncertain = std::find(by_laws.begin(), by_laws.end(), sym) != by_laws.end();
    auto v = add_double(f, parameter_variable_name(sym), l.grid, info.units,
                        parameter_long_name(info, sym),
                        uncertain ? fmt::format("the median of the law of model parameter {} "
                                                "(uncertain: each realization draws its own "
                                                "value; see the uncertain_parameters attribute): "
                                                "{}",
                                                sym, info.description)
                                  : fmt::format("model parameter {} at each grid point: {}", sym,
                                                info.description),
                        false);
    v.putAtt("symbol", sym);
    if (uncertain) v.putAtt("value_is", "median of the law");
    put_grid<double>(v, rs, [&](const point_result& p) { return parameter_value(p.parameters, sym); });
  }
  auto a = add_double(f, "band_half_width", l.grid, "m", "stick band half-width a",
                      "a = mu_s m g / k: the mass can stick only while |x + c v / k| <= a "
                      "(|x| <= a without damping)",
                      false);
  put_grid<double>(a, rs, [](const point_result& p) { return p.parameters.band_half_width(); });
  auto w = add_double(f, "natural_frequency", l.grid, "rad/s", "natural frequency",
                      "omega = sqrt(k / m)", false);
  put_grid<double>(w, rs, [](const point_result& p) { return p.parameters.natural_frequency(); });
  auto d = add_double(f, "max_stick_duration", l.grid, "s", "longest stick d_max",
                      "d_max = 2 a / V: a stick that crosses the whole band (Markov belt: 2 a / "
                      "smallest nonzero |v_i|, at least 5 / rate of leaving a level v = 0)",
                      false);
  put_grid<double>(d, rs, [](const point_result& p) { return p.parameters.max_stick_duration(); });
}

// The lower (side -1) or upper (+1) end of the 95% interval of a mean
// (mean_estimate: mean -+ 1.96 std / sqrt(count)).
double interval_end(const mean_variance& m, int side) {
  const auto e = mean_estimate(m);
  return side < 0 ? e.value - e.ci95_half_width() : e.value + e.ci95_half_width();
}

void write_statistics(nc::NcFile& f, const layout_info& l, const result_set& rs) {
  for (const auto& q : quantities()) {
    if (!selects(rs.spec.statistics, q)) continue;
    const std::string n = q.name, sym = q.symbol;
    const auto mv = [&](const point_result& p) -> const mean_variance& { return p.stats.*q.moments; };
    auto mean = add_double(f, n + "_mean", l.grid, q.units, std::string("mean ") + q.long_name,
                           fmt::format("{} {}: {}", q.long_name, sym, q.description));
    mean.putAtt("symbol", sym);
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

// Bin i of histogram h: [edge(h, i), edge(h, i + 1)], the last edge exactly hi.
double bin_edge(const histogram& h, std::size_t i) {
  return i == h.bins() ? h.hi()
                       : h.lo() + (h.hi() - h.lo()) * static_cast<double>(i) /
                                      static_cast<double>(h.bins());
}

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
    centre.putAtt("bounds", n + "_bin_bounds");
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
    density.putAtt("coordinates", n + "_bin");
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
    counts.putAtt("coordinates", n + "_bin");
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
      if (c.suffix == "_mean") v.putAtt("symbol", sym);
      v.putAtt("coordinates", "belt_level_velocity");
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

// The survival group: per law (stick, slip) a duration coordinate (the edges
// of the survival grid, shared by all points), the Kaplan-Meier curve with
// its interval and the numbers at risk over it, and the restricted mean.
void write_survival(nc::NcFile& f, const layout_info& l, const result_set& rs) {
  if (!rs.spec.statistics.survival) return;
  const auto& g = rs.spec.survival;
  for (const auto& law : survival_laws()) {
    const std::string name = law.name, coordinate = law.coordinate;
    const auto edges = survival_edges(g.*law.upper, g.bins);
    const auto dim = f.addDim(coordinate, edges.size());
    auto c = f.addVar(coordinate, nc::ncDouble, dim);
    std::string words = coordinate;
    std::replace(words.begin(), words.end(), '_', ' ');
    describe(c, "s", words,
             fmt::format("{} {}: the edges of the survival grid, {} bins on [0, {}] s, at "
                         "which the survival curve is evaluated",
                         words, law.symbol, g.bins, g.*law.upper));
    c.putVar(edges.data());
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
  const auto time = f.addDim("time", times.size());
  auto t = f.addVar("time", nc::ncDouble, time);
  describe(t, "s", "observation time",
           "the observe times t of sweep --observe-times, at which the state of every "
           "realization is taken from its closed-form motion (no interpolation)");
  t.putAtt("axis", "T");
  t.putVar(times.data());
  const std::size_t quantiles = std::size(observed_quantile_levels);
  const auto quantile = f.addDim("quantile", quantiles);
  auto q = f.addVar("quantile", nc::ncDouble, quantile);
  describe(q, "1", "quantile level", "the levels q of the quantile variables");
  q.putVar(observed_quantile_levels);
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

void write_global_attributes(nc::NcFile& f, const result_set& rs, const run_metadata& meta) {
  const auto& s = rs.spec;
  f.putAtt("title",
           "stickslip parametric sweep: statistics of a dry-friction oscillator on a belt "
           "whose direction switches at Poisson times");
  f.putAtt("Conventions", "CF-1.8");
  f.putAtt("source", fmt::format("stickslip {} (git {})", meta.version, meta.git_revision));
  f.putAtt("history", fmt::format("{}: {}", meta.created_utc, meta.command_line));
  std::string symbols, binned;
  for (const auto& q : quantities()) {
    symbols += fmt::format("{}{}", symbols.empty() ? "" : ", ", q.symbol);
    if (q.density) binned += fmt::format("{}{}", binned.empty() ? "" : ", ", q.symbol);
  }
  f.putAtt("comment",
           fmt::format("Exact event-driven simulation. Per grid point: mean, std and 95% CI of "
                       "{}; histograms (densities) of {} over dimension bin, with bin "
                       "coordinates and bounds; convergence traces over dimension trace. "
                       "Parameters that are not swept are global attributes named by their "
                       "symbol; every parameter is also a variable over the grid. Only the "
                       "parameters that define the model are written (mu only when mu_s = "
                       "mu_k = mu, V only on a (+V, -V) belt, lambda only with Poisson "
                       "switching), and only the derivatives that apply to it.",
                       symbols, binned));
  f.putAtt("version", meta.version);
  f.putAtt("git_revision", meta.git_revision);
  f.putAtt("command_line", meta.command_line);
  f.putAtt("created_utc", meta.created_utc);
  f.putAtt("resolved_config", meta.resolved_config);
  f.putAtt("seed", nc::ncUint64, static_cast<unsigned long long>(s.seed));
  f.putAtt("realizations", nc::ncUint64, static_cast<unsigned long long>(s.realizations));
  f.putAtt("block_size", nc::ncUint64, static_cast<unsigned long long>(s.block_size));
  f.putAtt("max_events", nc::ncInt64, static_cast<long long>(s.max_events));
  f.putAtt("keep_records", nc::ncInt, s.keep_records ? 1 : 0);
  f.putAtt("common_random_numbers", nc::ncInt, s.common_random_numbers ? 1 : 0);
  if (!s.target_statistic.empty()) {
    f.putAtt("target_ci_statistic", s.target_statistic);
    f.putAtt("target_ci_halfwidth", nc::ncDouble, s.target_halfwidth);
    f.putAtt("min_realizations", nc::ncUint64, static_cast<unsigned long long>(s.min_realizations));
  }
  f.putAtt("statistics", to_string(s.statistics));
  // Only with a burn-in: without one the file is what it was before.
  if (s.burn_in != 0.0) f.putAtt("burn_in", nc::ncDouble, s.burn_in);
  if (s.statistics.survival) {
    f.putAtt("survival_bins", nc::ncUint64, static_cast<unsigned long long>(s.survival.bins));
    f.putAtt("survival_stick_duration_max", nc::ncDouble, s.survival.stick_duration_max);
    f.putAtt("survival_slip_duration_max", nc::ncDouble, s.survival.slip_duration_max);
  }
  f.putAtt("histogram_bins", nc::ncUint64, static_cast<unsigned long long>(s.histograms.bins));
  f.putAtt("histogram_stick_duration_max", nc::ncDouble, s.histograms.stick_duration_max);
  f.putAtt("histogram_slip_duration_max", nc::ncDouble, s.histograms.slip_duration_max);
  f.putAtt("initial_position_min", nc::ncDouble, s.initial.position_min);
  f.putAtt("initial_position_max", nc::ncDouble, s.initial.position_max);
  f.putAtt("initial_velocity_min", nc::ncDouble, s.initial.velocity_min);
  f.putAtt("initial_velocity_max", nc::ncDouble, s.initial.velocity_max);
  f.putAtt("initial_belt_start", belt_start_text(s.initial.belt_start));
  std::string swept;
  for (const auto& sym : swept_symbols(s)) swept += (swept.empty() ? "" : " ") + sym;
  f.putAtt("swept_parameters", swept);
  // Uncertain parameters: drawn per realization, each from the law in the
  // attribute <symbol>_law; their grid variables hold the laws' medians.
  std::string uncertain;
  for (const auto& u : s.uncertain) {
    uncertain += (uncertain.empty() ? "" : " ") + u.symbol;
    f.putAtt(u.symbol + "_law", to_string(u.law));
  }
  if (!uncertain.empty()) f.putAtt("uncertain_parameters", uncertain);
  const auto sw = swept_symbols(s);
  const auto omitted = meaningless_parameters(rs);
  const auto by_laws = symbols_set_by_laws(s.uncertain);
  const auto is_uncertain = [&](const char* sym) {
    return std::find(by_laws.begin(), by_laws.end(), sym) != by_laws.end();
  };
  for (const char* sym : recorded_parameter_names)
    if (std::find(sw.begin(), sw.end(), sym) == sw.end() && !is_uncertain(sym) &&
        std::find(omitted.begin(), omitted.end(), sym) == omitted.end())
      f.putAtt(sym, nc::ncDouble, parameter_value(resolved_base(rs), sym));
  // The resolved belt of the base (a swept vI or rI is a coordinate instead):
  // levels v_i [m/s] and the generator Q, row-major [1/s].
  const auto levels = s.base.levels();
  const auto q = s.base.generator();
  f.putAtt("belt_levels", nc::ncDouble, levels.size(), levels.data());
  f.putAtt("belt_generator", nc::ncDouble, q.size(), q.data());
  f.putAtt("threads", nc::ncInt, static_cast<int>(rs.threads));
  f.putAtt("ranks", nc::ncInt, static_cast<int>(rs.ranks));
  f.putAtt("elapsed_seconds", nc::ncDouble, rs.elapsed_seconds);
}

void write_netcdf_file(const result_set& rs, const run_metadata& meta, const std::string& file) {
  nc::NcFile f(file, nc::NcFile::replace, nc::NcFile::nc4);
  write_global_attributes(f, rs, meta);
  const auto l = define_dimensions(f, rs);
  write_parameters(f, l, rs);
  write_statistics(f, l, rs);
  write_counts(f, l, rs);
  write_estimates(f, l, rs);
  write_histograms(f, l, rs);
  write_level_statistics(f, l, rs);
  write_joint_histograms(f, l, rs);
  write_survival(f, l, rs);
  write_observed(f, l, rs);
  write_convergence(f, l, rs);
  f.close();
}

}  // namespace

void write_netcdf_temporary(const result_set& rs, const run_metadata& meta,
                            const std::string& path) {
  check_shape(rs);
  write_netcdf_temporary_with(path, [&](const std::string& tmp) { write_netcdf_file(rs, meta, tmp); });
}

void write_netcdf_temporary_with(const std::string& path,
                                 const std::function<void(const std::string&)>& fill) {
  const std::string tmp = temporary_path(path);
  try {
    fill(tmp);
    sync_file(tmp, path);
  } catch (const nc::exceptions::NcException& e) {
    remove_file_quietly(tmp);
    throw io_error(path, fmt::format("NetCDF: {}", e.what()));
  } catch (const stickslip::error&) {
    remove_file_quietly(tmp);
    throw;
  } catch (const std::exception& e) {
    remove_file_quietly(tmp);
    throw io_error(path, e.what());
  }
}

}  // namespace detail

void write_netcdf(const result_set& rs, const run_metadata& meta, const std::string& path) {
  detail::write_netcdf_temporary(rs, meta, path);
  try {
    detail::commit_rename(detail::temporary_path(path), path);
  } catch (...) {
    detail::remove_file_quietly(detail::temporary_path(path));
    throw;
  }
}

}  // namespace stickslip::io
