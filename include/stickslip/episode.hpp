// What the engines report (simulate, simulate_model and the lanes): events
// (instants) and episodes (maximal stick or slip intervals). Episodes tile
// [0, t_a]; a slip episode runs through belt switches and slip reversals.
// The stick band at belt level v is |x - b| <= a_s, b = -c v / k
// (docs/model.md); in the paper's model b = 0 and a_s = a_k = a.
#pragma once
#include <cstdint>

#include "stickslip/motion_mode.hpp"

namespace stickslip {

enum class event_kind : unsigned char {
  belt_switch,    // the belt changes level (in the paper's model it flips sign at
                  // Poisson times); ends any stick
  stick_onset,    // a slip reaches x' = v inside the stick band
  stick_break,    // a stick reaches the band edge x = b + sgn(v) a_s
  slip_reversal,  // a slip reaches x' = v outside the band; slip continues the other way
};

inline constexpr const char* to_string(event_kind k) noexcept {
  switch (k) {
    case event_kind::belt_switch: return "belt_switch";
    case event_kind::stick_onset: return "stick_onset";
    case event_kind::stick_break: return "stick_break";
    case event_kind::slip_reversal: return "slip_reversal";
  }
  return "?";
}

// The state at an event, taken just after the event has acted
// (belt_velocity is the new one after a belt switch).
struct event {
  event_kind kind;
  double time;
  double position;       // x
  double velocity;       // x'
  double belt_velocity;  // v after the event
};

// The events of a realization (or of many: += merges), by kind.
struct event_counts {
  std::uint64_t belt_switches = 0, stick_onsets = 0, stick_breaks = 0, slip_reversals = 0;
  // The sum of the belt switch times in [0, t_a], in time order (not a
  // count: the integral of N(t) over the window is N t_a minus it, which the
  // causal likelihood-ratio derivative needs; docs/precision.md).
  double switch_time_sum = 0.0;
  [[nodiscard]] std::uint64_t total() const noexcept {
    return belt_switches + stick_onsets + stick_breaks + slip_reversals;
  }
  friend bool operator==(const event_counts&, const event_counts&) = default;
  event_counts& operator+=(const event_counts& o) noexcept {
    belt_switches += o.belt_switches;
    stick_onsets += o.stick_onsets;
    stick_breaks += o.stick_breaks;
    slip_reversals += o.slip_reversals;
    switch_time_sum += o.switch_time_sum;
    return *this;
  }
};

struct episode {
  mode kind;
  double start;
  double end;
  double position_at_start;  // x at `start`
  double belt_velocity;      // v at `start`
  bool censored;             // cut off by the end of the window t_a
  // N(start): the belt switches in [0, start], the switch that starts the
  // episode included (a count, exact in a double, which the lane engine
  // keeps it in). Constant during a stick (a switch ends every stick), so it
  // gives the causal likelihood-ratio derivative its integral of N(t) over
  // the sticks (docs/precision.md).
  double switches_before = 0.0;
  [[nodiscard]] double duration() const noexcept { return end - start; }
};

// One closed-form piece of motion between two consecutive events.
// Stick:  x(t) = x0 + v (t - t0),                 x'(t) = v.
// Slip:   x(t) = c + (x0 - c) cos w(t-t0) + (x0'/w) sin w(t-t0),
//         x'(t) = x0' cos w(t-t0) - w (x0 - c) sin w(t-t0),
//         c = sigma a_k, sigma = sgn(v - x') (sigma a in the paper's model).
// With damping (the model family, model/model_engine.hpp), y = x - c obeys
// y'' + 2 gamma y' + w^2 y = 0 from (x0 - c, x0'): model/damped_slip.hpp.
struct segment {
  mode kind;
  double start, end;
  double position, velocity;  // x, x' at start
  double belt_velocity;       // v during the segment
  double center;              // c = sigma a_k while slipping (0 while sticking)
  double omega;               // omega_0 = sqrt(k/m)
  double decay_rate = 0.0;    // gamma = c / 2m: 0 in the paper's model
};

struct phase_point {
  double position, velocity;
};

[[nodiscard]] phase_point evaluate(const segment& s, double t) noexcept;

}  // namespace stickslip
