// Mean and variance accumulator (Welford 1962) with an exact merge
// (Chan, Golub, LeVeque 1979): for parts A and B with n = nA + nB,
//   delta = mean_B - mean_A
//   mean  = mean_A + delta nB / n
//   M2    = M2_A + M2_B + delta^2 nA nB / n
// Merging two halves equals filling everything at once up to rounding;
// merging in a fixed order makes the result bit-reproducible.
#pragma once
#include <cmath>
#include <cstdint>

namespace stickslip {

// Two-sided 95 % normal quantile, Phi^-1(0.975).
inline constexpr double z95 = 1.959963984540054;

class mean_variance {
 public:
  void add(double x) noexcept {
    ++n_;
    const double d = x - mean_;
    mean_ += d / static_cast<double>(n_);
    m2_ += d * (x - mean_);
  }
  // add(x) with the reciprocal 1 / (count() + 1) given: mean += d r instead
  // of d / n (other last bits than add(x)), for accumulators that count
  // together and share one division (time_statistics). Precondition:
  // inverse_next_count == 1.0 / (count() + 1).
  void add(double x, double inverse_next_count) noexcept {
    ++n_;
    const double d = x - mean_;
    mean_ += d * inverse_next_count;
    m2_ += d * (x - mean_);
  }
  // Adds the samples [first, last) as one batch: their mean and sum of
  // squared deviations by two passes, then the exact merge below. One
  // division per batch instead of one per sample (point_statistics adds the
  // D_i and H_i of a realization this way). Each pass keeps four partial
  // sums in a fixed order: four independent dependency chains (and SIMD
  // adds), the same bits on every machine.
  void add_batch(const double* first, const double* last) noexcept {
    if (first == last) return;
    const auto n = static_cast<std::uint64_t>(last - first);
    const double m = sum4(first, last, [](double x) { return x; }) / static_cast<double>(n);
    const double m2 = sum4(first, last, [m](double x) { return (x - m) * (x - m); });
    *this += from_raw(n, m, m2);
  }
  mean_variance& operator+=(const mean_variance& o) noexcept {
    if (o.n_ == 0) return *this;
    if (n_ == 0) return *this = o;
    const double na = static_cast<double>(n_), nb = static_cast<double>(o.n_);
    const double n = na + nb, d = o.mean_ - mean_;
    mean_ += d * nb / n;
    m2_ += o.m2_ + d * d * na * nb / n;
    n_ += o.n_;
    return *this;
  }
  [[nodiscard]] std::uint64_t count() const noexcept { return n_; }
  [[nodiscard]] double mean() const noexcept { return n_ ? mean_ : NAN; }
  // Sample variance (n - 1 in the denominator); NaN below two samples.
  [[nodiscard]] double variance() const noexcept {
    return n_ > 1 ? m2_ / static_cast<double>(n_ - 1) : NAN;
  }
  [[nodiscard]] double std_dev() const noexcept { return std::sqrt(variance()); }
  [[nodiscard]] double std_error() const noexcept {
    return std_dev() / std::sqrt(static_cast<double>(n_));
  }
  // Half-width of the normal-approximation 95 % confidence interval of the mean.
  [[nodiscard]] double ci95_half_width() const noexcept { return z95 * std_error(); }
  [[nodiscard]] double sum_sq_dev() const noexcept { return m2_; }
  static mean_variance from_raw(std::uint64_t n, double mean, double m2) noexcept {
    mean_variance r;
    r.n_ = n;
    r.mean_ = mean;
    r.m2_ = m2;
    return r;
  }
  friend bool operator==(const mean_variance&, const mean_variance&) = default;

 private:
  template <class F>
  static double sum4(const double* p, const double* last, F f) noexcept {
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
    for (; last - p >= 4; p += 4) {
      s0 += f(p[0]);
      s1 += f(p[1]);
      s2 += f(p[2]);
      s3 += f(p[3]);
    }
    for (; p != last; ++p) s0 += f(*p);
    return (s0 + s1) + (s2 + s3);
  }
  std::uint64_t n_ = 0;
  double mean_ = 0.0, m2_ = 0.0;
};

}  // namespace stickslip
