// What the writers share: the names of parameters and axes, the shape check,
// and the writers' "write the temporary, do not rename yet" halves that
// write_all composes. The statistics they write, with names, units and
// descriptions, come from one table in the core (statistics_schema.hpp), and
// the estimates derived from them from another (estimates.hpp), so
// results.nc, summary.json and summary.csv name things the same way.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "stickslip/io/atomic_file.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/io/metadata.hpp"
#include "stickslip/estimates.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/statistics_schema.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::io::detail {

// The canonical symbols of the swept axes, in the spec's axis order.
[[nodiscard]] std::vector<std::string> swept_symbols(const sweep_spec& s);
// Whether the recorded parameter `symbol` defines the model `p`: mu only when
// the friction is that one coefficient (mu_s = mu_k = mu), V only on the
// default belt (+V, -V), lambda only with Poisson switching (no rates and no
// generator of the belt's own); every other recorded parameter always.
[[nodiscard]] bool defines_model(const model_parameters& p, std::string_view symbol);
// Whether `rs` holds every point of its grid. A run streamed window by window
// (streamed_outputs.hpp) hands the writers slabs of its points, and a header
// without any, whose spec is still the whole grid's.
[[nodiscard]] inline bool holds_every_point(const result_set& rs) {
  return rs.points.size() == point_count(rs.spec);
}
// `f(model)` for the model at each grid point of `rs`, in grid order: its
// points' parameters when it holds every point, else point_parameters of its
// spec (what the run computed them from). What the writers say of the whole
// grid (meaningless_parameters, varying_parameters, same_belt_everywhere) is
// thus the same for a whole result set and for a slab of it.
template <class F>
void for_each_point_model(const result_set& rs, F&& f) {
  if (holds_every_point(rs)) {
    for (const auto& p : rs.points) f(p.parameters);
    return;
  }
  for (std::size_t i = 0, n = point_count(rs.spec); i < n; ++i) f(point_parameters(rs.spec, i));
}
// The recorded parameters that do not define the model at some grid point of
// `rs` and are not swept: they are written nowhere (no variable, attribute,
// JSON member or CSV column), since their value means nothing there (a "mu"
// of 5 in a mu_s sweep at mu_k = 4).
[[nodiscard]] std::vector<std::string> meaningless_parameters(const result_set& rs);
// The model of the first grid point as the engines resolve it (the paper's
// model in its paper form, point_parameters): where the parameters that are
// not swept are read from, so that "mu" of --mu-s 2 --mu-k 2 is 2, not the
// unused default 5 (for_each_point_model's first).
[[nodiscard]] model_parameters resolved_base(const result_set& rs);
// The recorded scalars that are not swept but whose resolved value differs
// between points: mu_s and mu_k that resolve to a swept mu. They have no one
// value for the grid (their variables over the grid hold them): no global
// attribute, null in summary.json's base (a new user found mu_s = 0.5, the
// first point's, in a sweep over mu = 0.5 .. 7).
[[nodiscard]] std::vector<std::string> varying_parameters(const result_set& rs);
// Whether the belt's levels v_i and its generator Q are one for the whole
// result set: not when they differ between points (a swept lambda, V, vI or
// rI) or follow a law drawn per realization. The outputs' one belt of the
// grid (summary.json's parameters.base, results.nc's belt_levels and
// belt_generator attributes) gives only what is one (the first point's,
// resolved); what varies is read per point from the swept coordinates.
struct belt_sameness {
  bool levels = true, generator = true;
};
[[nodiscard]] belt_sameness same_belt_everywhere(const result_set& rs);
// summary.json's "base": {...}, the model of the result set (resolved_base,
// same_belt_everywhere, meaningless_parameters left out), null for each
// symbol of `without_value` (swept, or set by a law) and of
// varying_parameters: a sweep's parameters.base, a sensitivity study's base.
class json_emitter;
void emit_base(json_emitter& j, const result_set& rs, std::vector<std::string> without_value);
// The parameters every summary point carries: lambda and mu (swept or not,
// unless meaningless_parameters), then the other swept symbols in axis order.
[[nodiscard]] std::vector<std::string> point_parameter_symbols(const result_set& rs);
// A parameter's NetCDF variable name: its long alias with '_' ("switch_rate").
[[nodiscard]] std::string parameter_variable_name(const std::string& symbol);

// The most values one chunk of a compressed results.nc variable holds, and
// so one write call of put_rows (4 MiB of doubles, netCDF's default chunk
// size: with 1 MiB a 6,400-point grid's results.nc was 13 % larger). Tests
// lower it to exercise chunks of a few rows, of one row and of part of a row.
inline std::size_t netcdf_chunk_values = std::size_t{1} << 19;

// The chunk shape of a variable of `shape` (row-major) holding at most
// `target` values: [1, ..., 1, c, n_{j+1}, ..., n_last], the trailing
// dimensions whole and c = min(n_j, target / (n_{j+1} ... n_last)) for the
// outermost j where that is >= 1 (the last dimension alone is cut to
// `target`). A chunk is thus a contiguous row-major run of whole sub-boxes,
// and writing it whole (row_runs) never touches another chunk.
[[nodiscard]] std::vector<std::size_t> chunk_shape(const std::vector<std::size_t>& shape,
                                                   std::size_t target);

