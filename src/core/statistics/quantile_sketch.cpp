#include "stickslip/accumulators/quantile_sketch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace stickslip {

namespace {
// The indices [lo, hi) of a store's counts from its first to its last
// non-zero count (lo == hi: none).
std::pair<std::size_t, std::size_t> nonzero_range(const quantile_sketch::store& s) noexcept {
  std::size_t lo = 0, hi = s.counts.size();
  while (lo < hi && s.counts[lo] == 0) ++lo;
  while (hi > lo && s.counts[hi - 1] == 0) --hi;
  return {lo, hi};
}
std::uint64_t store_total(const quantile_sketch::store& s) noexcept {
  std::uint64_t n = 0;
  for (auto c : s.counts) n += c;
  return n;
}
}  // namespace

quantile_sketch::store quantile_sketch::trimmed(const store& s) {
  const auto [lo, hi] = nonzero_range(s);
  if (lo == hi) return {};
  return {s.first + static_cast<std::uint32_t>(lo),
          std::vector<std::uint32_t>(s.counts.begin() + static_cast<std::ptrdiff_t>(lo),
                                     s.counts.begin() + static_cast<std::ptrdiff_t>(hi))};
}

// Grows with room for the size held (at least 32 bins, 2 octaves) beyond
// the key asked for, so that a stream of adds moves the counts a number of
// times logarithmic in the range (doubling: a quarter moved a point's stores
// about 12 times each). The room is freed when the sketch takes no more
// samples (shrink_to_fit at a point's finish), so only the sketches of
// points in progress hold it; a store starts small (32 bins), since a work
// unit of 64 realizations or more fills sketches of its own.
void quantile_sketch::cover(store& s, std::uint32_t lo, std::uint32_t hi) {
  constexpr std::uint32_t initial = 32;
  if (s.counts.empty()) {
    s.first = lo >= min_key() + initial / 2 ? lo - initial / 2 : min_key();
    s.counts.assign(std::max<std::uint32_t>(initial, hi - s.first + 1), 0);
    return;
  }
  const auto size = static_cast<std::uint32_t>(s.counts.size());
  std::uint32_t first = s.first, end = s.first + size;  // [first, end)
  const std::uint32_t room = std::max<std::uint32_t>(initial, size);
  if (lo < first)
    first = static_cast<std::uint32_t>(std::max<std::int64_t>(
        std::int64_t{min_key()}, std::int64_t{lo} - room));
  if (hi >= end) end = hi + 1 + room;
  if (first == s.first && end == s.first + size) return;
  std::vector<std::uint32_t> grown(end - first, 0);
  std::copy(s.counts.begin(), s.counts.end(), grown.begin() + (s.first - first));
  s.first = first;
  s.counts = std::move(grown);
}

void quantile_sketch::merge(store& a, const store& b) {
  const auto [lo, hi] = nonzero_range(b);
  if (lo == hi) return;
  const auto k_lo = b.first + static_cast<std::uint32_t>(lo);
  const auto k_hi = b.first + static_cast<std::uint32_t>(hi - 1);
  reserve(a, k_lo, k_hi);
  for (std::size_t i = lo; i < hi; ++i) a.counts[b.first + i - a.first] += b.counts[i];
}

quantile_sketch& quantile_sketch::operator+=(const quantile_sketch& o) {
  merge(negative_, o.negative_);
  merge(positive_, o.positive_);
  zero_ += o.zero_;
  total_ += o.total_;
  return *this;
}

void quantile_sketch::set_raw(store negative, std::uint64_t zero, store positive) {
  negative_ = std::move(negative);
  zero_ = zero;
  positive_ = std::move(positive);
  total_ = store_total(negative_) + zero_ + store_total(positive_);
}

double quantile_sketch::quantile(double q) const {
  double out;
  quantiles(&q, 1, &out);
  return out;
}

void quantile_sketch::quantiles(const double* q, std::size_t n, double* out) const {
  const std::uint64_t total = count();
  if (total == 0) {
    std::fill(out, out + n, std::numeric_limits<double>::quiet_NaN());
    return;
  }
  // k = max(1, ceil(q n)): the k-th smallest sample, computed once per level
  auto rank_of = [&](std::size_t m) {
    return std::clamp<std::uint64_t>(
        static_cast<std::uint64_t>(std::ceil(q[m] * static_cast<double>(total))), 1, total);
  };
  constexpr std::size_t few = 16;
  std::uint64_t fixed[few];
  std::vector<std::uint64_t> many(n > few ? n : 0);
  std::uint64_t* const rank = n > few ? many.data() : fixed;
  for (std::size_t i = 0; i < n; ++i) rank[i] = rank_of(i);
  bool ascending = true;
  for (std::size_t i = 1; i < n; ++i) ascending = ascending && rank[i] >= rank[i - 1];
  if (!ascending) {
    for (std::size_t i = 0; i < n; ++i) out[i] = ranked(rank[i]);
    return;
  }
  // Ascending ranks (the usual levels 5 .. 95 %) in one walk over the bins:
  // each bin answers every rank it holds, below < k <= below + count.
  auto middle = [](std::uint32_t key) { return 0.5 * (lower(key) + upper(key)); };
  std::size_t i = 0;
  std::uint64_t below = 0;  // samples in the bins walked so far
  // (A bin without samples answers no rank: every rank <= below was
  // answered by an earlier bin, so the walk needs no test of the count.)
  auto bin = [&](std::uint64_t c, auto value) {
    below += c;
    while (i < n && rank[i] <= below) out[i++] = value();
  };
  const std::uint32_t* neg = negative_.counts.data();
  for (std::size_t b = negative_.counts.size(); b-- > 0 && i < n;)
    bin(neg[b], [&] { return -middle(negative_.first + static_cast<std::uint32_t>(b)); });
  if (i < n) bin(zero_, [] { return 0.0; });
  const std::uint32_t* pos = positive_.counts.data();
  for (std::size_t b = 0; b < positive_.counts.size() && i < n; ++b)
    bin(pos[b], [&] { return middle(positive_.first + static_cast<std::uint32_t>(b)); });
  for (; i < n; ++i) out[i] = ranked(rank[i]);  // not reached: the bins hold every rank
}

// Counted from the most negative (the negative store from its largest |x|
// down), then the zero bin, then the positive store.
double quantile_sketch::ranked(std::uint64_t k) const noexcept {
  auto middle = [](std::uint32_t key) { return 0.5 * (lower(key) + upper(key)); };
  for (std::size_t i = negative_.counts.size(); i-- > 0;) {
    if (k <= negative_.counts[i]) return -middle(negative_.first + static_cast<std::uint32_t>(i));
    k -= negative_.counts[i];
  }
  if (k <= zero_) return 0.0;
  k -= zero_;
  for (std::size_t i = 0; i < positive_.counts.size(); ++i) {
    if (k <= positive_.counts[i]) return middle(positive_.first + static_cast<std::uint32_t>(i));
    k -= positive_.counts[i];
  }
  return middle(positive_.first + static_cast<std::uint32_t>(positive_.counts.size()) - 1);
}

}  // namespace stickslip
