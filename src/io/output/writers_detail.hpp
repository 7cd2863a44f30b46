// What the writers share: the names of parameters and axes, the shape check,
// and the writers' "write the temporary, do not rename yet" halves that
// write_all composes. The statistics they write, with names, units and
// descriptions, come from one table in the core (statistics_schema.hpp), so
// results.nc, summary.json and summary.csv name things the same way.
#pragma once
#include <string>
#include <vector>

#include "stickslip/io/atomic_file.hpp"
#include "stickslip/io/metadata.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/statistics_schema.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::io::detail {

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
