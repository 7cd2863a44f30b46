// Quantiles of a stream with bounded memory and an exact merge: counts over
// log-linear bins of |x| (an HDR-histogram binning), one store of bins per
// sign. The bin of x != 0 is the top bits of |x|'s binary form: its exponent
// and the first `mantissa_bits` bits of its mantissa, so every bin is an
// interval [L, U) with U - L <= L 2^-mantissa_bits, and binning costs a shift
// (no logarithm). |x| < zero_threshold falls in the zero bin.
// Counts are integers, so a merge gives the same bits in any order, and the
// result does not depend on how realizations are split over threads, ranks,
// shards or resumes. Memory: the bins between the smallest and largest |x|
// seen, 2^mantissa_bits per octave (about 32 per octave, a few hundred per
// sign for values that span 10 decades), never per sample.
#pragma once
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

namespace stickslip {

class quantile_sketch {
 public:
  static constexpr int mantissa_bits = 5;
  // The largest relative error of a reported quantile against the exact
  // sample quantile (quantile()): half a bin, 2^-(mantissa_bits + 1).
  static constexpr double relative_accuracy = 1.0 / (2 << mantissa_bits);
  // |x| below this is counted as 0 (2^-40, about 9.1e-13): the absolute
  // accuracy near 0.
  static constexpr double zero_threshold = 0x1p-40;

  // One store of bins: counts[i] of bin key first + i, trimmed so that the
  // first and last counts are > 0 (empty: no counts). The canonical form the
  // serializer writes and checks.
  struct store {
    std::uint32_t first = 0;
    std::vector<std::uint32_t> counts;
    friend bool operator==(const store&, const store&) = default;
  };

  void add(double x) {
    if (!(std::abs(x) >= zero_threshold)) {  // also NaN, which the engines never give
      ++zero_;
      return;
    }
    bump(x > 0.0 ? positive_ : negative_, key(x));
  }
  quantile_sketch& operator+=(const quantile_sketch& o);

  [[nodiscard]] std::uint64_t count() const noexcept;
  // The sample quantile x_(k), k = max(1, ceil(q n)) (the lower one of the
  // sorted samples), to within relative_accuracy |x_(k)| (zero_threshold near
  // 0): the middle of its bin. NaN without samples. Precondition: 0 <= q <= 1.
  [[nodiscard]] double quantile(double q) const noexcept;

  // The bin of x != 0 (|x| >= zero_threshold) and its ends [L, U).
  [[nodiscard]] static std::uint32_t key(double x) noexcept {
    return static_cast<std::uint32_t>(std::bit_cast<std::uint64_t>(std::abs(x)) >>
                                      (52 - mantissa_bits));
  }
  [[nodiscard]] static double lower(std::uint32_t k) noexcept {
    return std::bit_cast<double>(static_cast<std::uint64_t>(k) << (52 - mantissa_bits));
  }
  [[nodiscard]] static double upper(std::uint32_t k) noexcept { return lower(k + 1); }
  // The smallest and largest keys a store may hold (|x| >= zero_threshold,
  // finite).
  [[nodiscard]] static std::uint32_t min_key() noexcept { return key(zero_threshold); }
  [[nodiscard]] static std::uint32_t max_key() noexcept { return key(1.7976931348623157e308); }

  // The raw state (serialization): negative values by |x|, the zero bin,
  // positive values. Precondition of set_raw: canonical stores with keys in
  // [min_key, max_key] (the deserializer checks).
  [[nodiscard]] const store& negative() const noexcept { return negative_; }
  [[nodiscard]] const store& positive() const noexcept { return positive_; }
  [[nodiscard]] std::uint64_t zero() const noexcept { return zero_; }
  void set_raw(store negative, std::uint64_t zero, store positive) {
    negative_ = std::move(negative);
    zero_ = zero;
    positive_ = std::move(positive);
  }
  friend bool operator==(const quantile_sketch&, const quantile_sketch&) = default;

 private:
  static void bump(store& s, std::uint32_t k);
  store negative_, positive_;
  std::uint64_t zero_ = 0;
};

}  // namespace stickslip
