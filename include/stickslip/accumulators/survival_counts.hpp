// Binned episode durations with right censoring: the sufficient statistics
// of a grouped Kaplan-Meier estimate (survival_estimate.hpp). On the fixed
// grid [0, upper] in `bins` equal bins (histogram's binning: bin j holds
// [e_j, e_j+1), the last bin also upper; durations above upper are counted
// apart), two counts per bin: episodes that ended (an event) and episodes
// cut by the end of the window (censored at the duration they had reached).
// Integer counts, so the merge is exact and the result does not depend on
// how realizations are split over threads, ranks, shards or resumes.
#pragma once
#include <cstdint>

#include "stickslip/accumulators/histogram.hpp"

namespace stickslip {

class survival_counts {
 public:
  survival_counts() = default;  // not selected: no bins
  // Preconditions (checked at the edge): upper > 0 and finite, bins >= 1.
  survival_counts(double upper, std::size_t bins)
      : ended_(0.0, upper, bins), censored_(0.0, upper, bins) {}

  void add(double duration, bool cut) noexcept { (cut ? censored_ : ended_).add(duration); }
  // Precondition: same binning.
  survival_counts& operator+=(const survival_counts& o) noexcept {
    ended_ += o.ended_;
    censored_ += o.censored_;
    return *this;
  }
  [[nodiscard]] bool selected() const noexcept { return ended_.bins() > 0; }
  [[nodiscard]] bool same_binning(const survival_counts& o) const noexcept {
    return ended_.same_binning(o.ended_);
  }
  [[nodiscard]] std::size_t bins() const noexcept { return ended_.bins(); }
  [[nodiscard]] double upper() const noexcept { return ended_.hi(); }
  // Durations in [0, upper] by bin; underflow: none (durations are >= 0),
  // overflow: durations above upper.
  [[nodiscard]] const histogram& ended() const noexcept { return ended_; }
  [[nodiscard]] const histogram& censored() const noexcept { return censored_; }
  // Precondition: both have this binning.
  void set_raw(histogram ended, histogram censored) {
    ended_ = std::move(ended);
    censored_ = std::move(censored);
  }
  friend bool operator==(const survival_counts&, const survival_counts&) = default;

 private:
  histogram ended_, censored_;
};

}  // namespace stickslip
