// The helpers of results.nc's variables (results_nc.hpp).
#include "results_nc.hpp"

#include <fmt/format.h>

#include "stickslip/error.hpp"

namespace stickslip::io::detail::results_nc {
namespace {

// The variable `name` the first slab defined (a later slab's variables are
// the first's, by name).
nc::NcVar defined_variable(const nc::NcFile& f, const std::string& name) {
  auto v = f.getVar(name);
  if (v.isNull())
    throw error(exit_code::internal,
                fmt::format("results.nc: a later slab writes {}, which the first did not define",
                            name));
  return v;
}

}  // namespace

void describe(const nc::NcVar& v, const std::string& units, const std::string& long_name,
              const std::string& description) {
  v.putAtt("units", units);
  v.putAtt("long_name", long_name);
  if (!description.empty()) v.putAtt("description", description);
}

std::vector<int> level_numbers(std::size_t n) {
  std::vector<int> numbers(n);
  for (std::size_t i = 0; i < n; ++i) numbers[i] = static_cast<int>(i + 1);
  return numbers;
}

std::vector<nc::NcDim> with(std::vector<nc::NcDim> dims, const nc::NcDim& last) {
  dims.push_back(last);
  return dims;
}

void compress(nc::NcVar& v, const std::vector<nc::NcDim>& dims) {
  std::vector<std::size_t> shape;
  for (const auto& d : dims) shape.push_back(d.getSize());
  std::size_t values = 1;
  for (auto n : shape) values *= n;
  if (dims.empty() || values < 4096) return;
  auto chunks = netcdf_chunks(shape);
  v.setChunking(nc::NcVar::nc_CHUNKED, chunks);
  v.setCompression(true, true, 1);
}

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
                     const std::string& description, bool fill, bool deflate) {
  if (!defining()) return defined_variable(f, name);
  auto v = f.addVar(name, nc::ncDouble, dims);
  if (deflate) compress(v, dims);
  if (fill) v.setFill(true, nan);
  describe(v, units, long_name, description);
  return v;
}

nc::NcVar add_count(nc::NcFile& f, const std::string& name, const std::vector<nc::NcDim>& dims,
                    const std::string& long_name, const std::string& description) {
  if (!defining()) return defined_variable(f, name);
  auto v = f.addVar(name, nc::ncInt64, dims);
  compress(v, dims);
  describe(v, "1", long_name, description);
  return v;
}

grid_rows rows_of(const result_set& rs, const std::vector<std::size_t>& grid) {
  const std::size_t n = grid.empty() ? 1 : grid[0];
  if (holds_every_point(rs)) return {0, n, true};
  std::size_t slab = 1;  // points per row of the first axis
  for (std::size_t d = 1; d < grid.size(); ++d) slab *= grid[d];
  if (rs.points.empty() || rs.points.size() % slab != 0 || rs.points.front().index.empty())
    throw error(exit_code::internal,
                fmt::format("a streamed slab of {} points is not whole rows of {} points",
                            rs.points.size(), slab));
  const grid_rows rows{rs.points.front().index[0], rs.points.size() / slab, false};
  if (rows.first + rows.count > n)
    throw error(exit_code::internal, "a streamed slab runs past the grid's last row");
  return rows;
}

std::vector<std::size_t> shape_of(const nc::NcVar& v) {
  std::vector<std::size_t> shape;
  for (const auto& d : v.getDims()) shape.push_back(d.getSize());
  return shape;
}

nc::NcDim dimension(nc::NcFile& f, const std::string& name, std::size_t size) {
  if (defining()) return f.addDim(name, size);
  auto d = f.getDim(name);
  if (d.isNull() || d.getSize() != size)
    throw error(exit_code::internal,
                fmt::format("results.nc: a later slab's dimension {} is not the first slab's", name));
  return d;
}

std::string parameter_long_name(const parameter_info& info, const std::string& symbol) {
  std::string n = info.long_name;
  std::replace(n.begin(), n.end(), '-', ' ');
  return n + " " + symbol;
}


}  // namespace stickslip::io::detail::results_nc
