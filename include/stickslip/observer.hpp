// Observers receive what the integrator computes (Boost.Odeint style: system,
// stepper and observer are separate). Any type with these members works;
// inherit observer_base to get no-op defaults that the compiler removes.
#pragma once
#include <type_traits>

#include "stickslip/episode.hpp"

namespace stickslip {

struct observer_base {
  void on_event(const event&) noexcept {}
  void on_segment(const segment&) noexcept {}
  void on_episode(const episode&) noexcept {}
};

struct null_observer : observer_base {};

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
};

}  // namespace stickslip
