// The ensemble at observe times (sweep --observe-times): for each time t_j,
// over the realizations of a grid point, the state each one is in at t_j,
// evaluated from the closed-form segment that holds t_j (observed_states,
// state_sampler.hpp):
//   the number sticking (stick probability), the number at each belt level,
//   mean and variance of x, x', the relative velocity x' - v and the
//   mechanical energy m x'^2/2 + k x^2/2, and quantile sketches of x and x'.
// Every realization adds one state per time, so memory is O(times) per point,
// never per realization; counts and sketches merge exactly, the moments by
// mean_variance's merge (in block order, as every accumulator).
#pragma once
#include <cstdint>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include "stickslip/accumulators/mean_variance.hpp"
#include "stickslip/accumulators/quantile_sketch.hpp"

namespace stickslip {

// One realization's states at the observe times, one array per field
// (index j: the time t_j), so that time_statistics::add runs down whole
// arrays; the six arrays share one allocation (an observer is made per
// work unit and realization slot).
class observed_states {
 public:
  observed_states() = default;
  explicit observed_states(std::size_t times) : n_(times), values_(fields * times, 0.0) {}
  [[nodiscard]] std::size_t size() const noexcept { return n_; }
  // x [m], x' [m/s], the belt velocity v [m/s], the energy m x'^2/2 + k x^2/2
  // [J], the index of the belt level (paper: 0 = +V, 1 = -V) and 1 while in
  // a stick at t_j (x' = v held by friction), else 0, as doubles.
  double* position() noexcept { return values_.data(); }
  double* velocity() noexcept { return values_.data() + n_; }
  double* belt_velocity() noexcept { return values_.data() + 2 * n_; }
  double* energy() noexcept { return values_.data() + 3 * n_; }
  double* level() noexcept { return values_.data() + 4 * n_; }
  double* sticking() noexcept { return values_.data() + 5 * n_; }
  const double* position() const noexcept { return values_.data(); }
  const double* velocity() const noexcept { return values_.data() + n_; }
  const double* belt_velocity() const noexcept { return values_.data() + 2 * n_; }
  const double* energy() const noexcept { return values_.data() + 3 * n_; }
  const double* level() const noexcept { return values_.data() + 4 * n_; }
  const double* sticking() const noexcept { return values_.data() + 5 * n_; }
  friend bool operator==(const observed_states&, const observed_states&) = default;

 private:
  static constexpr std::size_t fields = 6;
  std::size_t n_ = 0;
  std::vector<double> values_;
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
      : times_(std::move(times)), levels_(levels), sticking_(times_.size(), 0),
        position_(times_.size()), velocity_(times_.size()), relative_velocity_(times_.size()),
        energy_(times_.size()), level_counts_(times_.size() * levels, 0) {}

  [[nodiscard]] bool selected() const noexcept { return !times_.empty(); }
  // One realization: its state at each of times(). Precondition: one per
  // time, level < levels().
  void add(const observed_states& states);
  // Precondition: the same times and levels.
  time_statistics& operator+=(const time_statistics& o);

  [[nodiscard]] const std::vector<double>& times() const noexcept { return times_; }
  [[nodiscard]] std::size_t levels() const noexcept { return levels_; }
  [[nodiscard]] std::uint64_t realizations() const noexcept { return realizations_; }
  // (Refreshes the moments from the rows and settles the buffered codes of
  // the sketches first: const, but not to be called on one object from two
  // threads at once; nor is operator==. The sweep reads and serializes an
  // accumulator only under its merge's lock, the writers on one thread.)
  [[nodiscard]] const time_point_statistics& at(std::size_t j) const {
    settle();
    return at_[j];
  }
  // The quantiles at observed_quantile_levels of the sketch `sketch` (a
  // member of time_point_statistics) at t_j, into out[0 .. 5): computed for
  // every time and both sketches at the first call after a change, and kept
  // (the writers read them once each; the same caveat as at()).
  void quantiles(std::size_t j, quantile_sketch time_point_statistics::*sketch, double* out) const;
  // For an accumulator that takes no more realizations (a finished point):
  // settles the codes, frees the buffer and the sketches' room to grow
  // (most of a small store, about half or more of one that grew), and
  // computes the quantiles when the point finishes (the sweep calls it under
  // its merge's lock, while the other threads compute their units), rather
  // than all at once when the outputs are written. Changes no value; an add
  // or a merge after it still works.
  void finish();
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
  // The sticking counts and the moments are accumulated in one array per
  // quantity over the times (moment_rows: the mean and M2 of each time, all
  // counting realizations_), which add() updates a whole row at a time;
  // at_ gets them when read, and every buffered_realizations realizations
  // (settle()). A block's quantile samples are kept
  // as sketch codes (quantile_sketch::code) in one array, two per time per
  // realization, and go into the sketches every buffered_realizations
  // realizations, at a merge, or when read: one store per sample instead of
  // a growing list per sketch.
  struct moment_rows {
    std::vector<double> mean, m2;
    explicit moment_rows(std::size_t n = 0) : mean(n, 0.0), m2(n, 0.0) {}
    [[nodiscard]] mean_variance at(std::size_t j, std::uint64_t n) const {
      return mean_variance::from_raw(n, n ? mean[j] : 0.0, m2[j]);
    }
    void set(std::size_t j, const mean_variance& m) {
      mean[j] = m.count() ? m.mean() : 0.0;
      m2[j] = m.sum_sq_dev();
    }
  };
  static constexpr std::size_t buffered_realizations = 64;
  // An allocator that leaves new elements uninitialized: add() resizes the
  // buffer by a realization's codes and then writes every one of them, so
  // zero-filling them first was a memset of every sample.
  template <class T>
  struct uninitialized : std::allocator<T> {
    template <class U>
    struct rebind {
      using other = uninitialized<U>;
    };
    uninitialized() = default;
    template <class U>
    uninitialized(const uninitialized<U>&) noexcept {}  // NOLINT: allocator rebind
    template <class U>
    void construct(U* p) noexcept {
      ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... A>
    void construct(U* p, A&&... a) {
      ::new (static_cast<void*>(p)) U(std::forward<A>(a)...);
    }
  };
  using code_buffer = std::vector<std::uint32_t, uninitialized<std::uint32_t>>;
  void refresh() const;  // at_ gets the rows
  void settle() const;   // and the sketches the buffered codes
  void add_codes(const code_buffer& codes) const;
  void compute_quantiles() const;  // quantiles_, for every time and both sketches
  std::vector<double> times_;
  std::size_t levels_ = 0;
  std::uint64_t realizations_ = 0;
  std::vector<std::uint64_t> sticking_;
  moment_rows position_, velocity_, relative_velocity_, energy_;
  mutable std::vector<time_point_statistics> at_;  // empty until first read (refresh())
  mutable bool at_stale_ = false;  // the rows changed since at_ got them
  std::vector<std::uint64_t> level_counts_;  // times x levels, row-major
  mutable code_buffer codes_;
  // quantiles(): per time, the position's then the velocity's quantiles
  // (empty: to be computed)
  mutable std::vector<double> quantiles_;
};

// The quantile levels written for x and x' (5, 25, 50, 75, 95 %).
inline constexpr double observed_quantile_levels[] = {0.05, 0.25, 0.5, 0.75, 0.95};

}  // namespace stickslip
