// Joint histogram of two quantities (x, y), each binned exactly like a 1-D
// histogram of it (histogram::slot): (bins_x + 2) x (bins_y + 2) cells, the
// first and last row and column holding the samples below and above the
// range. Summing the cells over y (flow cells included) gives the 1-D counts
// of x, underflow and overflow included, exactly; and the same for y. A value
// type: add, an exact merge (cell-wise sums), ==.
#pragma once
#include <cassert>
#include <cstdint>
#include <utility>
#include <vector>

#include "stickslip/accumulators/histogram.hpp"

namespace stickslip {

class histogram2d {
 public:
  histogram2d() = default;
  // The binnings of x and y (their counts are not taken).
  histogram2d(const histogram& x, const histogram& y)
      : x_(x.lo(), x.hi(), x.bins()), y_(y.lo(), y.hi(), y.bins()),
        cells_((x_.bins() + 2) * (y_.bins() + 2), 0) {}

  void add(double x, double y) noexcept { ++cells_[x_.slot(x) * (y_.bins() + 2) + y_.slot(y)]; }
  // Precondition: same binning.
  histogram2d& operator+=(const histogram2d& o) noexcept {
    for (std::size_t i = 0; i < cells_.size(); ++i) cells_[i] += o.cells_[i];
    return *this;
  }
  [[nodiscard]] bool same_binning(const histogram2d& o) const noexcept {
    return x_.same_binning(o.x_) && y_.same_binning(o.y_);
  }
  // The binnings (their counts are always zero).
  [[nodiscard]] const histogram& x_binning() const noexcept { return x_; }
  [[nodiscard]] const histogram& y_binning() const noexcept { return y_; }
  // Cell (i, j) in slots: 0 = below, 1..bins = bin - 1, bins + 1 = above.
  [[nodiscard]] std::uint64_t cell(std::size_t i, std::size_t j) const noexcept {
    return cells_[i * (y_.bins() + 2) + j];
  }
  // Bin (i, j) of the ranges (0-based, both inside).
  [[nodiscard]] std::uint64_t count(std::size_t i, std::size_t j) const noexcept {
    return cell(i + 1, j + 1);
  }
  // Samples outside the range in x or y (or both).
  [[nodiscard]] std::uint64_t outside() const noexcept {
    std::uint64_t n = 0;
    for (std::size_t i = 0; i < x_.bins() + 2; ++i)
      for (std::size_t j = 0; j < y_.bins() + 2; ++j)
        if (i == 0 || j == 0 || i == x_.bins() + 1 || j == y_.bins() + 1) n += cell(i, j);
    return n;
  }
  [[nodiscard]] std::uint64_t total() const noexcept {
    std::uint64_t n = 0;
    for (auto c : cells_) n += c;
    return n;
  }
  [[nodiscard]] const std::vector<std::uint64_t>& cells() const noexcept { return cells_; }
  // Precondition: cells.size() == (bins_x + 2) (bins_y + 2).
  void set_raw(std::vector<std::uint64_t> cells) {
    assert(cells.size() == cells_.size());
    cells_ = std::move(cells);
  }
  friend bool operator==(const histogram2d&, const histogram2d&) = default;

 private:
  histogram x_, y_;
  std::vector<std::uint64_t> cells_;
};

}  // namespace stickslip
