// results.nc: NetCDF-4 (HDF5) file, self-describing (CF-1.8 conventions).
// Dimensions: one per swept axis, in the spec's axis order and named after
// the parameter symbol (or `point` of length 1 when nothing is swept), then
// `bin` (histogram bins), `nv` (the 2 ends of a bin) and `trace` (convergence
// trace entries).
// Point i of the result set sits at rs.points[i].index on the grid dims,
// which is row-major order of the dims (first axis outermost).
// The statistics come from the schema (statistics_schema.hpp), the derived
// estimates from the estimate table (estimates.hpp). long_name
// values stay within the 30 characters xarray puts on one line of a plot
// label (with " [units]"); the full definition is in `description`.
// The groups of variables are written by results_nc_*.cpp (results_nc.hpp).
#include <netcdf>

#include <fmt/format.h>

#include <algorithm>
#include <functional>

#include "../netcdf_file.hpp"
#include "results_nc.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/statistics_groups.hpp"
#include "stickslip/statistics_schema.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/uncertainty/uncertain_draws.hpp"
#include "writers_detail.hpp"

namespace stickslip::io {
namespace detail {
namespace {

using namespace results_nc;

layout_info define_dimensions(nc::NcFile& f, const result_set& rs) {
  layout_info l;
  const auto& spec = rs.spec;
  if (spec.axes.empty()) {
    l.grid.push_back(f.addDim("point", 1));
  } else {
    for (const auto& ax : spec.axes) {
      const std::string sym = canonical_symbol(ax.name);
      const auto& info = info_for(sym);
      auto dim = f.addDim(sym, ax.values.size());
      l.grid.push_back(dim);
      auto v = f.addVar(sym, nc::ncDouble, dim);
      describe(v, info.units, parameter_long_name(info, sym),
               fmt::format("swept model parameter {}: {}", sym, info.description));
      v.putVar(ax.values.data());
    }
  }
  l.bins = std::max<std::size_t>(1, spec.histograms.bins);
  l.bin = f.addDim("bin", l.bins);
  l.bounds = f.addDim("nv", 2);
  for (const auto& p : rs.points) l.trace_length = std::max(l.trace_length, p.stats.convergence.size());
  l.trace_length = std::max<std::size_t>(1, l.trace_length);
  l.trace = f.addDim("trace", l.trace_length);
  // The belt levels: their number cannot be swept, so one dimension fits all
  // points; the level values (which can) are belt_level_velocity over the grid.
  l.levels = rs.spec.base.levels().size();
  l.level = f.addDim("belt_level", l.levels);
  auto level_index = f.addVar("belt_level", nc::ncInt, l.level);
  describe(level_index, "1", "belt level number", "number j = 1..n of the belt level v_j");
  level_index.putVar(level_numbers(l.levels).data());
  // The second bin dimension of the joint histograms (the same length as bin).
  if (!joint_histograms().empty()) l.bin_y = f.addDim("bin_y", l.bins);
  l.meaningless = meaningless_parameters(rs);
  return l;
}

void write_parameters(nc::NcFile& f, const layout_info& l, const result_set& rs) {
  // Every recorded scalar that defines the model (meaningless_parameters),
  // then the swept belt levels and rates (vI, rI).
  // (l.meaningless: one pass over the grid's models, not one per slab.)
  const auto& omitted = l.meaningless;
  std::vector<std::string> symbols;
  for (const char* sym : recorded_parameter_names)
    if (std::find(omitted.begin(), omitted.end(), sym) == omitted.end()) symbols.emplace_back(sym);
  for (const auto& sym : swept_symbols(rs.spec))
    if (std::find(symbols.begin(), symbols.end(), sym) == symbols.end()) symbols.push_back(sym);
  // A parameter set by a law has no one value: the variable holds its law's
  // median (what the point's ETA and derived scales use) and says so.
  const auto by_laws = symbols_set_by_laws(rs.spec.uncertain);
  for (const auto& sym : symbols) {
    const auto& info = info_for(sym);
    const bool uncertain = std::find(by_laws.begin(), by_laws.end(), sym) != by_laws.end();
    auto v = add_double(f, parameter_variable_name(sym), l.grid, info.units,
                        parameter_long_name(info, sym),
                        uncertain ? fmt::format("the median of the law of model parameter {} "
                                                "(uncertain: each realization draws its own "
                                                "value; see the uncertain_parameters attribute): "
                                                "{}",
                                                sym, info.description)
                                  : fmt::format("model parameter {} at each grid point: {}", sym,
                                                info.description),
                        false);
    if (defining()) {
      v.putAtt("symbol", sym);
      if (uncertain) v.putAtt("value_is", "median of the law");
    }
    put_grid<double>(v, rs, [&](const point_result& p) { return parameter_value(p.parameters, sym); });
  }
  auto a = add_double(f, "band_half_width", l.grid, "m", "stick band half-width a",
                      "a = mu_s m g / k: the mass can stick only while |x + c v / k| <= a "
                      "(|x| <= a without damping)",
                      false);
  put_grid<double>(a, rs, [](const point_result& p) { return p.parameters.band_half_width(); });
  auto w = add_double(f, "natural_frequency", l.grid, "rad/s", "natural frequency",
                      "omega = sqrt(k / m)", false);
  put_grid<double>(w, rs, [](const point_result& p) { return p.parameters.natural_frequency(); });
  auto d = add_double(f, "max_stick_duration", l.grid, "s", "longest stick d_max",
                      "d_max = 2 a / V: a stick that crosses the whole band (Markov belt: 2 a / "
                      "smallest nonzero |v_i|, at least 5 / rate of leaving a level v = 0)",
                      false);
  put_grid<double>(d, rs, [](const point_result& p) { return p.parameters.max_stick_duration(); });
}

void write_global_attributes(nc::NcFile& f, const result_set& rs, const run_metadata& meta) {
  const auto& s = rs.spec;
  f.putAtt("title",
           "stickslip parametric sweep: statistics of a dry-friction oscillator on a belt "
           "whose direction switches at Poisson times");
  f.putAtt("Conventions", "CF-1.8");
  f.putAtt("source", fmt::format("stickslip {} (git {})", meta.version, meta.git_revision));
  f.putAtt("history", fmt::format("{}: {}", meta.created_utc, meta.command_line));
  // What this file holds: the selected statistics only (a new user read
  // X, W_f and W_c here in a default sweep that does not write them).
  std::string symbols, binned;
  for (const auto& q : quantities()) {
    if (!selects(s.statistics, q)) continue;
    symbols += fmt::format("{}{}", symbols.empty() ? "" : ", ", q.symbol);
    if (q.density && !s.means_only) binned += fmt::format("{}{}", binned.empty() ? "" : ", ", q.symbol);
  }
  for (const auto& l : level_quantities())  // the belt level fractions P_j, over belt_level
    if (selects(s.statistics, l)) symbols += fmt::format("{}{} (per belt level)", symbols.empty() ? "" : ", ", l.symbol);
  std::string held = symbols.empty() ? std::string() : "mean, std and 95% CI of " + symbols;
  if (s.statistics.survival)
    held += (held.empty() ? "" : "; ") +
            std::string("Kaplan-Meier survival of stick and slip durations over their time grids");
  f.putAtt("comment",
           fmt::format("Exact event-driven simulation. Per grid point: "
                       "{}; {}; convergence traces over dimension trace. "
                       "Parameters that are not swept are global attributes named by their "
                       "symbol (unless they follow a swept one: mu_s and mu_k of a swept mu); "
                       "every parameter is also a variable over the grid. Only the "
                       "parameters that define the model are written (mu only when mu_s = "
                       "mu_k = mu, V only on a (+V, -V) belt, lambda only with Poisson "
                       "switching), and only the derivatives that apply to it.",
                       held,
                       binned.empty() ? std::string("no histograms")
                                      : fmt::format("histograms (densities) of {} over dimension "
                                                    "bin, with bin coordinates and bounds",
                                                    binned)));
  f.putAtt("version", meta.version);
  f.putAtt("git_revision", meta.git_revision);
  f.putAtt("command_line", meta.command_line);
  f.putAtt("created_utc", meta.created_utc);
  f.putAtt("resolved_config", meta.resolved_config);
  f.putAtt("seed", nc::ncUint64, static_cast<unsigned long long>(s.seed));
  f.putAtt("realizations", nc::ncUint64, static_cast<unsigned long long>(s.realizations));
  f.putAtt("block_size", nc::ncUint64, static_cast<unsigned long long>(s.block_size));
  f.putAtt("max_events", nc::ncInt64, static_cast<long long>(s.max_events));
  f.putAtt("keep_records", nc::ncInt, s.keep_records ? 1 : 0);
  f.putAtt("common_random_numbers", nc::ncInt, s.common_random_numbers ? 1 : 0);
  if (!s.target_statistic.empty()) {
    f.putAtt("target_ci_statistic", s.target_statistic);
    f.putAtt("target_ci_halfwidth", nc::ncDouble, s.target_halfwidth);
    f.putAtt("min_realizations", nc::ncUint64, static_cast<unsigned long long>(s.min_realizations));
  }
  // Grid points that did not reach the precision target within the cap
  // (unmet_target_note): `sweep`'s warning, kept with the results, where a
  // --resume that finds them finished reads it to say it again.
  if (const auto note = unmet_target_note(rs); !note.empty()) f.putAtt("warning", note);
  f.putAtt("statistics", to_string(s.statistics));
  // Only with a burn-in: without one the file is what it was before.
  if (s.burn_in != 0.0) f.putAtt("burn_in", nc::ncDouble, s.burn_in);
  if (s.statistics.survival) {
    f.putAtt("survival_bins", nc::ncUint64, static_cast<unsigned long long>(s.survival.bins));
    f.putAtt("survival_stick_duration_max", nc::ncDouble, s.survival.stick_duration_max);
    f.putAtt("survival_slip_duration_max", nc::ncDouble, s.survival.slip_duration_max);
  }
  f.putAtt("histogram_bins", nc::ncUint64, static_cast<unsigned long long>(s.histograms.bins));
  f.putAtt("histogram_stick_duration_max", nc::ncDouble, s.histograms.stick_duration_max);
  f.putAtt("histogram_slip_duration_max", nc::ncDouble, s.histograms.slip_duration_max);
  f.putAtt("initial_position_min", nc::ncDouble, s.initial.position_min);
  f.putAtt("initial_position_max", nc::ncDouble, s.initial.position_max);
  f.putAtt("initial_velocity_min", nc::ncDouble, s.initial.velocity_min);
  f.putAtt("initial_velocity_max", nc::ncDouble, s.initial.velocity_max);
  f.putAtt("initial_belt_start", belt_start_text(s.initial.belt_start));
  std::string swept;
  for (const auto& sym : swept_symbols(s)) swept += (swept.empty() ? "" : " ") + sym;
  f.putAtt("swept_parameters", swept);
  // Uncertain parameters: drawn per realization, each from the law in the
  // attribute <symbol>_law; their grid variables hold the laws' medians.
  std::string uncertain;
  for (const auto& u : s.uncertain) {
    uncertain += (uncertain.empty() ? "" : " ") + u.symbol;
    f.putAtt(u.symbol + "_law", to_string(u.law));
  }
  if (!uncertain.empty()) f.putAtt("uncertain_parameters", uncertain);
  auto sw = swept_symbols(s);
  for (auto& sym : varying_parameters(rs)) sw.push_back(std::move(sym));  // no one value either
  const auto omitted = meaningless_parameters(rs);
  const auto by_laws = symbols_set_by_laws(s.uncertain);
  const auto is_uncertain = [&](const char* sym) {
    return std::find(by_laws.begin(), by_laws.end(), sym) != by_laws.end();
  };
  for (const char* sym : recorded_parameter_names)
    if (std::find(sw.begin(), sw.end(), sym) == sw.end() && !is_uncertain(sym) &&
        std::find(omitted.begin(), omitted.end(), sym) == omitted.end())
      f.putAtt(sym, nc::ncDouble, parameter_value(resolved_base(rs), sym));
  // The resolved belt of the grid, when it is one for every point: levels
  // v_i [m/s] and the generator Q, row-major [1/s]. Left out when it varies
  // (a swept lambda, V, vI or rI is a coordinate, with its variable over the
  // grid; a law's parameter is named in uncertain_parameters).
  const auto belt = same_belt_everywhere(rs);
  const auto levels = resolved_base(rs).levels();
  const auto q = resolved_base(rs).generator();
  if (belt.levels) f.putAtt("belt_levels", nc::ncDouble, levels.size(), levels.data());
  if (belt.generator) f.putAtt("belt_generator", nc::ncDouble, q.size(), q.data());
  f.putAtt("threads", nc::ncInt, static_cast<int>(rs.threads));
  f.putAtt("ranks", nc::ncInt, static_cast<int>(rs.ranks));
  f.putAtt("elapsed_seconds", nc::ncDouble, rs.elapsed_seconds);
}

// Every variable over the grid, for the points of `rs` (all, or a slab's).
void write_variables(nc::NcFile& f, const layout_info& l, const result_set& rs) {
  write_parameters(f, l, rs);
  write_statistics(f, l, rs);
  write_counts(f, l, rs);
  write_estimates(f, l, rs);
  write_histograms(f, l, rs);
  write_level_statistics(f, l, rs);
  write_joint_histograms(f, l, rs);
  write_survival(f, l, rs);
  write_observed(f, l, rs);
  write_convergence(f, l, rs);
}

void write_netcdf_file(const result_set& rs, const run_metadata& meta, const std::string& file) {
  nc_file f(file, nc::NcFile::replace, nc::NcFile::nc4);
  write_global_attributes(f, rs, meta);
  const auto l = define_dimensions(f, rs);
  write_variables(f, l, rs);
  f.close();
}

// NetCDF and other failures as io_error(path, ...), as write_netcdf_temporary_with.
template <class F>
void reporting_as(const std::string& path, F&& f) {
  try {
    f();
  } catch (const nc::exceptions::NcException& e) {
    throw io_error(path, netcdf_message(e) + write_limit_hint(path));
  } catch (const stickslip::error&) {
    throw;
  } catch (const std::exception& e) {
    throw io_error(path, e.what());
  }
}

}  // namespace

void write_netcdf_temporary(const result_set& rs, const run_metadata& meta,
                            const std::string& path) {
  check_shape(rs);
  write_netcdf_temporary_with(path, [&](const std::string& tmp) { write_netcdf_file(rs, meta, tmp); });
}

struct netcdf_stream::file {
  explicit file(const std::string& tmp) : f(tmp, nc::NcFile::replace, nc::NcFile::nc4) {}
  nc_file f;
  layout_info l;
  std::size_t rows = 0;  // of the first axis in each slab but the last
};

netcdf_stream::netcdf_stream(std::string path) : path_(std::move(path)) {}

netcdf_stream::~netcdf_stream() {
  file_.reset();  // closes the file quietly (nc_file)
  if (!finished_) remove_file_quietly(temporary_path(path_));
}

void netcdf_stream::slab(const result_set& header, const result_set& slab) {
  reporting_as(path_, [&] {
    std::size_t row_points = 1;  // of one row of the first axis
    for (std::size_t a = 1; a < header.spec.axes.size(); ++a)
      row_points *= header.spec.axes[a].values.size();
    const bool first = !file_;
    if (first) {
      file_ = std::make_unique<file>(temporary_path(path_));
      // One slab of the whole grid: the chunks of a file written whole.
      const std::size_t rows = slab.points.size() / row_points;
      file_->rows = rows == header.spec.axes.front().values.size() ? 0 : rows;
    }
    auto& w = *file_;
    // For this thread's writes: every chunk within one slab (netcdf_chunks),
    // and the variables defined by the first slab only.
    struct slab_state {
      explicit slab_state(netcdf_slab_state s) { netcdf_slab = s; }
      ~slab_state() { netcdf_slab = {}; }
    } const state({w.rows, first});
    if (first) w.l = define_dimensions(w.f, slab);
    std::size_t trace = 0;
    for (const auto& p : slab.points) trace = std::max(trace, p.stats.convergence.size());
    if (trace > w.l.trace_length)
      throw error(exit_code::internal,
                  fmt::format("a streamed slab's convergence trace of {} entries is longer than "
                              "the first slab's {}",
                              trace, w.l.trace_length));
    write_variables(w.f, w.l, slab);
  });
}

void netcdf_stream::finish(const result_set& header, const run_metadata& meta) {
  reporting_as(path_, [&] {
    if (!file_) throw error(exit_code::internal, "results.nc streamed without any slab");
    write_global_attributes(file_->f, header, meta);
    file_->f.close();
    file_.reset();
    sync_file(temporary_path(path_), path_);
  });
  finished_ = true;
}

void write_netcdf_temporary_with(const std::string& path,
                                 const std::function<void(const std::string&)>& fill) {
  const std::string tmp = temporary_path(path);
  try {
    reporting_as(path, [&] {
      fill(tmp);
      sync_file(tmp, path);
    });
  } catch (...) {
    remove_file_quietly(tmp);
    throw;
  }
}

}  // namespace detail

void write_netcdf(const result_set& rs, const run_metadata& meta, const std::string& path) {
  detail::write_netcdf_temporary(rs, meta, path);
  try {
    detail::commit_rename(detail::temporary_path(path), path);
  } catch (...) {
    detail::remove_file_quietly(detail::temporary_path(path));
    throw;
  }
}

}  // namespace stickslip::io

