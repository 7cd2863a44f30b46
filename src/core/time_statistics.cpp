#include "stickslip/accumulators/time_statistics.hpp"

#include <cmath>
#include <limits>

namespace stickslip {

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

}  // namespace stickslip
