// Writers of a sweep's result set. Each writes to `path` atomically: it writes
// `path.tmp`, flushes, and renames, so a failed run leaves no partial file.
// They throw stickslip::error (exit_code::io_failure) naming the path.
#pragma once
#include <string>

#include "stickslip/io/metadata.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::io {

// results.nc: NetCDF-4, one dimension per swept axis (coordinate variables
// named after the parameter symbols), statistics as variables with units and
// long_name, histograms with a bin dimension, convergence traces, and global
// attributes holding run_metadata and the seed.
void write_netcdf(const result_set& rs, const run_metadata& meta, const std::string& path);

// summary.json: {"parameters": {...}, "points": [...], "elapsed_seconds": ...}
void write_summary_json(const result_set& rs, const run_metadata& meta, const std::string& path);

// summary.csv: one row per grid point.
void write_summary_csv(const result_set& rs, const std::string& path);

// records.csv: raw per-realization records (only when spec.keep_records).
void write_records_csv(const result_set& rs, const std::string& path);

// All of the above into directory `dir` (created if missing). Writes every
// file to a temporary name first and renames them only when all succeeded.
void write_all(const result_set& rs, const run_metadata& meta, const std::string& dir);

}  // namespace stickslip::io
