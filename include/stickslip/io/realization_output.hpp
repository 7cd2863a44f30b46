// The outputs of `stickslip simulate` for one realization: the episode
// table (CSV or JSON), the event list and the sampled trajectory. Pure
// text; writing it to files is io::write_text_files (output_files.hpp).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "stickslip/replay.hpp"
#include "stickslip/uncertainty/parameter_law.hpp"

namespace stickslip::io {

// One realization as replay() computed it, with what was asked: the
// parameters, seed and index, and which inputs were given rather than drawn.
struct realization_report {
  replay_request request;
  realization_trace trace;
  // With uncertain parameters (replay_uncertain, uncertain_replay.hpp): the
  // laws and the values realization r drew from them, in the same order;
  // request.parameters is then the model it ran at.
  std::vector<uncertain_parameter> uncertain;
  std::vector<double> drawn;
};

// mode,start,end,x_start,belt_velocity,censored (one row per episode).
[[nodiscard]] std::string episodes_csv(const realization_report& r);
// kind,time,x,xdot,v (one row per event).
[[nodiscard]] std::string events_csv(const realization_report& r);
// {"parameters", "seed", "realization"[, "laws", "drawn"], "initial_conditions",
//  "switch_times", "statistics", "event_counts", "episodes"[, "events"]};
// "statistics" holds the record's outcome fields (record_schema.hpp);
// with laws, "laws" maps each uncertain symbol to its law's canonical text
// and "drawn" to the value realization r drew ("parameters" is the model at
// those values).
[[nodiscard]] std::string realization_json(const realization_report& r, bool with_events);
// t,x,xdot,v,mode sampled by sample_trajectory (trajectory.hpp) every `step`.
[[nodiscard]] std::string trajectory_csv(const realization_report& r, double step);

}  // namespace stickslip::io
