// The pieces of results.nc (writer_netcdf.cpp writes the file): its layout
// (dimensions), the helpers that define, describe, compress and fill its
// variables, and one function per group of variables, each in the file of
// its concern: results_nc_statistics.cpp (the schema's statistics, counts,
// estimates, histograms, level and joint statistics), results_nc_time.cpp
// (survival curves, observe times, convergence traces). Private to the io
// library.
#pragma once
#include <netcdf>

#include <algorithm>
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "stickslip/parameters.hpp"
#include "stickslip/sweep.hpp"
#include "writers_detail.hpp"

namespace stickslip::io::detail::results_nc {

namespace nc = netCDF;
inline constexpr double nan = std::numeric_limits<double>::quiet_NaN();

struct layout_info {
  std::vector<nc::NcDim> grid;  // grid dims
  nc::NcDim bin, bin_y, bounds, trace, level;
  std::size_t bins = 0, trace_length = 0, levels = 0;
  std::vector<std::string> meaningless;  // meaningless_parameters of the grid
};

// A variable's units, long_name and (when not empty) description attributes.
void describe(const nc::NcVar& v, const std::string& units, const std::string& long_name,
              const std::string& description);

// The level numbers 1..n (the coordinate of belt_level and belt_level_to).
std::vector<int> level_numbers(std::size_t n);

// `dims` with `last` after them.
std::vector<nc::NcDim> with(std::vector<nc::NcDim> dims, const nc::NcDim& last);

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
// row-major order (netcdf_chunks, at most 4 MiB), and put_rows writes one
// chunk per call, so every chunk is compressed once. With netCDF's default chunks (which span
// many slabs of the first axis) the slab-wise writes of a 400 x 250 grid
// decompressed and recompressed the same chunks over and over: hours
// instead of seconds.
void compress(nc::NcVar& v, const std::vector<nc::NcDim>& dims);

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
void release_chunks(const nc::NcVar& v);

// A double (or a 64-bit count) variable over `dims`, described, compressed
// as above, and with NaN as its fill value unless `fill` is false; when not
// defining(), the one of that name the first slab defined.
nc::NcVar add_double(nc::NcFile& f, const std::string& name, const std::vector<nc::NcDim>& dims,
                     const std::string& units, const std::string& long_name,
                     const std::string& description, bool fill = true, bool deflate = true);
nc::NcVar add_count(nc::NcFile& f, const std::string& name, const std::vector<nc::NcDim>& dims,
                    const std::string& long_name, const std::string& description);

// A parameter's long_name: its long alias in words and its symbol
// ("switch rate lambda").
std::string parameter_long_name(const parameter_info& info, const std::string& symbol);

// The rows of the grid's first dimension that rs's points cover: all of them
// for a whole result set; for a slab of a run streamed window by window
// (streamed_outputs.hpp: whole rows of the first axis, in order, indexed on
// the whole grid), the slab's. `grid` is the whole grid's shape.
struct grid_rows {
  std::size_t first = 0, count = 0;
  bool whole = true;
};
[[nodiscard]] grid_rows rows_of(const result_set& rs, const std::vector<std::size_t>& grid);

// Whether the writes define results.nc (a whole result set, or the first
// slab of a streamed one: netcdf_slab.defining) or only add a slab's rows.
[[nodiscard]] inline bool defining() { return netcdf_slab.defining; }

// The shape of `v` (all of its dimensions).
[[nodiscard]] std::vector<std::size_t> shape_of(const nc::NcVar& v);

// One value per grid point, computed by `value(point)`.
template <class T, class F>
void put_grid(const nc::NcVar& v, const result_set& rs, F value) {
  std::vector<T> data;
  data.reserve(rs.points.size());
  for (const auto& p : rs.points) data.push_back(static_cast<T>(value(p)));
  const auto shape = shape_of(v);
  const auto rows = rows_of(rs, shape);
  if (rows.whole) {
    v.putVar(data.data());
  } else {
    std::vector<std::size_t> start(shape.size(), 0), count = shape;
    start[0] = rows.first;
    count[0] = rows.count;
    v.putVar(start, count, data.data());
  }
  if (rows.first == 0) release_chunks(v);
}

// A row of `len` values per grid point (the dimensions after the grid's).
// Written one chunk at a time (netcdf_chunks of the variable's shape, also
// for a contiguous variable): each call covers whole chunks, so each is
// compressed once, and the buffer holds at most one chunk (or one row, if a
// row alone is longer than a chunk). Relies on rs.points being in row-major
// grid order (check_shape verifies it, check_slab for a slab, whose chunks
// end at its last row: netcdf_slab).
template <class T>
void put_rows(const nc::NcVar& v, const result_set& rs, std::size_t len,
              const std::function<void(const point_result&, std::vector<T>&)>& row) {
  const auto shape = shape_of(v);
  const std::size_t grid_rank = std::max<std::size_t>(1, rs.spec.axes.size());
  const auto chunk = netcdf_chunks(shape);
  std::vector<std::size_t> grid(shape.begin(), shape.begin() + grid_rank);
  const auto rows = rows_of(rs, grid);
  grid[0] = rows.count;
  const auto runs = row_runs(grid, std::vector<std::size_t>(chunk.begin(), chunk.begin() + grid_rank));
  std::vector<T> buf, one(len);
  for (const auto& run : runs) {
    buf.resize(run.points * len);
    for (std::size_t i = 0; i < run.points; ++i) {
      row(rs.points[run.first + i], one);
      std::copy(one.begin(), one.end(), buf.begin() + static_cast<std::ptrdiff_t>(i * len));
    }
    auto start = run.start, count = run.count;
    start[0] += rows.first;
    start.resize(shape.size(), 0);
    for (std::size_t d = grid_rank; d < shape.size(); ++d) count.push_back(shape[d]);
    v.putVar(start, count, buf.data());
  }
  if (rows.first == 0) release_chunks(v);
}

// A dimension of results.nc: added when defining(), else the first slab's.
nc::NcDim dimension(nc::NcFile& f, const std::string& name, std::size_t size);

// The groups of variables, in the order write_netcdf_file writes them.
void write_statistics(nc::NcFile& f, const layout_info& l, const result_set& rs);
void write_counts(nc::NcFile& f, const layout_info& l, const result_set& rs);
void write_estimates(nc::NcFile& f, const layout_info& l, const result_set& rs);
void write_histograms(nc::NcFile& f, const layout_info& l, const result_set& rs);
void write_level_statistics(nc::NcFile& f, const layout_info& l, const result_set& rs);
void write_joint_histograms(nc::NcFile& f, const layout_info& l, const result_set& rs);
void write_survival(nc::NcFile& f, const layout_info& l, const result_set& rs);
void write_observed(nc::NcFile& f, const layout_info& l, const result_set& rs);
void write_convergence(nc::NcFile& f, const layout_info& l, const result_set& rs);

}  // namespace stickslip::io::detail::results_nc
