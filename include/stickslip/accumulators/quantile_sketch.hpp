// Quantiles of a stream with bounded memory and an exact merge: counts over
// log-linear bins of |x| (an HDR-histogram binning), one store of bins per
// sign. The bin of x != 0 is the top bits of |x|'s binary form: its exponent
// and the first `mantissa_bits` bits of its mantissa, so every bin is an
// interval [L, U) with U - L <= L 2^-mantissa_bits, and binning costs a shift
// (no logarithm). |x| < zero_threshold falls in the zero bin.
// Counts are integers, so a merge gives the same bits in any order, and the
// result does not depend on how realizations are split over threads, ranks,
// shards or resumes. Memory: the bins between the smallest and largest |x|
// seen, 2^mantissa_bits = 16 per octave (a few hundred per
// sign for values that span 10 decades), never per sample.
#pragma once
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace stickslip {

class quantile_sketch {
 public:
  static constexpr int mantissa_bits = 4;
  // The largest relative error of a reported quantile against the exact
  // sample quantile (quantile()): half a bin, 2^-(mantissa_bits + 1).
  static constexpr double relative_accuracy = 1.0 / (2 << mantissa_bits);
  // |x| below this is counted as 0 (2^-40, about 9.1e-13): the absolute
  // accuracy near 0.
  static constexpr double zero_threshold = 0x1p-40;

  // One store of bins: counts[i] of bin key first + i. Trimmed (the first
  // and last counts > 0, or no counts) is the canonical form that
  // negative(), positive() return and the serializer writes and checks; the
  // sketch itself keeps zero bins on both sides to grow into.
  struct store {
    std::uint32_t first = 0;
    std::vector<std::uint32_t> counts;
    friend bool operator==(const store&, const store&) = default;
  };

  void add(double x) { add_code(code(x)); }
  // The bin of x as one number: 0 for the zero bin, else key(x), with
  // sign_bit set for x < 0 (keys are < 2^15). add(x) is add_code(code(x)):
  // a buffer of codes can be added later (time_statistics keeps a block's
  // codes in one array, so that its samples cost a store each).
  static constexpr std::uint32_t sign_bit = 0x80000000u;
  // Without a branch, so that loops over many samples vectorize: |x| as x's
  // bits without the sign (key(x)), the sign bit moved to sign_bit, and 0
  // unless |x| >= zero_threshold (also for NaN, which the engines never give).
  [[nodiscard]] static std::uint32_t code(double x) noexcept {
    const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
    const std::uint64_t magnitude = bits & ~(std::uint64_t{1} << 63);
    const auto k = static_cast<std::uint32_t>(magnitude >> (52 - mantissa_bits));
    const std::uint32_t sign = static_cast<std::uint32_t>(bits >> 63) << 31;
    return std::abs(x) >= zero_threshold ? (k | sign) : 0u;
  }
  void add_code(std::uint32_t c) {
    ++total_;
    if (c == 0)
      ++zero_;
    else
      bump(c & sign_bit ? negative_ : positive_, c & ~sign_bit);
  }
  quantile_sketch& operator+=(const quantile_sketch& o);
  // Frees the room the stores keep to grow into (a finished point's
  // sketches take no more samples; an add after it grows them again).
  void shrink_to_fit() {
    negative_ = trimmed(negative_);
    positive_ = trimmed(positive_);
  }

  // The samples added (kept as they are added: the outputs ask every sketch).
  [[nodiscard]] std::uint64_t count() const noexcept { return total_; }
  // The sample quantile x_(k), k = max(1, ceil(q n)) (the lower one of the
  // sorted samples), to within relative_accuracy |x_(k)| (zero_threshold near
  // 0): the middle of its bin. NaN without samples. Precondition: 0 <= q <= 1.
  [[nodiscard]] double quantile(double q) const;
  // quantile(q[i]) into out[i] for i < n, counting the samples once.
  void quantiles(const double* q, std::size_t n, double* out) const;

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

  // The raw state (serialization), trimmed: negative values by |x|, the
  // zero bin, positive values. Precondition of set_raw: trimmed stores with
  // keys in [min_key, max_key] (the deserializer checks).
  [[nodiscard]] store negative() const { return trimmed(negative_); }
  [[nodiscard]] store positive() const { return trimmed(positive_); }
  [[nodiscard]] std::uint64_t zero() const noexcept { return zero_; }
  void set_raw(store negative, std::uint64_t zero, store positive);
  // The same counts (whatever room either keeps to grow into).
  friend bool operator==(const quantile_sketch& a, const quantile_sketch& b) {
    return a.zero_ == b.zero_ && a.negative() == b.negative() && a.positive() == b.positive();
  }

 private:
  static store trimmed(const store& s);
  // The k-th smallest sample's bin middle, 1 <= k <= count().
  [[nodiscard]] double ranked(std::uint64_t k) const noexcept;
  // Makes room in s for the keys [lo, hi].
  static void cover(store& s, std::uint32_t lo, std::uint32_t hi);
  // a += b, bin by bin.
  static void merge(store& a, const store& b);
  // Makes room in s for the keys [lo, hi] unless it has it.
  static void reserve(store& s, std::uint32_t lo, std::uint32_t hi) {
    if (s.counts.empty() || lo < s.first || hi - s.first >= s.counts.size()) cover(s, lo, hi);
  }
  static void bump(store& s, std::uint32_t k) {
    reserve(s, k, k);
    ++s.counts[k - s.first];
  }
  store negative_, positive_;
  std::uint64_t zero_ = 0;
  std::uint64_t total_ = 0;  // count(): zero_ and every store's counts
};

}  // namespace stickslip
