#include "stickslip/replay.hpp"

#include "stickslip/belt_switches.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip {
namespace {

// Everything the integrator reports about one realization.
struct trace_observer : observer_base {
  realization_trace& out;
  bool keep_events, keep_segments;
  void on_event(const event& e) {
    if (keep_events) out.events.push_back(e);
  }
  void on_segment(const segment& s) {
    if (keep_segments) out.segments.push_back(s);
  }
  void on_episode(const episode& e) { out.episodes.push_back(e); }
};

}  // namespace

realization_trace replay(const replay_request& r) {
  sweep_spec spec;  // the sweep's checks for one point, e.g. lambda * ta vs max_events
  spec.base = r.parameters;
  // With given switch times the switch rate plays no role, so lambda = 0 is
  // accepted then (and kept in the outputs, which say what was asked).
  if (r.switch_times && spec.base.switch_rate == 0.0) spec.base.switch_rate = 1.0;
  spec.seed = r.seed;
  spec.initial = r.initial;
  spec.max_events = r.max_events;
  spec.common_random_numbers = r.common_random_numbers;
  validate(spec);
  if (r.switch_times) validate_switch_times(*r.switch_times);

  realization_trace out;
  const auto key = stream_key(spec, r.parameters);
  auto& ic = out.initial;
  ic = draw_initial_conditions(r.initial, r.seed, key, r.realization);
  if (r.x0) ic.position = *r.x0;
  if (r.xdot0) ic.velocity = *r.xdot0;
  if (r.belt_start) ic.belt_direction = *r.belt_start;
  validate(ic);

  trace_observer trace{{}, out, r.keep_events, r.keep_segments};
  realization_observer stats(r.parameters.window);
  stats.reset(r.realization, ic.position, ic.velocity, ic.belt_direction);
  observer_pair<trace_observer, realization_observer> both{trace, stats};
  event_counts counts;
  if (r.switch_times) {
    given_switches sw(*r.switch_times);
    counts = simulate(r.parameters, ic, sw, both, r.max_events);
  } else {
    poisson_switches sw(r.parameters.switch_rate, r.seed, key, r.realization);
    counts = simulate(r.parameters, ic, sw, both, r.max_events);
  }
  stats.finish();
  out.record = stats.record();
  out.record.events = counts;
  return out;
}

}  // namespace stickslip
