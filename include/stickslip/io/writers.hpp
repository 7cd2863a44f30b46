// Writers of a sweep's result set. Each writes to `path` atomically: it writes
// `path.tmp`, flushes, fsyncs, and renames, so a failed run leaves no partial
// file. They throw stickslip::error (exit_code::io_failure) naming the path.
#pragma once
#include <string>
#include <vector>

#include "stickslip/io/metadata.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::io {

// What the outputs hold beyond the defaults. summary.json leaves out the
// joint histograms (the (D, X) counts: most of its bytes, 2.5 of 3.5 MB on
// the paper grid) unless asked; results.nc always has them.
struct output_options {
  bool json_joint_histograms = false;
};

// File names that write_all uses inside its directory.
inline constexpr const char* results_file = "results.nc";
inline constexpr const char* summary_json_file = "summary.json";
inline constexpr const char* summary_csv_file = "summary.csv";
inline constexpr const char* records_csv_file = "records.csv";
// A sensitivity study (uncertainty/sensitivity_design.hpp) writes
// sensitivity.nc and summary.json instead of the sweep's files.
inline constexpr const char* sensitivity_file = "sensitivity.nc";
// and its figure, sensitivity.{dat,gp,png,svg} (study/sensitivity_figure.hpp).
inline constexpr const char* sensitivity_figure_stem = "sensitivity";
inline constexpr const char* figure_extensions[] = {".dat", ".gp", ".png", ".svg"};

// results.nc: NetCDF-4, one dimension per swept axis (coordinate variables
// named after the parameter symbols), statistics as variables with units and
// long_name, histograms with a bin dimension, convergence traces, and global
// attributes holding run_metadata and the seed.
void write_netcdf(const result_set& rs, const run_metadata& meta, const std::string& path);

// summary.json: {"parameters": {...}, "points": [...], "elapsed_seconds": ...}
void write_summary_json(const result_set& rs, const run_metadata& meta, const std::string& path,
                        const output_options& options = {});

// The text of summary.json, and its "points" array exactly as it appears in
// the file. The points text depends only on the result set's statistics (no
// timestamps, no thread count), so identical result sets give identical bytes.
[[nodiscard]] std::string summary_json(const result_set& rs, const run_metadata& meta,
                                       const output_options& options = {});
[[nodiscard]] std::string summary_json_points(const result_set& rs,
                                              const output_options& options = {});

// summary.csv: one row per grid point.
void write_summary_csv(const result_set& rs, const std::string& path);
[[nodiscard]] std::string summary_csv(const result_set& rs);

// records.csv: raw per-realization records (only when spec.keep_records;
// throws stickslip::error with exit_code::invalid_input otherwise).
void write_records_csv(const result_set& rs, const std::string& path);

// What `sensitivity --format json` prints: the statistic, the realizations
// and samples, the laws, every input's indices of the mean response
// ("of": "mean", first and total order) and in the response ("of":
// "response", first order), each with its 95 % interval, and the shares.
// summary.json of a sensitivity study is this with a "run" object added.
[[nodiscard]] std::string sensitivity_json(const result_set& rs);

// All of the above into directory `dir` (created if missing; records.csv
// only when spec.keep_records; sensitivity.nc and summary.json for a
// sensitivity study). Writes every file to a temporary name first
// and renames them only when all succeeded. On failure nothing new is left in
// `dir` (and `dir` itself is removed again if this call created it).
// Once they are in place, it removes the outputs of an earlier run in `dir`
// that this one did not write (records.csv without records, a sweep's
// files under a study's): returns their paths, for the caller to name.
std::vector<std::string> write_all(const result_set& rs, const run_metadata& meta, const std::string& dir,
               const output_options& options = {});

}  // namespace stickslip::io
