// Physics-free figures: curves with 95 % bands, a heat map over two axes,
// and bars with error bars. Each is described by plain values (what to draw,
// the labels, the file stem) and written like every figure of stickslip
// (figures.hpp): a .dat file, a .gp script, and PNG + SVG rendered by
// gnuplot. `stickslip plot` fills these from any results.nc or
// sensitivity.nc (study/plot.hpp).
#pragma once
#include <string>
#include <variant>
#include <vector>

#include "stickslip/study/figures.hpp"

namespace stickslip::study {

// The text around a figure: file stem, title, caption, axis labels.
struct figure_text {
  std::string stem, title, caption, xlabel, ylabel;
};

// One curve: y against x, with a band [low, high] (empty: no band).
struct plot_series {
  std::string label;
  std::vector<double> x, y, low, high;
};

enum class curve_style {
  points,      // a statistic over a swept axis: lines through marked points
  lines,       // a curve over a fine coordinate (time)
  steps,       // a step function (a survival curve)
  histogram,   // densities over bin centres (steps between the bins)
};

struct curve_plot {
  figure_text text;
  curve_style style = curve_style::points;
  bool logx = false;
  std::vector<plot_series> series;
};

// z over the grid x × y, z[i * y.size() + j] at (x[i], y[j]); each value
// fills its cell, whose edges are halfway between neighbouring values
// (geometrically halfway on a log axis).
struct map_plot {
  figure_text text;
  std::string zlabel;
  bool logx = false, logy = false;
  std::vector<double> x, y, z;
};

// Groups of bars with error bars, one bar per category in each group.
struct bar_group {
  std::string label;
  std::vector<double> value, low, high;  // one per category
};
struct bar_plot {
  figure_text text;
  std::vector<std::string> categories;
  std::vector<bar_group> groups;
};

using plot_figure = std::variant<curve_plot, map_plot, bar_plot>;

[[nodiscard]] const figure_text& text_of(const plot_figure& p);

// Writes dir/STEM.dat and dir/STEM.gp, and renders STEM.png and STEM.svg
// when `render` (figure::rendered says whether gnuplot succeeded).
[[nodiscard]] figure write_plot_figure(const plot_figure& p, const std::string& dir, bool render);

// Text for gnuplot's enhanced mode: _ ^ { } & ~ shown as themselves.
[[nodiscard]] std::string literal_text(const std::string& s);

}  // namespace stickslip::study
