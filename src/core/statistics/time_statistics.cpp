#include "stickslip/accumulators/time_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

namespace stickslip {

namespace {

// The row loops below are compiled for AVX-512 and AVX2 as well as the
// baseline, and the widest the CPU has runs (GCC function multiversioning):
// 8 or 4 lanes instead of SSE2's 2. Each element's operations are the same
// (+, -, x, no fused multiply-add: the core is built with -ffp-contract=off),
// so every version gives the same bits. Only where the toolchain makes such
// clones (x86-64 ELF with ifunc), and not under a sanitizer: the clones'
// resolver runs while the program is relocated, before a sanitizer's
// runtime is ready, and its instrumented code crashes there (TSan did);
// elsewhere the baseline alone.
#if defined(__SANITIZE_THREAD__) || defined(__SANITIZE_ADDRESS__)
#define STICKSLIP_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer) || __has_feature(address_sanitizer) || \
    __has_feature(memory_sanitizer)
#define STICKSLIP_SANITIZED 1
#endif
#endif
#if defined(__x86_64__) && defined(__ELF__) && defined(__has_attribute) && \
    !defined(STICKSLIP_SANITIZED)
#if __has_attribute(target_clones)
#define STICKSLIP_ROW_CLONES __attribute__((target_clones("default", "avx2", "avx512f")))
#endif
#endif
#ifndef STICKSLIP_ROW_CLONES
#define STICKSLIP_ROW_CLONES
#endif

// Welford's update (mean_variance::add(x, inverse)) of every time's moments
// by one realization's values x[j] - minus[j] (minus: nullptr for 0): one
// pass down the arrays, which the compiler vectorizes; each element's
// operations are those of mean_variance::add, so the same bits.
STICKSLIP_ROW_CLONES
void add_row(double* __restrict mean, double* __restrict m2, const double* __restrict x,
             const double* __restrict minus, std::size_t n, double inverse) noexcept {
  if (minus == nullptr) {
    for (std::size_t j = 0; j < n; ++j) {
      const double d = x[j] - mean[j];
      mean[j] += d * inverse;
      m2[j] += d * (x[j] - mean[j]);
    }
    return;
  }
  for (std::size_t j = 0; j < n; ++j) {
    const double y = x[j] - minus[j];
    const double d = y - mean[j];
    mean[j] += d * inverse;
    m2[j] += d * (y - mean[j]);
  }
}

// quantile_sketch::code of x[j] and z[j] into c[2 j], c[2 j + 1] (code has
// no branch, so the loop vectorizes).
STICKSLIP_ROW_CLONES
void add_code_row(std::uint32_t* __restrict c, const double* __restrict x,
                  const double* __restrict z, std::size_t n) noexcept {
  for (std::size_t j = 0; j < n; ++j) {
    c[2 * j] = quantile_sketch::code(x[j]);
    c[2 * j + 1] = quantile_sketch::code(z[j]);
  }
}

}  // namespace

void time_statistics::add(const observed_states& s) {
  ++realizations_;
  quantiles_.clear();
  // Every moment counts every realization (count() + 1 = realizations_ for
  // each): one division for all (mean_variance::add with the reciprocal).
  const double inverse = 1.0 / static_cast<double>(realizations_);
  const std::size_t n = times_.size();
  const double *sticking = s.sticking(), *level = s.level();
  for (std::size_t j = 0; j < n; ++j) sticking_[j] += sticking[j] != 0.0 ? 1 : 0;
  for (std::size_t j = 0; j < n; ++j)
    ++level_counts_[j * levels_ + static_cast<std::size_t>(level[j])];
  add_row(position_.mean.data(), position_.m2.data(), s.position(), nullptr, n, inverse);
  add_row(velocity_.mean.data(), velocity_.m2.data(), s.velocity(), nullptr, n, inverse);
  add_row(energy_.mean.data(), energy_.m2.data(), s.energy(), nullptr, n, inverse);
  // x' - v
  add_row(relative_velocity_.mean.data(), relative_velocity_.m2.data(), s.velocity(),
          s.belt_velocity(), n, inverse);
  at_stale_ = true;
  if (codes_.empty()) codes_.reserve(2 * n * buffered_realizations);
  const std::size_t first = codes_.size();
  codes_.resize(first + 2 * n);
  add_code_row(codes_.data() + first, s.position(), s.velocity(), n);
  if (codes_.size() >= 2 * n * buffered_realizations) settle();
}

// The buffered codes, realization by realization (each time's x then x'),
// into the sketches: the same counts as adding each sample at once.
void time_statistics::add_codes(const code_buffer& codes) const {
  const std::size_t n = times_.size();
  for (std::size_t i = 0; i < codes.size(); i += 2 * n)
    for (std::size_t j = 0; j < n; ++j) {
      at_[j].position_quantiles.add_code(codes[i + 2 * j]);
      at_[j].velocity_quantiles.add_code(codes[i + 2 * j + 1]);
    }
}

void time_statistics::refresh() const {
  if (at_.size() != times_.size()) {  // made when first read (a unit's accumulator never is)
    at_.resize(times_.size());
    at_stale_ = true;
  }
  if (at_stale_) {
    for (std::size_t j = 0; j < at_.size(); ++j) {
      time_point_statistics& a = at_[j];
      a.sticking = sticking_[j];
      a.position = position_.at(j, realizations_);
      a.velocity = velocity_.at(j, realizations_);
      a.relative_velocity = relative_velocity_.at(j, realizations_);
      a.energy = energy_.at(j, realizations_);
    }
    at_stale_ = false;
  }
}

void time_statistics::settle() const {
  refresh();
  if (codes_.empty()) return;
  add_codes(codes_);
  codes_.clear();  // its room kept: O(times), and no page faults on the next block
}

time_statistics& time_statistics::operator+=(const time_statistics& o) {
  settle();
  quantiles_.clear();
  // o is only read: its buffered codes, its rows (current even when its at_
  // is not refreshed) and its sketches
  add_codes(o.codes_);
  const std::uint64_t n = o.realizations_;
  // o's sketches, where o has them: an accumulator never read holds its
  // samples in its codes alone
  const bool o_sketches = !o.at_.empty();
  for (std::size_t j = 0; j < at_.size(); ++j) {
    time_point_statistics& a = at_[j];
    a.sticking += o.sticking_[j];
    a.position += o.position_.at(j, n);
    a.velocity += o.velocity_.at(j, n);
    a.relative_velocity += o.relative_velocity_.at(j, n);
    a.energy += o.energy_.at(j, n);
    if (o_sketches) {
      a.position_quantiles += o.at_[j].position_quantiles;
      a.velocity_quantiles += o.at_[j].velocity_quantiles;
    }
    sticking_[j] = a.sticking;
    position_.set(j, a.position);
    velocity_.set(j, a.velocity);
    relative_velocity_.set(j, a.relative_velocity);
    energy_.set(j, a.energy);
  }
  realizations_ += n;
  for (std::size_t i = 0; i < level_counts_.size(); ++i) level_counts_[i] += o.level_counts_[i];
  return *this;
}

void time_statistics::compute_quantiles() const {
  constexpr std::size_t q = std::size(observed_quantile_levels);
  settle();
  quantiles_.resize(times_.size() * 2 * q);
  for (std::size_t i = 0; i < times_.size(); ++i) {
    at_[i].position_quantiles.quantiles(observed_quantile_levels, q, &quantiles_[2 * q * i]);
    at_[i].velocity_quantiles.quantiles(observed_quantile_levels, q, &quantiles_[2 * q * i + q]);
  }
}

void time_statistics::finish() {
  if (!selected()) return;
  settle();
  code_buffer().swap(codes_);
  for (auto& a : at_) {
    a.position_quantiles.shrink_to_fit();
    a.velocity_quantiles.shrink_to_fit();
  }
  if (quantiles_.empty()) compute_quantiles();
}

void time_statistics::quantiles(std::size_t j, quantile_sketch time_point_statistics::*sketch,
                                double* out) const {
  constexpr std::size_t q = std::size(observed_quantile_levels);
  if (quantiles_.empty()) compute_quantiles();
  const std::size_t which = sketch == &time_point_statistics::position_quantiles ? 0 : 1;
  std::copy_n(&quantiles_[2 * q * j + which * q], q, out);
}

double time_statistics::stick_probability(std::size_t j) const noexcept {
  if (realizations_ == 0) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(sticking_[j]) / static_cast<double>(realizations_);
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
  quantiles_.clear();
  at_ = std::move(at);
  at_stale_ = false;
  for (std::size_t j = 0; j < at_.size(); ++j) {
    sticking_[j] = at_[j].sticking;
    position_.set(j, at_[j].position);
    velocity_.set(j, at_[j].velocity);
    relative_velocity_.set(j, at_[j].relative_velocity);
    energy_.set(j, at_[j].energy);
  }
  level_counts_ = std::move(level_counts);
}

}  // namespace stickslip
