// The state of one realization at the observe times (sweep --observe-times):
// fed the closed-form segments of the motion (episode.hpp) in time order, it
// evaluates the segment that holds each time t_j (evaluate(): no
// interpolation, no step). Conventions, for every engine:
//   - t_j belongs to the segment with start <= t_j < end: at an event time the
//     state just after the event (a stick that starts at t_j is sticking at
//     t_j, one that ends there is not); a zero-length segment holds no time;
//   - t_j = t_a belongs to the last segment (end = t_a): the state at t_a.
// The reference engines pass every segment (state_sampling_observer in
// statistics.hpp); the lane engine writes the start state of the round that
// holds each observe time at it, and evaluates a realization's states in
// place when it ends, with the vector forms of evaluate()'s closed forms and
// kernels and of record_next's energy and level (fast_lanes.cpp): both give
// the same bits.
#pragma once
#include <cstddef>
#include <limits>
#include <vector>

#include "stickslip/accumulators/time_statistics.hpp"
#include "stickslip/episode.hpp"

namespace stickslip {

class state_sampler {
 public:
  state_sampler() = default;  // no observe times: does nothing
  // `times`: ascending, within [0, window] (validate()); `levels`: the belt
  // levels v_1..v_n (distinct), the level of a segment is the index of its v.
  state_sampler(const std::vector<double>& times, std::vector<double> levels, double window,
                double mass, double stiffness)
      : times_(&times), levels_(std::move(levels)), window_(window), mass_(mass),
        stiffness_(stiffness), states_(times.size()) {}

  [[nodiscard]] bool active() const noexcept { return times_ && !times_->empty(); }
  void reset() noexcept { next_ = 0; }
  // The next observe time not yet sampled (+inf when all are).
  [[nodiscard]] double next_time() const noexcept {
    return next_ < states_.size() ? (*times_)[next_] : std::numeric_limits<double>::infinity();
  }
  // Whether segment `s` holds an observe time not yet sampled.
  [[nodiscard]] bool holds_next(const segment& s) const noexcept {
    return next_ < states_.size() &&
           ((*times_)[next_] < s.end || (s.end >= window_ && (*times_)[next_] <= window_));
  }
  void on_segment(const segment& s) {
    if (holds_next(s)) sample(s);
  }
  // The lane engine's path: it fills the state of every time itself, with
  // record_next's values (fast_lanes.cpp), and then marks them sampled. Precondition of mark_sampled: each of the times filled.
  [[nodiscard]] observed_states& states_to_fill() noexcept { return states_; }
  void mark_sampled() noexcept { next_ = states_.size(); }
  [[nodiscard]] const std::vector<double>& levels() const noexcept { return levels_; }
  [[nodiscard]] double mass() const noexcept { return mass_; }
  [[nodiscard]] double stiffness() const noexcept { return stiffness_; }
  // After the last segment: every time sampled (the segments tile [0, t_a]).
  [[nodiscard]] bool complete() const noexcept { return next_ == states_.size(); }
  [[nodiscard]] const observed_states& states() const noexcept { return states_; }

 private:
  void sample(const segment& s);
  // The state (x, x') at next_time() (evaluate()), in a segment at belt
  // velocity v, with its energy and level; the time is then sampled.
  void record_next(double position, double velocity, double belt_velocity, bool sticking) noexcept;
  const std::vector<double>* times_ = nullptr;
  std::vector<double> levels_;
  double window_ = 0.0, mass_ = 0.0, stiffness_ = 0.0;
  std::size_t next_ = 0;
  observed_states states_;
};

}  // namespace stickslip
