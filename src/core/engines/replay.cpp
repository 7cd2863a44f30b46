#include "stickslip/replay.hpp"

#include <fmt/format.h>

#include "stickslip/belt_switches.hpp"
#include "stickslip/engines/point_engine.hpp"
#include "stickslip/model/model_realization.hpp"
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

// Runs `simulate(observer)` into the trace and a realization_observer
// started from out.initial, and stores the realization's record.
template <class Simulate>
void trace_realization(const replay_request& r, const model_parameters& p, realization_trace& out,
                       Simulate simulate) {
  trace_observer trace{{}, out, r.keep_events, r.keep_segments};
  realization_observer stats(p, true, r.burn_in);
  stats.reset(r.realization, out.initial.position, out.initial.velocity,
              out.initial.belt_direction);
  observer_pair<trace_observer, realization_observer> both{trace, stats};
  const event_counts counts = simulate(both);
  stats.finish();
  out.record = stats.record();
  out.record.events = counts;
}

// The reference engine, simulate_model, for every model (the paper's is its
// undamped two-level case, the same bits as simulate): the start drawn as
// the sweep draws it (model_realization.hpp) from the streams of `key`, then
// the fixed inputs.
void replay_reference(const replay_request& r, const sweep_spec& spec, std::uint64_t key,
                      realization_trace& out) {
  detail::count_engine_run(point_engine::reference);
  const model_parameters& p = spec.base;
  const family_point fp(p, key);
  const std::size_t levels = fp.model.belt.level_count();
  model_initial_state start = draw_model_initial_state(fp, r.initial, r.seed, r.realization);
  if (r.x0) start.position = *r.x0;
  if (r.xdot0) start.velocity = *r.xdot0;
  if (r.belt_start) start.level = level_of_belt_start(*r.belt_start);
  validate(start, fp.model.belt);
  out.initial = {start.position, start.velocity, recorded_belt_start(start.level, levels)};

  trace_realization(r, p, out, [&](auto& observer) {
    if (!r.switch_times)
      return simulate_family_realization(fp, start, r.seed, r.realization, r.max_events, observer);
    std::vector<level_switch> switches;
    if (r.switch_levels) {
      for (std::size_t i = 0; i < r.switch_times->size(); ++i)
        switches.push_back({(*r.switch_times)[i], (*r.switch_levels)[i]});
    } else {
      switches = alternating_switches(*r.switch_times, start.level);
    }
    validate_level_switches(switches, levels, start.level);
    given_level_switches sw(switches);
    return simulate_model(fp.model, start, sw, observer, r.max_events);
  });
}

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
  // After the model's checks (t_a > 0); its own message, since the sweep's
  // names a grid.
  if (r.burn_in != 0.0 && (!(r.burn_in > 0.0) || !(r.burn_in < r.parameters.window)))
    throw invalid_parameter("burn_in", r.burn_in,
                            fmt::format("0 <= burn_in < t_a = {} (the realization's window; 0 = "
                                        "no burn-in)",
                                        r.parameters.window));
  const std::size_t levels = spec.base.levels().size();
  if (r.belt_start) validate_belt_start(*r.belt_start, levels, false);
  if (r.switch_levels && (!r.switch_times || r.switch_levels->size() != r.switch_times->size()))
    throw invalid_value("switch levels", std::to_string(r.switch_levels->size()) + " levels",
                        "one level per switch time");
  if (r.switch_times && !r.switch_levels && levels != 2)
    throw invalid_value("switch times", "without levels",
                        "a level for every switch: the belt has " + std::to_string(levels) +
                            " levels, so 'go to the other one' is not defined");
  if (r.switch_times) validate_switch_times(*r.switch_times);

  // The streams of the point as asked. With given switch times and lambda =
  // 0, the paper's model keys lambda = 0 (its bits of 0.1.0) and any other
  // model the rate 1 the checks above ran with.
  const std::uint64_t key = stream_key(spec, r.parameters.is_paper_model() ? r.parameters : spec.base);
  realization_trace out;
  replay_reference(r, spec, key, out);
  return out;
}

}  // namespace stickslip
