// One realization at drawn parameter values, and the sweep's blocks of a
// point with uncertain parameters (sweep_spec::uncertain).
//
// A point with laws has one stream key, uncertain_point_key(point, laws)
// (common_stream_key with common random numbers). Realization r of it
//   1. draws its parameter values: draw_values(laws, seed, key, r)
//      (substream uncertain_parameters, words 0 .. d-1);
//   2. runs at those values with its own intrinsic randomness, the initial
//      conditions and the belt drawn from the same key and realization as
//      any realization (substreams 0, 1, 2), on the engine draw_engine
//      (engines/point_engine.hpp) gives the drawn model: simulate() for
//      the paper's model, else the reference engine
//      (model/model_realization.hpp).
// So a realization replays alone from (seed, key, r), and its draws depend
// on nothing else: not on the other points, realizations, threads or ranks.
// Points with laws run one realization at a time (no lanes).
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "stickslip/belt_switches.hpp"
#include "stickslip/engines/point_engine.hpp"
#include "stickslip/initial_conditions.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/model/model_realization.hpp"
#include "stickslip/statistics.hpp"
#include "stickslip/sweep_spec.hpp"
#include "stickslip/uncertainty/uncertain_draws.hpp"

namespace stickslip {

// validate_laws at every grid point's values of the axes (each axis value
// with the others at their first value, as validate(sweep_spec) checks the
// axes): called by validate(sweep_spec). Nothing without laws.
void validate_uncertain_points(const sweep_spec& s);

// The stream key of grid point `point` of a spec with laws:
// uncertain_point_key of its parameters, or common_stream_key with common
// random numbers.
[[nodiscard]] std::uint64_t uncertain_stream_key(const sweep_spec& s, std::size_t point);

// Realization `realization`'s intrinsic randomness (initial conditions and
// belt, streams keyed by `key`) run at the parameters `drawn` into `obs`:
// resets `obs` (obs.reset(realization, x0, x'0, belt start)) and simulates;
// the caller then calls obs.finish(). Precondition: validate(drawn) passed;
// `obs` was made for `drawn` (realization_observer(drawn, ...): its window,
// friction, damping and levels). s supplies the seed, the initial-condition
// law and the event bound. Throws work_bound_exceeded as simulate() does.
template <class Observer>
event_counts simulate_with_values(const sweep_spec& s, const model_parameters& drawn,
                                  std::uint64_t key, std::uint64_t realization, Observer& obs);

// The same, finished: a realization_observer made for `drawn` (with
// s.family_statistics, s.burn_in and s.observe_times) holding realization r's record (events included) and
// samples. What a sensitivity design evaluates per row and input; what
// `simulate --realization` replays.
[[nodiscard]] realization_observer observe_with_values(const sweep_spec& s,
                                                       const model_parameters& drawn,
                                                       std::uint64_t key,
                                                       std::uint64_t realization);

// The parameters realization r of grid point `point` runs at, and the values
// it drew (in the order of s.uncertain). Validates the drawn model.
struct drawn_realization {
  model_parameters parameters;
  std::vector<double> values;
};
[[nodiscard]] drawn_realization draw_realization(const sweep_spec& s, std::size_t point,
                                                 std::uint64_t realization);

// A unit of a point with laws: each realization drawn, run and added in
// realization order (point_statistics::add with the realization's own
// window). The point's statistics are built on its median parameters
// (point_parameters: each uncertain value at its law's median), which fix
// the histogram ranges. Records (keep_records) carry the drawn values.
// The likelihood-ratio scores (d mean / d lambda, the rates' and the
// generator's, R's causal score) assume the switching law and the window of
// the point: they stay valid for laws over other parameters (their
// centring holds given each draw), and are left empty when a law is over
// lambda, ta, r1 or r2 (writers then report NaN).
[[nodiscard]] block_result simulate_block_uncertain(const sweep_spec& s, const work_unit& u);

// ---- implementation of the template ----
template <class Observer>
event_counts simulate_with_values(const sweep_spec& s, const model_parameters& drawn,
                                  std::uint64_t key, std::uint64_t realization, Observer& obs) {
  if (draw_engine(drawn) == point_engine::paper_integrator) {
    const model_parameters p = paper_form(drawn);
    const auto ic = draw_initial_conditions(s.initial, s.seed, key, realization);
    poisson_switches switches(p.switch_rate, s.seed, key, realization);
    obs.reset(realization, ic.position, ic.velocity, ic.belt_direction);
    return simulate(p, ic, switches, obs, s.max_events);
  }
  const family_point fp(drawn, key);
  const model_initial_state start = draw_model_initial_state(fp, s.initial, s.seed, realization);
  obs.reset(realization, start.position, start.velocity,
            recorded_belt_start(start.level, fp.model.belt.level_count()));
  return simulate_family_realization(fp, start, s.seed, realization, s.max_events, obs);
}

}  // namespace stickslip
