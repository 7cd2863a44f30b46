#include "stickslip/accumulators/time_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stickslip/state_sampler.hpp"

namespace stickslip {

// ---- quantile_sketch ----

void quantile_sketch::bump(store& s, std::uint32_t k) {
  if (s.counts.empty()) {
    s.first = k;
    s.counts.assign(1, 1);
    return;
  }
  if (k < s.first) {
    s.counts.insert(s.counts.begin(), s.first - k, 0);
    s.first = k;
  } else if (k - s.first >= s.counts.size()) {
    s.counts.resize(k - s.first + 1, 0);
  }
  ++s.counts[k - s.first];
}

namespace {
void merge_store(quantile_sketch::store& a, const quantile_sketch::store& b) {
  if (b.counts.empty()) return;
  if (a.counts.empty()) {
    a = b;
    return;
  }
  const std::uint32_t first = std::min(a.first, b.first);
  const std::uint32_t end = std::max<std::uint32_t>(
      a.first + static_cast<std::uint32_t>(a.counts.size()),
      b.first + static_cast<std::uint32_t>(b.counts.size()));
  if (first < a.first) a.counts.insert(a.counts.begin(), a.first - first, 0);
  a.first = first;
  a.counts.resize(end - first, 0);
  for (std::size_t i = 0; i < b.counts.size(); ++i) a.counts[b.first - first + i] += b.counts[i];
}
std::uint64_t store_total(const quantile_sketch::store& s) noexcept {
  std::uint64_t n = 0;
  for (auto c : s.counts) n += c;
  return n;
}
}  // namespace

quantile_sketch& quantile_sketch::operator+=(const quantile_sketch& o) {
  merge_store(negative_, o.negative_);
  merge_store(positive_, o.positive_);
  zero_ += o.zero_;
  return *this;
}

std::uint64_t quantile_sketch::count() const noexcept {
  return store_total(negative_) + zero_ + store_total(positive_);
}

double quantile_sketch::quantile(double q) const noexcept {
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
  for (std::size_t j = 0; j < at_.size(); ++j) {
    const observed_state& s = states[j];
    time_point_statistics& a = at_[j];
    a.sticking += s.sticking ? 1 : 0;
    ++level_counts_[j * levels_ + s.level];
    a.position.add(s.position);
    a.velocity.add(s.velocity);
    a.relative_velocity.add(s.velocity - s.belt_velocity);
    a.energy.add(s.energy);
    a.position_quantiles.add(s.position);
    a.velocity_quantiles.add(s.velocity);
  }
}

time_statistics& time_statistics::operator+=(const time_statistics& o) {
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
  at_ = std::move(at);
  level_counts_ = std::move(level_counts);
}

// ---- state_sampler ----

double state_sampler::next_time() const noexcept {
  return next_ < states_.size() ? (*times_)[next_] : std::numeric_limits<double>::infinity();
}

void state_sampler::sample(const segment& s) {
  const auto level = static_cast<std::uint32_t>(
      std::find(levels_.begin(), levels_.end(), s.belt_velocity) - levels_.begin());
  do {
    const phase_point p = evaluate(s, (*times_)[next_]);
    states_[next_] = observed_state{
        p.position, p.velocity, s.belt_velocity,
        0.5 * mass_ * p.velocity * p.velocity + 0.5 * stiffness_ * p.position * p.position, level,
        s.kind == mode::stick};
    ++next_;
  } while (holds_next(s));
}

}  // namespace stickslip
