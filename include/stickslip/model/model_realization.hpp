// One realization of a grid point of any model, drawn exactly as a sweep
// draws it: the reference engine (engines/point_engine.hpp) that the sweep,
// `simulate --seed --realization` and the Python package share; the paper's
// model is its undamped two-level case (the lane engine draws these same
// values).
//
// Random inputs, each a pure function of (seed, point_key, realization,
// substream, index):
//   x0, x'0     draw_initial_conditions (substream 0, words 0 and 1);
//   start level the law's belt_start, or the stationary law: for two levels
//               left at equal rates (pi = 1/2, 1/2) the paper's direction bit
//               (word 2), otherwise draw_stationary_level (word 3);
//   the belt    markov_level_switches (substreams 1 and 2).
#pragma once
#include <cstdint>

#include "stickslip/initial_conditions.hpp"
#include "stickslip/model/belt_chain.hpp"
#include "stickslip/model/model_engine.hpp"
#include "stickslip/model/oscillator_model.hpp"
#include "stickslip/parameters.hpp"
#include "stickslip/random_stream.hpp"

namespace stickslip {

// What one grid point of the family needs, computed once per block.
struct family_point {
  oscillator_model model;
  belt_chain chain;
  std::uint64_t key;
  bool even_two_level;  // two levels left at equal rates: pi = (1/2, 1/2)

  // Precondition: validate(p) passed. `key` is the point's stream key:
  // point_key(p), or common_stream_key with common random numbers
  // (stream_key in sweep.hpp).
  family_point(const model_parameters& p, std::uint64_t stream)
      : model(model_of(p)),
        chain(model.belt),
        key(stream),
        even_two_level(model.belt.level_count() == 2 &&
                       model.belt.leaving_rate(0) == model.belt.leaving_rate(1)) {}
  explicit family_point(const model_parameters& p) : family_point(p, point_key(p)) {}
};

// The starting level index of initial_condition_law::belt_start: 0 = the
// stationary law, +1 = the first level, -1 = the second (two levels), k >= 1
// = level k. `direction` is the paper's direction draw (+1 or -1).
[[nodiscard]] inline std::size_t start_level(const family_point& fp, int belt_start, int direction,
                                             std::uint64_t seed, std::uint64_t realization) noexcept {
  if (belt_start == -1) return 1;
  if (belt_start >= 1) return static_cast<std::size_t>(belt_start - 1);
  if (fp.even_two_level) return direction > 0 ? 0 : 1;
  return draw_stationary_level(fp.chain, seed, fp.key, realization);
}

// The initial state of realization r: x0, x'0 and the starting level.
[[nodiscard]] inline model_initial_state draw_model_initial_state(
    const family_point& fp, const initial_condition_law& law, std::uint64_t seed,
    std::uint64_t realization) noexcept {
  const initial_conditions ic = draw_initial_conditions(law, seed, fp.key, realization);
  return {ic.position, ic.velocity,
          start_level(fp, law.belt_start, ic.belt_direction, seed, realization)};
}

// Realization r from `start` with the belt drawn from its streams.
template <class Observer>
event_counts simulate_family_realization(const family_point& fp, const model_initial_state& start,
                                         std::uint64_t seed, std::uint64_t realization,
                                         std::int64_t max_events, Observer& obs) {
  markov_level_switches switches(fp.chain, start.level, seed, fp.key, realization);
  return simulate_model(fp.model, start, switches, obs, max_events);
}

}  // namespace stickslip
