// One realization of a point with uncertain parameters, replayed alone as the
// sweep draws it: what `stickslip simulate --realization R` with a law and
// Python's stickslip.simulate(realization=R) with a law compute.
//
// It belongs beside replay() (replay_request carrying the laws); it lives in
// the I/O library only because the report is what both front ends print.
#pragma once
#include <string>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/io/realization_output.hpp"

namespace stickslip::io {

// Realization `request.realization` of the sweep point with parameters
// `request.parameters` and laws `laws` (canonical symbols, in the sweep's
// order: io::sort_laws): the values drawn with draw_realization (key
// uncertain_point_key, or common_stream_key with common random numbers),
// then the run at them with simulate_with_values, the sweep's engine choice.
// The record is the sweep's record r (records.csv) bit for bit.
// Validates as a sweep does (validate_laws: exit 2 naming the parameter, the
// law and the domain). Precondition: no fixed x0, x'0, belt start or switch
// times in `request` (a drawn realization is replayed whole; the sweep's
// starting belt level is request.initial.belt_start).
[[nodiscard]] realization_report replay_uncertain(const replay_request& request,
                                                  std::vector<uncertain_parameter> laws);

// The refusals both front ends give, in the command line's words (Python
// maps the flags to its keywords):
//   no realization index with a law: one trajectory of an uncertain model is
//   realization R of the sweep point (--realization R);
//   a fixed input (--x0 X, ...) with a law: the realization is replayed whole.
[[nodiscard]] error realization_required(const std::vector<uncertain_parameter>& laws);
[[nodiscard]] error fixed_input_with_laws(const std::string& flag, const std::string& value,
                                          const std::vector<uncertain_parameter>& laws);

}  // namespace stickslip::io
