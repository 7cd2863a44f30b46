// Reads a finished output (results.nc, sensitivity.nc) generically: its
// dimensions, its variables with their `units`, `long_name`, `symbol` and
// `coordinates` attributes, and their values as doubles. Nothing here knows
// which statistics exist: a reader that wants "R" looks it up in the
// variables' names and symbols, so a statistic added to the schema is found
// without a change here.
#pragma once
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace stickslip::io {

struct result_dimension {
  std::string name;
  std::size_t size = 0;
};

struct result_variable {
  std::string name;
  std::vector<std::string> dims;  // outermost first
  std::string units, long_name, symbol, coordinates;  // "" when the attribute is absent
  bool text = false;              // a string variable (sensitivity.nc's `input`, `law`)
};

class result_file {
 public:
  // Opens `path` for reading. Throws stickslip::error (invalid_input) naming
  // the path when it is missing or not a NetCDF file.
  explicit result_file(const std::string& path);
  ~result_file();
  result_file(result_file&&) noexcept;
  result_file& operator=(result_file&&) noexcept;
  result_file(const result_file&) = delete;
  result_file& operator=(const result_file&) = delete;

  [[nodiscard]] const std::string& path() const noexcept { return path_; }
  [[nodiscard]] const std::vector<result_dimension>& dimensions() const noexcept { return dims_; }
  [[nodiscard]] const std::vector<result_variable>& variables() const noexcept { return vars_; }
  // nullptr when absent.
  [[nodiscard]] const result_dimension* dimension(const std::string& name) const noexcept;
  [[nodiscard]] const result_variable* variable(const std::string& name) const noexcept;

  // The values along a dimension: its coordinate variable (a 1-D numeric
  // variable of the same name) when there is one, else 0, 1, ..., n - 1.
  [[nodiscard]] std::vector<double> coordinate(const std::string& dim) const;
  // Every value of a numeric variable, row-major over its dims, as doubles
  // (integers converted; a _FillValue of NaN stays NaN).
  [[nodiscard]] std::vector<double> values(const std::string& var) const;
  // Every value of a string variable.
  [[nodiscard]] std::vector<std::string> strings(const std::string& var) const;
  // A global text attribute, "" when absent.
  [[nodiscard]] std::string attribute(const std::string& name) const;

 private:
  struct handle;
  std::string path_;
  std::unique_ptr<handle> nc_;
  std::vector<result_dimension> dims_;
  std::vector<result_variable> vars_;
};

}  // namespace stickslip::io
