#include "stickslip/accumulators/time_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stickslip/state_sampler.hpp"

namespace stickslip {

// ---- quantile_sketch ----

quantile_sketch::store quantile_sketch::trimmed(const store& s) {
  std::size_t lo = 0, hi = s.counts.size();
  while (lo < hi && s.counts[lo] == 0) ++lo;
  while (hi > lo && s.counts[hi - 1] == 0) --hi;
  if (lo == hi) return {};
  return {s.first + static_cast<std::uint32_t>(lo),
          std::vector<std::uint32_t>(s.counts.begin() + static_cast<std::ptrdiff_t>(lo),
                                     s.counts.begin() + static_cast<std::ptrdiff_t>(hi))};
}

// Grows with room for a quarter of the size held (at least 32 bins) beyond
// the key asked for, so that a stream of adds moves the counts a number of
// times logarithmic in the range, and the room stays small.
void quantile_sketch::cover(store& s, std::uint32_t lo, std::uint32_t hi) {
  constexpr std::uint32_t initial = 32;
  if (s.counts.empty()) {
    s.first = lo >= min_key() + initial / 2 ? lo - initial / 2 : min_key();
    s.counts.assign(std::max<std::uint32_t>(initial, hi - s.first + 1), 0);
    return;
  }
  const auto size = static_cast<std::uint32_t>(s.counts.size());
  std::uint32_t first = s.first, end = s.first + size;  // [first, end)
  const std::uint32_t room = std::max<std::uint32_t>(initial, size / 4);
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

namespace {
void merge_store(quantile_sketch::store& a, const quantile_sketch::store& b,
                 void (*cover)(quantile_sketch::store&, std::uint32_t, std::uint32_t)) {
  std::size_t lo = 0, hi = b.counts.size();
  while (lo < hi && b.counts[lo] == 0) ++lo;
  while (hi > lo && b.counts[hi - 1] == 0) --hi;
  if (lo == hi) return;
  const auto k_lo = b.first + static_cast<std::uint32_t>(lo);
  const auto k_hi = b.first + static_cast<std::uint32_t>(hi - 1);
  if (a.counts.empty() || k_lo < a.first || k_hi - a.first >= a.counts.size()) cover(a, k_lo, k_hi);
  for (std::size_t i = lo; i < hi; ++i) a.counts[b.first + i - a.first] += b.counts[i];
}
std::uint64_t store_total(const quantile_sketch::store& s) noexcept {
  std::uint64_t n = 0;
  for (auto c : s.counts) n += c;
  return n;
}
}  // namespace

quantile_sketch& quantile_sketch::operator+=(const quantile_sketch& o) {
  merge_store(negative_, o.negative_, &cover);
  merge_store(positive_, o.positive_, &cover);
  zero_ += o.zero_;
  return *this;
}

std::uint64_t quantile_sketch::count() const noexcept {
  return store_total(negative_) + zero_ + store_total(positive_);
}

double quantile_sketch::quantile(double q) const {
  const std::uint64_t n = count();
  if (n == 0) return std::numeric_limits<double>::quiet_NaN();
  // k = max(1, ceil(q n)): the k-th smallest sample, counted from the most
  // negative (the negative store from its largest |x| down).
  auto k = static_cast<std::uint64_t>(std::ceil(q * static_cast<double>(n)));
  k = std::clamp<std::uint64_t>(k, 1, n);
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

// ---- time_statistics ----

void time_statistics::add(std::span<const observed_state> states) {
  ++realizations_;
  // Every moment counts every realization (count() + 1 = realizations_ for
  // each): one division for all (mean_variance::add with the reciprocal).
  const double inverse = 1.0 / static_cast<double>(realizations_);
  if (codes_.empty()) codes_.reserve(2 * at_.size() * buffered_realizations);
  for (std::size_t j = 0; j < at_.size(); ++j) {
    const observed_state& s = states[j];
    time_point_statistics& a = at_[j];
    a.sticking += s.sticking ? 1 : 0;
    ++level_counts_[j * levels_ + s.level];
    a.position.add(s.position, inverse);
    a.velocity.add(s.velocity, inverse);
    a.relative_velocity.add(s.velocity - s.belt_velocity, inverse);
    a.energy.add(s.energy, inverse);
    codes_.push_back(quantile_sketch::code(s.position));
    codes_.push_back(quantile_sketch::code(s.velocity));
  }
  if (codes_.size() >= 2 * at_.size() * buffered_realizations) settle();
}

// The buffered codes, realization by realization (each time's x then x'),
// into the sketches: the same counts as adding each sample at once.
void time_statistics::add_codes(const std::vector<std::uint32_t>& codes) const {
  const std::size_t n = at_.size();
  for (std::size_t i = 0; i < codes.size(); i += 2 * n)
    for (std::size_t j = 0; j < n; ++j) {
      at_[j].position_quantiles.add_code(codes[i + 2 * j]);
      at_[j].velocity_quantiles.add_code(codes[i + 2 * j + 1]);
    }
}

void time_statistics::settle() const {
  if (codes_.empty()) return;
  add_codes(codes_);
  codes_ = {};
}

time_statistics& time_statistics::operator+=(const time_statistics& o) {
  settle();
  add_codes(o.codes_);
  realizations_ += o.realizations_;
  for (std::size_t j = 0; j < at_.size(); ++j) {
    time_point_statistics& a = at_[j];
    const time_point_statistics& b = o.at_[j];
    a.sticking += b.sticking;
    a.position += b.position;
    a.velocity += b.velocity;
    a.relative_velocity += b.relative_velocity;
    a.energy += b.energy;
    a.position_quantiles += b.position_quantiles;
    a.velocity_quantiles += b.velocity_quantiles;
  }
  for (std::size_t i = 0; i < level_counts_.size(); ++i) level_counts_[i] += o.level_counts_[i];
  return *this;
}

double time_statistics::stick_probability(std::size_t j) const noexcept {
  if (realizations_ == 0) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(at_[j].sticking) / static_cast<double>(realizations_);
}

double time_statistics::stick_probability_std_error(std::size_t j) const noexcept {
  const double p = stick_probability(j);
  return std::sqrt(p * (1.0 - p) / static_cast<double>(realizations_));
}

double time_statistics::level_occupancy(std::size_t j, std::size_t level) const noexcept {
  if (realizations_ == 0) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(level_count(j, level)) / static_cast<double>(realizations_);
}

void time_statistics::set_raw(std::uint64_t realizations, std::vector<time_point_statistics> at,
                              std::vector<std::uint64_t> level_counts) {
  realizations_ = realizations;
  codes_.clear();
  at_ = std::move(at);
  level_counts_ = std::move(level_counts);
}

// ---- state_sampler ----

double state_sampler::next_time() const noexcept {
  return next_ < states_.size() ? (*times_)[next_] : std::numeric_limits<double>::infinity();
}

// No SLP vectorization here: GCC paired the two halves of the energy and
// the returned (x, x') through two 8-byte spills read back as one 16-byte
// load, a failed store forward (the paper grid with 101 observe times:
// 9.42 -> 9.19 s CPU, 3 runs each).
#if defined(__GNUC__) && !defined(__clang__)
[[gnu::optimize("no-tree-slp-vectorize")]]
#endif
void state_sampler::sample(const segment& s) {
  const auto level = static_cast<std::uint32_t>(
      std::find(levels_.begin(), levels_.end(), s.belt_velocity) - levels_.begin());
  const bool sticking = s.kind == mode::stick;
  do {
    const phase_point p = evaluate(s, (*times_)[next_]);
    const double x = p.position, xd = p.velocity;
    observed_state& o = states_[next_];
    o.position = x;
    o.velocity = xd;
    o.belt_velocity = s.belt_velocity;
    o.energy = 0.5 * mass_ * xd * xd + 0.5 * stiffness_ * x * x;
    o.level = level;
    o.sticking = sticking;
    ++next_;
  } while (holds_next(s));
}

}  // namespace stickslip
