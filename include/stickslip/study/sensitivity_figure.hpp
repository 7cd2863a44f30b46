// The figure of a sensitivity study: first- and total-order Sobol' indices
// of the mean response, one pair of bars per uncertain input, with their
// 95 % intervals as whiskers, and the parameter and intrinsic shares in the
// title. Written as sensitivity.dat + sensitivity.gp and rendered to PNG and
// SVG by gnuplot (figures.hpp), so a user can edit and rerun it.
#pragma once
#include <string>

#include "stickslip/study/figures.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::study {

// Precondition: `rs` is a finished sensitivity study
// (uncertainty/sensitivity_design.hpp). Renders when `render` and gnuplot is
// available; figure::rendered says whether it did.
[[nodiscard]] figure write_sensitivity_figure(const result_set& rs, const std::string& dir,
                                              bool render);

}  // namespace stickslip::study
