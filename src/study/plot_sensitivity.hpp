// The bars of a sensitivity result (sensitivity.nc): what `stickslip plot`
// draws for one. Internal to src/study.
#pragma once
#include "stickslip/io/result_file.hpp"
#include "stickslip/study/plot_figures.hpp"
#include "stickslip/study/plot_request.hpp"

namespace stickslip::study::detail {

// One group of bars per index variable over `input` (--y, by default
// first_order and total_order), one bar per uncertain input, whiskers from
// the variable's _ci95_low/_high. Refuses the flags of a grid plot.
[[nodiscard]] bar_plot plan_sensitivity_bars(const io::result_file& f, const plot_request& r);

}  // namespace stickslip::study::detail
