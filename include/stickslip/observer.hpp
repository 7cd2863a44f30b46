// Observers receive what the integrator computes (Boost.Odeint style: system,
// stepper and observer are separate). Any type with these members works;
// inherit observer_base to get no-op defaults that the compiler removes.
#pragma once
#include <cmath>
#include <cstddef>
#include <type_traits>

#include "stickslip/episode.hpp"

namespace stickslip {

// One piece of motion between two consecutive state updates of an engine
// (an event, a touch of the band edge, t_a), at one belt level. `end_*` is
// the state the motion reaches, before the engine resolves what happens
// there (a contact clamps x into the band); the next piece starts from the
// resolved state. What the statistics integrate over time (the time at each
// belt level, the energy dissipated) is a sum over pieces (docs/model.md).
struct motion_piece {
  mode kind;
  std::size_t level;     // index of the belt level (paper's model: 0 = +V, 1 = -V)
  double duration;       // t_end - t_start
  double start_position, end_position;
  double start_velocity, end_velocity;  // x' (a stick: v)
  double belt_velocity;  // v
  double sigma;          // friction direction sgn(v - x') of a slip (0 while sticking)
  double start_time = 0.0, end_time = 0.0;  // t_start, t_end (duration = t_end - t_start)
  // The relative travel |v dt - dx| of a slip: sigma (v - x') keeps its sign
  // over a piece (a reversal ends it), so int |v - x'| dt = |v dt - dx|.
  [[nodiscard]] double relative_travel() const noexcept {
    return std::abs(belt_velocity * duration - (end_position - start_position));
  }
};

struct observer_base {
  void on_event(const event&) noexcept {}
  void on_segment(const segment&) noexcept {}
  void on_episode(const episode&) noexcept {}
  void on_piece(const motion_piece&) noexcept {}
};

struct null_observer : observer_base {};

// Whether an observer uses episode::switches_before and
// event_counts::switch_time_sum (the causal score of
// accumulators/score_moments.hpp): default yes; an observer opts out with
// `static constexpr bool causal_score = false`, and the lane engine then
// skips that bookkeeping (the paper study's observer: docs/performance.md).
template <class Observer>
inline constexpr bool wants_causal_score = [] {
  if constexpr (requires { Observer::causal_score; })
    return Observer::causal_score;
  else
    return true;
}();

// Whether the lane engine hands an observer the tallies of a realization's
// closed episodes (realization_observer::set_closed_episode_tallies) instead
// of each episode: an observer that declares `static constexpr bool
// episode_tallies = true` (the means only, without the causal score).
template <class Observer>
inline constexpr bool takes_episode_tallies = [] {
  if constexpr (requires { Observer::episode_tallies; })
    return Observer::episode_tallies;
  else
    return false;
}();

// Whether an observer takes events or segments itself, or inherits the no-ops
// of observer_base (the lane engine then skips building them, and refuses an
// observer of segments at compile time).
template <class Observer>
inline constexpr bool observes_events =
    !std::is_same_v<decltype(&Observer::on_event), void (observer_base::*)(const event&) noexcept>;
template <class Observer>
inline constexpr bool observes_segments =
    !std::is_same_v<decltype(&Observer::on_segment),
                    void (observer_base::*)(const segment&) noexcept>;

// Whether the engines report pieces of motion to an observer: any type with
// on_piece (observer_base's no-op included; the compiler removes it).
template <class Observer>
concept takes_pieces = requires(Observer& o, const motion_piece& p) { o.on_piece(p); };
// Whether an observer takes pieces itself (not observer_base's no-op).
template <class Observer>
inline constexpr bool observes_pieces =
    !std::is_same_v<decltype(&Observer::on_piece),
                    void (observer_base::*)(const motion_piece&) noexcept>;

// Fans one stream out to two observers.
template <class A, class B>
struct observer_pair {
  A& first;
  B& second;
  void on_event(const event& e) {
    first.on_event(e);
    second.on_event(e);
  }
  void on_segment(const segment& s) {
    first.on_segment(s);
    second.on_segment(s);
  }
  void on_episode(const episode& e) {
    first.on_episode(e);
    second.on_episode(e);
  }
  void on_piece(const motion_piece& p) {
    if constexpr (takes_pieces<A>) first.on_piece(p);
    if constexpr (takes_pieces<B>) second.on_piece(p);
  }
};

}  // namespace stickslip
