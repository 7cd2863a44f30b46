// `stickslip plot DIR`: a figure of any finished sweep (DIR/results.nc) or
// sensitivity study (DIR/sensitivity.nc), read generically: statistics are
// found by their variable names and symbols, labels come from the `units`
// and `long_name` attributes. Kinds:
//   curves     --y STAT --x AXIS [--by AXIS]: the mean against an axis, one
//              curve per value of another, with the 95 % band
//   heat map   --map --y STAT --x AXIS --by AXIS
//   histogram  --histogram STAT --at POINT [--at POINT ...]
//   time       --time [--y VAR] --at POINT ...: a variable over `time`
//   survival   --survival stick|slip --at POINT ...: NAME_survival over its
//              duration coordinate, with its 95 % band
//   bars       a sensitivity result: first- and total-order indices per input
// Planning reads and checks everything and writes nothing, so a bad request
// exits before any file exists (docs/plot.md).
#pragma once
#include <string>
#include <vector>

#include "stickslip/io/result_file.hpp"
#include "stickslip/study/plot_figures.hpp"
#include "stickslip/study/plot_request.hpp"

namespace stickslip::study {

// DIR/results.nc, else DIR/sensitivity.nc. Throws invalid_input when DIR
// holds neither.
[[nodiscard]] std::string find_result_file(const std::string& dir);

// The figure `r` asks for. Throws stickslip::error (invalid_input) naming
// the flag, its value and what is allowed.
[[nodiscard]] plot_figure plan_plot(const io::result_file& f, const plot_request& r);

}  // namespace stickslip::study
