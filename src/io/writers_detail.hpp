// What the writers share: the list of per-point statistics and histograms
// with their names, units and descriptions (one table, so results.nc,
// summary.json and summary.csv name things the same way), and the writers'
// "write the temporary, do not rename yet" halves that write_all composes.
#pragma once
#include <string>
#include <vector>

#include "atomic_file.hpp"
#include "stickslip/io/metadata.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::io::detail {

struct statistic_info {
  const char* short_name;  // summary.json / summary.csv: "R", "stick_duration", ...
  const char* name;        // results.nc prefix: "stick_fraction", "stick_duration", ...
  mean_variance point_statistics::*member;
  const char* units;
  const char* long_name;
  const char* description;
  const char* counted;  // what <name>_count counts
};
[[nodiscard]] const std::vector<statistic_info>& statistics_table();

struct histogram_info {
  const char* name;  // results.nc prefix: "<name>_density", ...
  histogram point_statistics::*member;
  const char* units;          // of the binned quantity
  const char* density_units;  // of the density
  const char* long_name;      // of the binned quantity
};
[[nodiscard]] const std::vector<histogram_info>& histograms_table();

// The canonical symbols of the swept axes, in the spec's axis order.
[[nodiscard]] std::vector<std::string> swept_symbols(const sweep_spec& s);
// The parameters every summary point carries: lambda and mu always (swept or
// not), then the other swept symbols in axis order.
[[nodiscard]] std::vector<std::string> point_parameter_symbols(const sweep_spec& s);
// A parameter's NetCDF variable name: its long alias with '_' ("switch_rate").
[[nodiscard]] std::string parameter_variable_name(const std::string& symbol);

// How many values results.nc's writer buffers per call for the (grid, bin)
// and (grid, trace) variables. Tests lower it to exercise the slab-wise and
// point-wise paths.
inline std::size_t netcdf_buffer_values = std::size_t{1} << 22;  // 32 MiB of doubles

// Throws stickslip::error (internal) unless rs has one point per grid point.
void check_shape(const result_set& rs);

// Write `path.tmp` completely (flushed, fsynced, closed) without renaming.
// On failure the temporary is removed and io_error(path, ...) thrown.
void write_netcdf_temporary(const result_set& rs, const run_metadata& meta,
                            const std::string& path);
void fill_summary_json(text_sink& out, const result_set& rs, const run_metadata& meta);
void fill_summary_csv(text_sink& out, const result_set& rs);
void fill_records_csv(text_sink& out, const result_set& rs);

}  // namespace stickslip::io::detail
