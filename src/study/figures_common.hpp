// Helpers shared by the figure writers: data files, script preambles and
// the PNG + SVG rendering loop. Internal to src/io.
#pragma once
#include <string>
#include <vector>

#include <fmt/format.h>

#include "stickslip/study/figures.hpp"

namespace stickslip::study::detail {

// Writes `text` to `path` atomically.
void write_text_file(const std::string& path, const std::string& text);

// A number for a data file or a script: shortest round-trip text, NaN as "NaN".
[[nodiscard]] std::string num(double x);

// A gnuplot string literal in double quotes (backslash, quote and '@' escaped).
[[nodiscard]] std::string gp_string(const std::string& s);

// The head of every script: a comment that says how to rerun it, UTF-8, the
// line styles. `size` is the canvas in pixels (PNG); SVG gets the same size.
[[nodiscard]] std::string gp_preamble(const figure& f, int width, int height);

// Wraps the plotting commands `body` in a loop over the PNG and SVG terminals.
[[nodiscard]] std::string gp_render_loop(const figure& f, int width, int height,
                                         const std::string& body);

// Writes `dat` (if not empty) and the script, then renders when asked.
void finish_figure(figure& f, const std::string& dat, const std::string& script, bool render);

// The mu of the grid nearest to `mu`.
[[nodiscard]] double nearest_mu(const result_set& rs, double mu);
// The lambda values of the grid nearest to each wanted value (distinct, sorted).
[[nodiscard]] std::vector<double> nearest_lambdas(const result_set& rs,
                                                  const std::vector<double>& wanted);

// "m=1 kg, k=40 N/m, g=9.81 m/s^2, V=1 m/s, t_a=50 s" (enhanced-text safe).
[[nodiscard]] std::string parameter_line(const model_parameters& p);

}  // namespace stickslip::study::detail
