// The chunk shape of results.nc's compressed variables and the writes that
// cover whole chunks (writers_detail.hpp).
#include <algorithm>

#include "writers_detail.hpp"

namespace stickslip::io::detail {

std::vector<std::size_t> chunk_shape(const std::vector<std::size_t>& shape, std::size_t target) {
  target = std::max<std::size_t>(1, target);
  std::vector<std::size_t> chunk(shape.size(), 1);
  std::size_t inner = 1;  // values of the whole dimensions after d
  for (std::size_t d = shape.size(); d-- > 0;) {
    const std::size_t n = std::max<std::size_t>(1, shape[d]);
    const std::size_t fit = target / inner;  // >= 1: inner <= target
    chunk[d] = std::min(n, fit);
    if (chunk[d] < n) break;  // outer dimensions stay 1
    inner *= n;
  }
  return chunk;
}

std::vector<std::size_t> netcdf_chunks(const std::vector<std::size_t>& shape) {
  auto chunk = chunk_shape(shape, netcdf_chunk_values);
  const std::size_t rows = netcdf_slab.rows;
  if (rows == 0 || chunk.empty()) return chunk;
  std::size_t c = std::min(chunk[0], rows);
  while (rows % c != 0) --c;  // the largest divisor of rows <= chunk[0]
  chunk[0] = c;
  return chunk;
}

std::vector<row_run> row_runs(const std::vector<std::size_t>& grid,
                              const std::vector<std::size_t>& chunk) {
  const std::size_t rank = grid.size();
  // j: the innermost dimension the chunk does not hold whole (the chunk is 1
  // in the dimensions before it, whole after it), or 0 when it holds the
  // whole grid.
  std::size_t j = rank;
  while (j > 0 && chunk[j - 1] >= grid[j - 1]) --j;
  j = j == 0 ? 0 : j - 1;
  std::size_t inner = 1, points = 1;
  for (std::size_t d = j + 1; d < rank; ++d) inner *= grid[d];
  for (const auto n : grid) points *= n;
  const std::size_t step = std::max<std::size_t>(1, std::min(chunk[j], grid[j]));
  std::vector<row_run> runs;
  for (std::size_t first = 0; first < points;) {
    row_run r;
    r.first = first;
    r.start.assign(rank, 0);
    r.count.assign(rank, 1);
    std::size_t rest = first;
    for (std::size_t d = rank; d-- > 0;) {
      r.start[d] = rest % grid[d];
      rest /= grid[d];
    }
    for (std::size_t d = j + 1; d < rank; ++d) r.count[d] = grid[d];
    r.count[j] = std::min(step, grid[j] - r.start[j]);
    r.points = r.count[j] * inner;
    runs.push_back(std::move(r));
    first += runs.back().points;
  }
  return runs;
}

}  // namespace stickslip::io::detail
