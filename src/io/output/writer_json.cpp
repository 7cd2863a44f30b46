// summary.json: the resolved configuration, one inline object per grid point,
// and the elapsed time. Layout (points one per line, so files diff well):
// {
//   "parameters": {...},
//   "points": [
//     {"lambda": 0.1, "mu": 5, "realizations": 200, "R": {"mean": ..., "std": ...,
//      "ci95": [lo, hi]}, ..., "no_stick": 0, "first_stick_censored": 3, ...},
//     ...
//   ],
//   "elapsed_seconds": 1.25
// }
#include <fmt/format.h>

#include <algorithm>
#include <string_view>
#include <vector>

#include "json_emitter.hpp"
#include "stickslip/estimates.hpp"
#include "stickslip/precision/crn_slopes.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/survival_estimate.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/uncertainty/uncertain_draws.hpp"
#include "observed_variables.hpp"
#include "writers_detail.hpp"

namespace stickslip::io {
namespace detail {
namespace {

void emit_interval(json_emitter& j, const estimate& e) {
  j.key("ci95");
  j.begin_array();
  j.value(e.value - e.ci95_half_width());
  j.value(e.value + e.ci95_half_width());
  j.end_array();
}

void emit_statistic(json_emitter& j, const mean_variance& mv) {
  j.begin_object();
  j.member("mean", mv.mean());
  j.member("std", mv.std_dev());
  emit_interval(j, mean_estimate(mv));
  j.end_object();
}

// One estimate inside the caller's object: its value (the row's
// value_member: "value", or "mean" for a control-variate mean),
// "std_error", "ci95" and the row's extra member.
void emit_estimate(json_emitter& j, const estimate_info& row, const estimate_value& v) {
  j.member(row.value_member, v.value.value);
  j.member("std_error", v.value.std_error);
  emit_interval(j, v.value);
  switch (row.extra) {
    case estimate_extra::none: break;
    case estimate_extra::variance_reduction:
      j.member(extra_name(row.extra), v.variance_reduction);
      break;
    case estimate_extra::pairs: j.member(extra_name(row.extra), v.pairs); break;
  }
}

// The estimates of one quantity by the row's index: one object (no index),
// an object per belt rate ({"r1": {...}, "r2": {...}}) or a list of
// generator entries, levels numbered from 1 as in --belt-start ([{"from":
// 1, "to": 2, ...}, ...]); only those that exist at the point.
void emit_quantity_estimates(json_emitter& j, const estimate_info& row, const estimate_source& src,
                             const quantity_info& q) {
  const auto indices = estimate_indices(row, src.spec);
  switch (row.index) {
    case estimate_index::axis: break;  // by axis first (emit_estimates)
    case estimate_index::none:
      if (const auto v = row.at(src, q, indices.front())) {
        j.key(q.summary_name);
        j.begin_object();
        emit_estimate(j, row, *v);
        j.end_object();
      }
      break;
    case estimate_index::belt_rate:
      j.key(q.summary_name);
      j.begin_object();
      for (const auto i : indices)
        if (const auto v = row.at(src, q, i)) {
          j.key(estimate_index_name(row, src.spec, i));
          j.begin_object();
          emit_estimate(j, row, *v);
          j.end_object();
        }
      j.end_object();
      break;
    case estimate_index::generator_entry: {
      const std::size_t n = src.spec.base.levels().size();
      j.key(q.summary_name);
      j.begin_array();
      for (const auto ij : indices)
        if (const auto v = row.at(src, q, ij)) {
          j.begin_object();
          j.member("from", static_cast<std::uint64_t>(ij / n + 1));
          j.member("to", static_cast<std::uint64_t>(ij % n + 1));
          emit_estimate(j, row, *v);
          j.end_object();
        }
      j.end_array();
      break;
    }
  }
}

// The estimate table (estimates.hpp): per row that applies at the point and
// whose group is selected, its key holding the estimates of the selected
// quantities that have it; the CRN slopes by axis first ({"lambda": {"R":
// {...}}}).
void emit_estimates(json_emitter& j, const estimate_source& src, const statistics_selection& sel) {
  for (const auto& row : estimate_kinds()) {
    if (!(sel.*row.group) || !row.applies(src)) continue;
    // A row of one statistic only (R's causal slope) has no key without it,
    // as before the table; the others keep theirs, empty if need be.
    std::size_t having = 0, selected = 0;
    for (const auto& q : quantities())
      if (row.has(q)) ++having, selected += selects(sel, row, q) ? 1 : 0;
    if (having == 1 && selected == 0) continue;
    j.key(row.name);
    j.begin_object();
    if (row.index == estimate_index::axis) {
      for (const auto k : estimate_indices(row, src.spec)) {
        j.key(estimate_index_name(row, src.spec, k));
        j.begin_object();
        for (const auto& q : quantities())
          if (selects(sel, row, q))
            if (const auto v = row.at(src, q, k)) {
              j.key(q.summary_name);
              j.begin_object();
              emit_estimate(j, row, *v);
              j.end_object();
            }
        j.end_object();
      }
    } else {
      for (const auto& q : quantities())
        if (selects(sel, row, q)) emit_quantity_estimates(j, row, src, q);
    }
    j.end_object();
  }
}

// The survival group: results.nc's variables of each law at the edges of
// parameters.survival's duration coordinates.
void emit_survival(json_emitter& j, const point_statistics& s) {
  for (const auto& law : survival_laws()) {
    const auto k = kaplan_meier(s.*law.counts);
    const std::string name = law.name;
    for (const auto& col : survival_curve_columns) {
      j.key(name + col.suffix);
      j.begin_array();
      for (double v : k.*col.values) j.value(v);
      j.end_array();
    }
    j.key(name + "_at_risk");
    j.begin_array();
    for (auto n : k.at_risk) j.value(n);
    j.end_array();
    j.member(name + "_restricted_mean", k.restricted_mean);
  }
}

// The ensemble at the observe times: `time` and the stick probability with
// its standard error. The other variables over `time` (moments, level
// occupancy, quantiles: about 40 numbers per time and point, which made
// summary.json 16x larger on the paper grid with 101 times) are in
// results.nc only. The variables whose values are nested per time (over
// belt levels or quantile levels) would be written the same way.
bool in_summary_json(const observed_variable& v) {
  return v.name == "stick_probability" || v.name == "stick_probability_std_error";
}
void emit_observed(json_emitter& j, const time_statistics& s) {
  j.key("observed");
  j.begin_object(layout::multi_line);
  j.key("time");
  j.begin_array();
  for (double t : s.times()) j.value(t);
  j.end_array();
  for (const auto& v : observed_variables()) {
    if (!in_summary_json(v)) continue;
    const std::size_t width = v.width(s.levels());
    const auto values = observed_values(v, s);
    j.key(v.name);
    j.begin_array();
    for (std::size_t t = 0; t < s.times().size(); ++t) {
      if (v.shape == observed_shape::one) {
        j.value(values[t]);
        continue;
      }
      j.begin_array();
      for (std::size_t i = 0; i < width; ++i) j.value(values[t * width + i]);
      j.end_array();
    }
    j.end_array();
  }
  j.end_object();
}

// The point's parameters and realizations, every quantity of the schema,
// the counters that belong to no group, the sample counts of the quantities
// not sampled once per realization ("samples"), then each group of counters
// ("events") as an object, the derivative estimates and the joint histograms.
void emit_point(json_emitter& j, const std::vector<std::string>& symbols,
                const estimate_source& src, const output_options& options) {
  const auto& spec = src.spec;
  const auto& p = src.point;
  const auto& s = p.stats;
  j.begin_object();
  for (const auto& sym : symbols)
    j.member(sym, parameter_value(p.parameters, sym));
  j.member("realizations", s.realizations);
  const auto& sel = spec.statistics;  // the selected statistics only
  for (const auto& q : quantities()) {
    if (!selects(sel, q)) continue;
    j.key(q.summary_name);
    emit_statistic(j, s.*q.moments);
  }
  for (const auto& q : level_quantities()) {  // one object per belt level
    if (!selects(sel, q)) continue;
    j.key(q.summary_name);
    j.begin_array();
    for (const auto& m : s.*q.moments) emit_statistic(j, m);
    j.end_array();
  }
  // Extras after the required keys.
  for (const auto& c : counters())
    if (!c.group) j.member(c.summary_name, c.value(s));
  j.key("samples");  // how many values entered the pooled statistics
  j.begin_object();
  for (const auto& q : quantities())
    if (q.sampled != sampling::per_realization && selects(sel, q))
      j.member(q.summary_name, (s.*q.moments).count());
  j.end_object();
  std::vector<std::string_view> groups;
  for (const auto& c : counters())
    if (c.group && std::find(groups.begin(), groups.end(), c.group) == groups.end())
      groups.emplace_back(c.group);
  for (const auto group : groups) {
    j.key(group);
    j.begin_object();
    for (const auto& c : counters())
      if (c.group && group == c.group) j.member(c.summary_name, c.value(s));
    j.end_object();
  }
  emit_estimates(j, src, sel);
  if (spec.statistics.survival) emit_survival(j, s);
  if (!spec.observe_times.empty()) emit_observed(j, s.observed);
  // Joint histograms, when asked: counts[i][k] of x bin i and y bin k (in
  // range), and the samples outside either range.
  for (const auto& jh : joint_histograms()) {
    if (!options.json_joint_histograms || !selects_joint_histograms(sel) || spec.means_only) break;
    const auto& h = s.*jh.counts;
    j.key(jh.summary_name);
    j.begin_array();
    for (std::size_t a = 0; a < h.x_binning().bins(); ++a) {
      j.begin_array();
      for (std::size_t b = 0; b < h.y_binning().bins(); ++b) j.value(h.count(a, b));
      j.end_array();
    }
    j.end_array();
    j.member(std::string(jh.name) + "_outside", h.outside());
  }
  j.end_object();
}

// The points of `rs` (whole, or a slab of a streamed run) as elements of
// the "points" array, each with the parameters `symbols`
// (point_parameter_symbols of the whole grid).
void emit_points(json_emitter& j, const result_set& rs, const std::vector<std::string>& symbols,
                 const output_options& options) {
  const auto slopes = precision::crn_slopes(rs);  // empty without CRN and records
  for (const auto& src : estimate_sources(rs, slopes)) emit_point(j, symbols, src, options);
}

void emit_parameters(json_emitter& j, const result_set& rs, const run_metadata& meta,
                     const output_options& options) {
  const auto& s = rs.spec;
  j.begin_object(layout::multi_line);
  // A swept parameter has no single value: null in "base", named in "swept";
  // nor has one set by a law: null, named in "uncertain_parameters".
  const auto swept = swept_symbols(s);
  auto without_value = swept;
  for (auto& sym : symbols_set_by_laws(s.uncertain)) without_value.push_back(sym);
  emit_base(j, rs, without_value);
  j.key("swept");
  j.begin_array();
  for (const auto& sym : swept) j.value(sym);
  j.end_array();
  j.key("axes");
  j.begin_array(layout::multi_line);
  for (const auto& ax : s.axes) {
    j.begin_object();
    j.member("name", canonical_symbol(ax.name));
    j.key("values");
    j.begin_array();
    for (double v : ax.values) j.value(v);
    j.end_array();
    j.end_object();
  }
  j.end_array();
  j.key("initial_conditions");
  j.begin_object();
  j.member("position_min", s.initial.position_min);
  j.member("position_max", s.initial.position_max);
  j.member("velocity_min", s.initial.velocity_min);
  j.member("velocity_max", s.initial.velocity_max);
  j.member("belt_start", belt_start_text(s.initial.belt_start));
  j.end_object();
  j.member("seed", s.seed);
  j.member("realizations", s.realizations);
  j.member("block_size", s.block_size);
  j.member("max_events", static_cast<std::int64_t>(s.max_events));
  j.member("keep_records", s.keep_records);
  j.member("common_random_numbers", s.common_random_numbers);
  if (!s.uncertain.empty()) {
    // Each drawn per realization from its law (docs/uncertainty.md); the
    // points' values of these are the laws' medians.
    j.key("uncertain_parameters");
    j.begin_object();
    for (const auto& u : s.uncertain) j.member(u.symbol, to_string(u.law));
    j.end_object();
  }
  j.key("target_ci");
  if (s.target_statistic.empty()) {
    j.null();
  } else {
    j.begin_object();
    j.member("statistic", s.target_statistic);
    j.member("halfwidth", s.target_halfwidth);
    j.member("min_realizations", s.min_realizations);
    j.member("max_realizations", s.realizations);
    j.end_object();
  }
  j.key("statistics");
  j.begin_array();
  for (const auto& name : selected_group_names(s.statistics)) j.value(name);
  j.end_array();
  if (s.burn_in != 0.0) j.member("burn_in", s.burn_in);  // only with one: [T, t_a] [s]
  if (s.statistics.survival) {
    j.key("survival");
    j.begin_object();
    j.member("bins", static_cast<std::uint64_t>(s.survival.bins));
    for (const auto& law : survival_laws()) {
      j.key(law.coordinate);  // the edges, the curves' durations [s]
      j.begin_array();
      for (double e : survival_edges(s.survival.*law.upper, s.survival.bins)) j.value(e);
      j.end_array();
    }
    j.end_object();
  }
  j.key("histograms");
  j.begin_object();
  j.member("bins", static_cast<std::uint64_t>(s.histograms.bins));
  j.member("stick_duration_max", s.histograms.stick_duration_max);
  j.member("slip_duration_max", s.histograms.slip_duration_max);
  j.end_object();
  j.member("threads", static_cast<std::uint64_t>(rs.threads));
  j.member("ranks", static_cast<std::uint64_t>(rs.ranks));
  j.member("version", meta.version);
  j.member("git_revision", meta.git_revision);
  j.member("command_line", meta.command_line);
  j.member("created_utc", meta.created_utc);
  j.member("config", meta.resolved_config);
  j.member("joint_histograms", !selects_joint_histograms(s.statistics) || s.means_only
                                   ? "not selected (--statistics family)"
                               : options.json_joint_histograms ? "here and in results.nc"
                                                               : "in results.nc only");
  if (!s.observe_times.empty())
    j.member("observed", "time, stick_probability and its std error here; every observe-time "
                         "variable in results.nc");
  j.end_object();
}

// summary.json up to the opening of its "points" array: what holds for the
// whole grid (`rs`, or a streamed run's header: its spec, threads and ranks).
void begin_summary_json(json_emitter& j, const result_set& rs, const run_metadata& meta,
                        const output_options& options) {
  j.begin_object(layout::multi_line);
  j.key("parameters");
  emit_parameters(j, rs, meta, options);
  // As results.nc's `warning` attribute (writer_netcdf.cpp).
  if (const auto note = unmet_target_note(rs); !note.empty()) j.member("warning", note);
  j.key("points");
  j.begin_array(layout::multi_line);
}

// The rest after the points: the run's elapsed time.
void end_summary_json(json_emitter& j, text_sink& out, const result_set& rs) {
  j.end_array();
  j.member("elapsed_seconds", rs.elapsed_seconds);
  j.end_object();
  out.put('\n');
}

}  // namespace

void fill_summary_json(text_sink& out, const result_set& rs, const run_metadata& meta,
                       const output_options& options) {
  check_shape(rs);
  json_emitter j(out);
  begin_summary_json(j, rs, meta, options);
  emit_points(j, rs, point_parameter_symbols(rs), options);
  end_summary_json(j, out, rs);
}

summary_json_stream::summary_json_stream(text_sink& out, const result_set& header,
                                         const run_metadata& meta, const output_options& options)
    : out_(out),
      options_(options),
      symbols_(point_parameter_symbols(header)),
      j_(std::make_unique<json_emitter>(out)) {
  begin_summary_json(*j_, header, meta, options);
}

summary_json_stream::~summary_json_stream() = default;

void summary_json_stream::slab(const result_set& slab) {
  emit_points(*j_, slab, symbols_, options_);
}

void summary_json_stream::end(const result_set& header) { end_summary_json(*j_, out_, header); }

}  // namespace detail

std::string summary_json(const result_set& rs, const run_metadata& meta,
                         const output_options& options) {
  detail::text_sink out;
  detail::fill_summary_json(out, rs, meta, options);
  return out.str();
}

std::string summary_json_points(const result_set& rs, const output_options& options) {
  detail::check_shape(rs);
  detail::text_sink out;
  detail::json_emitter j(out, 1);  // indented as inside the document
  j.begin_array(detail::layout::multi_line);
  detail::emit_points(j, rs, detail::point_parameter_symbols(rs), options);
  j.end_array();
  return out.str();
}

void write_summary_json(const result_set& rs, const run_metadata& meta, const std::string& path,
                        const output_options& options) {
  detail::write_text_atomically(
      path, [&](detail::text_sink& out) { detail::fill_summary_json(out, rs, meta, options); });
}

}  // namespace stickslip::io
