// Choosing what `stickslip plot` draws from a result file read generically
// (io/result_file.hpp): a quantity by name or symbol with its 95 % band, the
// values of an axis, the grid point nearest to `--at name=value`, and a
// variable's values along one dimension with every other one fixed. Errors
// name the flag, the value and what is allowed. Internal to src/study.
#pragma once
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "stickslip/io/result_file.hpp"

namespace stickslip::study::detail {

// A variable to draw, with what gives its 95 % interval: the variables
// `low`/`high`, or `half_width` (value +- it), or `std_error` (value +- z95
// se), or nothing.
struct quantity {
  std::string asked;            // the name as the user gave it
  const io::result_variable* value = nullptr;
  std::string low, high, half_width, std_error;
  [[nodiscard]] bool has_band() const {
    return !low.empty() || !half_width.empty() || !std_error.empty();
  }
  // "X_ci95_low, X_ci95_high", "X_ci95_half_width", "X_std_error x 1.96".
  [[nodiscard]] std::string band_text() const;
};

// `--y NAME`: the statistic NAME (its NAME_mean), the statistic whose mean
// has the symbol NAME ("R"), or the numeric variable NAME. An unknown NAME
// is refused with the names there are (over `along`, when given: "time" for
// --time) and the nearest of them.
[[nodiscard]] quantity find_quantity(const io::result_file& f, const std::string& flag,
                                     const std::string& name, const std::string& along = "");
// The statistics of the file (every X of an X_mean) as "X (symbol)".
[[nodiscard]] std::string statistic_list(const io::result_file& f);

struct axis {
  std::string name;
  std::vector<double> values;
  std::string label;  // "switch rate lambda (1/s)"
  bool log_spaced = false;
};
[[nodiscard]] axis axis_of(const io::result_file& f, const std::string& dim);

// "long name (units)", or the name when there is no long name.
[[nodiscard]] std::string axis_label(const io::result_variable& v);

// `values` (>= 3, positive) have one ratio between neighbours, to 1e-6:
// a log:a:b:n grid.
[[nodiscard]] bool log_spaced(const std::vector<double>& values);

// One `--at` set: "lambda=3.8,mu=5" -> {(lambda, 3.8), (mu, 5)}.
using at_set = std::vector<std::pair<std::string, double>>;
[[nodiscard]] at_set parse_at(const std::string& text);

// Indices of fixed dimensions, and how the choice reads in a title.
struct grid_choice {
  std::map<std::string, std::size_t> index;
  std::string text;  // "lambda = 3.718 (nearest to 3.8), mu = 5"
  std::string stem;  // "lambda3.718_mu5"
};
// Resolves an --at set against the dimensions of `var`: each name must be
// one of them and not in `free`, each value within the axis's range; the
// grid value nearest to it is used (nearest in log on a log-spaced axis).
[[nodiscard]] grid_choice choose_point(const io::result_file& f, const io::result_variable& var,
                                       const std::vector<std::string>& free, const at_set& at);

// Every dimension of `var` that is neither free nor chosen must have length
// 1 (fixed at 0); else the error says to give --by or --at for it.
void complete_point(const io::result_file& f, const io::result_variable& var,
                    const std::vector<std::string>& free, grid_choice& c);

// The values of `var` along `dim` at the indices `fixed` (all other dims).
[[nodiscard]] std::vector<double> slice(const io::result_file& f, const std::string& var,
                                        const std::string& dim,
                                        const std::map<std::string, std::size_t>& fixed);

// `q` along `dim` at `fixed`: values, and the band when there is one.
struct quantity_slice {
  std::vector<double> y, low, high;
};
[[nodiscard]] quantity_slice slice(const io::result_file& f, const quantity& q,
                                   const std::string& dim,
                                   const std::map<std::string, std::size_t>& fixed);

// A value for a label or a file stem: 4 significant digits.
[[nodiscard]] std::string short_number(double x);
// A file stem from free text: letters, digits, '.', '-', '_'; others -> '_'.
[[nodiscard]] std::string stem_text(const std::string& s);

}  // namespace stickslip::study::detail
