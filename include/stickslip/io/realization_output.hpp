// The outputs of `stickslip simulate` for one realization: the episode
// table (CSV or JSON), the event list and the sampled trajectory. Pure
// text; writing it to files is io::write_text_files (output_files.hpp).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "stickslip/episode.hpp"
#include "stickslip/initial_conditions.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/parameters.hpp"
#include "stickslip/statistics.hpp"

namespace stickslip::io {

// Everything the integrator reported about one realization, and how its
// inputs were chosen (drawn from the streams or given for a replay).
struct realization_report {
  model_parameters params;
  std::uint64_t seed = 1, realization = 0;
  initial_conditions ic;
  bool given_x0 = false, given_xdot0 = false, given_belt = false, given_switches = false;
  event_counts counts;
  realization_record record;
  std::vector<episode> episodes;
  std::vector<event> events;
  std::vector<segment> segments;
};

// mode,start,end,x_start,belt_velocity,censored (one row per episode).
[[nodiscard]] std::string episodes_csv(const realization_report& r);
// kind,time,x,xdot,v (one row per event).
[[nodiscard]] std::string events_csv(const realization_report& r);
// {"parameters", "seed", "realization", "initial_conditions", "switch_times",
//  "statistics", "event_counts", "episodes"[, "events"]}.
[[nodiscard]] std::string realization_json(const realization_report& r, bool with_events);
// t,x,xdot,v,mode sampled by sample_trajectory (trajectory.hpp) every `step`.
[[nodiscard]] std::string trajectory_csv(const realization_report& r, double step);

}  // namespace stickslip::io
