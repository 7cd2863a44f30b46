// The ensemble at observe times (sweep --observe-times): for each time t_j,
// over the realizations of a grid point, the state each one is in at t_j,
// evaluated from the closed-form segment that holds t_j (observed_state,
// state_sampler.hpp):
//   the number sticking (stick probability), the number at each belt level,
//   mean and variance of x, x', the relative velocity x' - v and the
//   mechanical energy m x'^2/2 + k x^2/2, and quantile sketches of x and x'.
// Every realization adds one state per time, so memory is O(times) per point,
// never per realization; counts and sketches merge exactly, the moments by
// mean_variance's merge (in block order, as every accumulator).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "stickslip/accumulators/mean_variance.hpp"
#include "stickslip/accumulators/quantile_sketch.hpp"

namespace stickslip {

// One realization's state at one observe time.
struct observed_state {
  double position = 0.0;       // x [m]
  double velocity = 0.0;       // x' [m/s]
  double belt_velocity = 0.0;  // v [m/s]
  double energy = 0.0;         // m x'^2 / 2 + k x^2 / 2 [J]
  std::uint32_t level = 0;     // index of the belt level (paper: 0 = +V, 1 = -V)
  bool sticking = false;       // in a stick at t (x' = v held by friction)
  friend bool operator==(const observed_state&, const observed_state&) = default;
};

// The accumulators at one observe time.
struct time_point_statistics {
  std::uint64_t sticking = 0;
  mean_variance position, velocity, relative_velocity, energy;
  quantile_sketch position_quantiles, velocity_quantiles;
  friend bool operator==(const time_point_statistics&, const time_point_statistics&) = default;
};

class time_statistics {
 public:
  time_statistics() = default;  // not selected: no times
  // Preconditions (sweep validate()): times ascending, finite, >= 0; levels >= 1.
  time_statistics(std::vector<double> times, std::size_t levels)
      : times_(std::move(times)), levels_(levels), at_(times_.size()),
        level_counts_(times_.size() * levels, 0) {}

  [[nodiscard]] bool selected() const noexcept { return !times_.empty(); }
  // One realization: states[j] at times()[j]. Precondition: one per time,
  // level < levels().
  void add(std::span<const observed_state> states);
  // Precondition: the same times and levels.
  time_statistics& operator+=(const time_statistics& o);

  [[nodiscard]] const std::vector<double>& times() const noexcept { return times_; }
  [[nodiscard]] std::size_t levels() const noexcept { return levels_; }
  [[nodiscard]] std::uint64_t realizations() const noexcept { return realizations_; }
  // (Settles the buffered codes of the sketches first: const, but not to be
  // called on one object from two threads at once.)
  [[nodiscard]] const time_point_statistics& at(std::size_t j) const {
    settle();
    return at_[j];
  }
  [[nodiscard]] std::uint64_t level_count(std::size_t j, std::size_t level) const noexcept {
    return level_counts_[j * levels_ + level];
  }
  // The fraction sticking at t_j and its standard error sqrt(p (1 - p) / n)
  // (NaN without realizations).
  [[nodiscard]] double stick_probability(std::size_t j) const noexcept;
  [[nodiscard]] double stick_probability_std_error(std::size_t j) const noexcept;
  // The fraction at belt level `level` at t_j.
  [[nodiscard]] double level_occupancy(std::size_t j, std::size_t level) const noexcept;

  // The raw state (serialization).
  [[nodiscard]] const std::vector<std::uint64_t>& level_counts() const noexcept {
    return level_counts_;
  }
  // Precondition: sizes as the constructor makes them.
  void set_raw(std::uint64_t realizations, std::vector<time_point_statistics> at,
               std::vector<std::uint64_t> level_counts);
  friend bool operator==(const time_statistics& a, const time_statistics& b) {
    a.settle();
    b.settle();
    return a.times_ == b.times_ && a.levels_ == b.levels_ && a.realizations_ == b.realizations_ &&
           a.at_ == b.at_ && a.level_counts_ == b.level_counts_;
  }

 private:
  // A block's quantile samples are kept as sketch codes (quantile_sketch::
  // code) in one array, two per time per realization, and go into the
  // sketches every buffered_realizations realizations, at a merge, or when
  // read: one store per sample instead of a growing list per sketch.
  static constexpr std::size_t buffered_realizations = 64;
  void settle() const;
  void add_codes(const std::vector<std::uint32_t>& codes) const;
  std::vector<double> times_;
  std::size_t levels_ = 0;
  std::uint64_t realizations_ = 0;
  mutable std::vector<time_point_statistics> at_;
  std::vector<std::uint64_t> level_counts_;  // times x levels, row-major
  mutable std::vector<std::uint32_t> codes_;
};

// The quantile levels written for x and x' (5, 25, 50, 75, 95 %).
inline constexpr double observed_quantile_levels[] = {0.05, 0.25, 0.5, 0.75, 0.95};

}  // namespace stickslip
