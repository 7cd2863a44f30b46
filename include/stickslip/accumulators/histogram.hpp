// Fixed-bin histogram on [lo, hi] (the last bin is closed on the right, so
// R = 1 and D = d_max land inside). Out-of-range samples are counted apart.
// density(i) = count_i / (total * width): the area equals the fraction of all
// samples that fell inside [lo, hi].
#pragma once
#include <cassert>
#include <cmath>
#include <cstdint>
#include <vector>

namespace stickslip {

class histogram {
 public:
  histogram() = default;
  // Preconditions (checked at the edge): lo < hi, finite, bins >= 1.
  histogram(double lo, double hi, std::size_t bins)
      : lo_(lo), hi_(hi), scale_(static_cast<double>(bins) / (hi - lo)), counts_(bins, 0) {}

  void add(double x) noexcept {
    if (!(x >= lo_)) {  // also catches NaN
      ++underflow_;
      return;
    }
    if (x > hi_) {
      ++overflow_;
      return;
    }
    // One multiplication (bins / (hi - lo) is fixed): this runs once per
    // episode of every realization.
    const double f = (x - lo_) * scale_;  // >= 0; inf if hi - lo underflows
    const auto n = counts_.size();
    ++counts_[f < static_cast<double>(n) ? static_cast<std::size_t>(f) : n - 1];
  }
  // add(x) for every x of [first, last), in one loop: the bounds, the scale
  // and the counts' storage in registers (add(x) in a loop reloaded them
  // after every count: a store to a count may alias the out-of-range
  // counters). The same counts as add(x) one at a time.
  void add_all(const double* first, const double* last) noexcept {
    const double lo = lo_, hi = hi_, scale = scale_;
    const auto n = counts_.size();
    const double bins = static_cast<double>(n);
    std::uint64_t* const counts = counts_.data();
    std::uint64_t under = 0, over = 0;
    for (; first != last; ++first) {
      const double x = *first;
      if (!(x >= lo)) {
        ++under;
        continue;
      }
      if (x > hi) {
        ++over;
        continue;
      }
      const double f = (x - lo) * scale;
      ++counts[f < bins ? static_cast<std::size_t>(f) : n - 1];
    }
    underflow_ += under;
    overflow_ += over;
  }
  // Where add(x) counts x: 0 below lo (or NaN), 1 + i for bin i, bins() + 1
  // above hi. The same arithmetic as add (histogram2d bins with it, so its
  // marginals equal the 1-D counts exactly).
  [[nodiscard]] std::size_t slot(double x) const noexcept {
    if (!(x >= lo_)) return 0;
    const auto n = counts_.size();
    if (x > hi_) return n + 1;
    const double f = (x - lo_) * scale_;
    return 1 + (f < static_cast<double>(n) ? static_cast<std::size_t>(f) : n - 1);
  }
  // Precondition: same binning.
  histogram& operator+=(const histogram& o) noexcept {
    for (std::size_t i = 0; i < counts_.size(); ++i) counts_[i] += o.counts_[i];
    underflow_ += o.underflow_;
    overflow_ += o.overflow_;
    return *this;
  }
  [[nodiscard]] bool same_binning(const histogram& o) const noexcept {
    return lo_ == o.lo_ && hi_ == o.hi_ && counts_.size() == o.counts_.size();
  }
  [[nodiscard]] std::size_t bins() const noexcept { return counts_.size(); }
  [[nodiscard]] double lo() const noexcept { return lo_; }
  [[nodiscard]] double hi() const noexcept { return hi_; }
  [[nodiscard]] double width() const noexcept { return (hi_ - lo_) / static_cast<double>(bins()); }
  [[nodiscard]] double center(std::size_t i) const noexcept { return lo_ + (static_cast<double>(i) + 0.5) * width(); }
  [[nodiscard]] std::uint64_t count(std::size_t i) const noexcept { return counts_[i]; }
  [[nodiscard]] const std::vector<std::uint64_t>& counts() const noexcept { return counts_; }
  [[nodiscard]] std::uint64_t underflow() const noexcept { return underflow_; }
  [[nodiscard]] std::uint64_t overflow() const noexcept { return overflow_; }
  [[nodiscard]] std::uint64_t total() const noexcept {
    std::uint64_t t = underflow_ + overflow_;
    for (auto c : counts_) t += c;
    return t;
  }
  [[nodiscard]] double density(std::size_t i) const noexcept {
    const auto n = total();
    return n ? static_cast<double>(counts_[i]) / (static_cast<double>(n) * width()) : 0.0;
  }
  // Precondition: counts.size() == bins() (the binning is the constructor's).
  void set_raw(std::vector<std::uint64_t> counts, std::uint64_t under, std::uint64_t over) {
    assert(counts.size() == counts_.size());
    counts_ = std::move(counts);
    underflow_ = under;
    overflow_ = over;
  }
  friend bool operator==(const histogram&, const histogram&) = default;

 private:
  double lo_ = 0.0, hi_ = 1.0, scale_ = 0.0;
  std::vector<std::uint64_t> counts_;
  std::uint64_t underflow_ = 0, overflow_ = 0;
};

}  // namespace stickslip
