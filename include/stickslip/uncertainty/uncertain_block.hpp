// What a sensitivity design (uncertainty/sensitivity.hpp) needs of a point
// with uncertain parameters: its stream key, and one realization run at
// given parameter values, finished. The sweep's own path (draws, blocks)
// is uncertain_realization.hpp; these are thin views of it, so a design row
// and a sweep realization run the very same code.
#pragma once
#include <cstdint>
#include <vector>

#include "stickslip/random_stream.hpp"
#include "stickslip/statistics.hpp"
#include "stickslip/sweep_spec.hpp"
#include "stickslip/uncertainty/uncertain_draws.hpp"
#include "stickslip/uncertainty/uncertain_realization.hpp"

namespace stickslip {

// The stream key of a point with laws: uncertain_point_key(p, s.uncertain),
// or common_stream_key with common random numbers. uncertain_point_key
// ignores the values `p` holds for the uncertain symbols, so p may be the
// point with its base values or at its medians (point_parameters): the same
// key as uncertain_stream_key(s, point).
[[nodiscard]] inline std::uint64_t uncertain_stream_key(const sweep_spec& s,
                                                        const model_parameters& p) noexcept {
  return s.common_random_numbers ? common_stream_key : uncertain_point_key(p, s.uncertain);
}

// One finished realization: its record (events set) and the durations its
// observer listed (D_i of the sticks, H_i of the counted slips).
struct uncertain_run {
  realization_record record;
  std::vector<double> stick_durations, slip_durations;
};

// Realization `realization`'s intrinsic randomness (initial conditions,
// belt; streams keyed by `key`) run at the parameters `drawn`.
// Precondition: validate(drawn) passed (the laws' domains hold).
// record.drawn_values is left empty: the caller knows what it drew.
[[nodiscard]] inline uncertain_run simulate_uncertain_realization(const sweep_spec& s,
                                                                  const model_parameters& drawn,
                                                                  std::uint64_t key,
                                                                  std::uint64_t realization) {
  realization_observer obs = observe_with_values(s, drawn, key, realization);
  return {obs.record(), obs.stick_durations(), obs.slip_durations()};
}

}  // namespace stickslip