// While results.nc is written slab by slab (netcdf_stream, around each
// slab's writes, on its thread): `rows`, those of the first grid axis each
// slab but the last holds (0: chunks as for a file written whole), and
// `defining`, whether this slab defines the file (the first: dimensions,
// variables, their attributes and coordinates) or only writes its rows into
// what the first defined. Outside a stream: {0, true}.
struct netcdf_slab_state {
  std::size_t rows = 0;
  bool defining = true;
};
inline thread_local netcdf_slab_state netcdf_slab;

// The chunk shape results.nc uses for a variable of `shape`: chunk_shape at
// netcdf_chunk_values; while streamed, a chunk's extent in the first axis is
// cut to a divisor of netcdf_slab.rows, so that no chunk spans two slabs
// (each slab's writes cover whole chunks, each compressed once: a chunk
// written in parts is read back, decompressed and compressed again).
[[nodiscard]] std::vector<std::size_t> netcdf_chunks(const std::vector<std::size_t>& shape);

// One write of a chunk-aligned hyperslab over the grid dimensions: points
// [first, first + points) in row-major order, at `start` with `count`.
struct row_run {
  std::size_t first = 0, points = 0;
  std::vector<std::size_t> start, count;
};
// The runs that tile a grid of `grid` (row-major) in order, each covering
// the grid extent of one chunk of shape `chunk` (the grid part of a
// chunk_shape): a chunk that is partial in dimension j is a run of
// chunk[j] (fewer at the edge) indices of j with the inner dimensions whole.
[[nodiscard]] std::vector<row_run> row_runs(const std::vector<std::size_t>& grid,
                                            const std::vector<std::size_t>& chunk);

// Throws stickslip::error (internal) unless rs has one point per grid point.
void check_shape(const result_set& rs);
// The same for a slab of a streamed run (streamed_outputs): its spec the
// whole grid's, its points those of the grid from point `first` on, whole
// rows of the first axis.
void check_slab(const result_set& slab, std::size_t first);

// Write `path.tmp` completely (flushed, fsynced, closed) without renaming.
// On failure the temporary is removed and io_error(path, ...) thrown.
void write_netcdf_temporary(const result_set& rs, const run_metadata& meta,
                            const std::string& path);
// The same for any NetCDF file `fill` writes to the temporary path it is
// given: NetCDF and other failures become io_error(path, ...).
void write_netcdf_temporary_with(const std::string& path,
                                 const std::function<void(const std::string&)>& fill);
void fill_summary_json(text_sink& out, const result_set& rs, const run_metadata& meta,
                       const output_options& options);
void fill_summary_csv(text_sink& out, const result_set& rs);
// Renames the temporaries of `paths` (each written in full) into place in
// `dir`, then removes the outputs of an earlier run there that they do not
// replace (and an earlier study's figure, beside its sensitivity.nc):
// returns those. On a failed rename, removes what it renamed, the
// temporaries and `created`.
std::vector<std::string> commit_outputs(const std::string& dir, const std::vector<std::string>& paths,
                                        const std::vector<created_directory>& created);
// summary.csv's header (constructed) and rows (print), for a whole result
// set (fill_summary_csv) or slab by slab (streamed_outputs.cpp: the header
// of a run's header, no derived estimates).
struct csv_estimate_column;
class summary_csv_rows {
 public:
  summary_csv_rows(text_sink& out, const result_set& rs, const std::vector<estimate_source>& sources);
  summary_csv_rows(const summary_csv_rows&) = delete;
  summary_csv_rows& operator=(const summary_csv_rows&) = delete;
  ~summary_csv_rows();
  void print(const result_set& rs, const std::vector<estimate_source>& sources);
  void print(const result_set& slab);

 private:
  text_sink& out_;
  std::vector<std::string> symbols_;
  std::vector<csv_estimate_column> estimates_;
};
// summary.json, begun with a run's header (a result set without points:
// its spec, threads and ranks), given each slab of points in grid order,
// ended with the header again (its elapsed time).
class json_emitter;
class summary_json_stream {
 public:
  summary_json_stream(text_sink& out, const result_set& header, const run_metadata& meta,
                      const output_options& options);
  summary_json_stream(const summary_json_stream&) = delete;
  summary_json_stream& operator=(const summary_json_stream&) = delete;
  ~summary_json_stream();
  void slab(const result_set& slab);
  void end(const result_set& header);

 private:
  text_sink& out_;
  output_options options_;
  std::vector<std::string> symbols_;  // point_parameter_symbols of the grid
  std::unique_ptr<json_emitter> j_;
};
// results.nc written slab by slab: the first slab defines the file (its
// dimensions from the header's spec, the trace length from the slab) and
// every slab writes its rows; finish adds the global attributes (the header
// with its elapsed time), closes and fsyncs the temporary without renaming.
// Destroyed unfinished, it removes the temporary.
class netcdf_stream {
 public:
  explicit netcdf_stream(std::string path);
  netcdf_stream(const netcdf_stream&) = delete;
  netcdf_stream& operator=(const netcdf_stream&) = delete;
  ~netcdf_stream();
  void slab(const result_set& header, const result_set& slab);
  void finish(const result_set& header, const run_metadata& meta);

 private:
  struct file;
  std::string path_;
  std::unique_ptr<file> file_;
  bool finished_ = false;
};
void fill_records_csv(text_sink& out, const result_set& rs);
// A sensitivity study's outputs (writer_sensitivity.cpp); `meta` adds the
// "run" object of summary.json.
void write_sensitivity_temporary(const result_set& rs, const run_metadata& meta,
                                 const std::string& path);
void fill_sensitivity_json(text_sink& out, const result_set& rs, const run_metadata* meta);

}  // namespace stickslip::io::detail
