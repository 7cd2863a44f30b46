// summary.csv (one row per grid point, the same table as summary.json's
// points) and records.csv (one row per realization). Numbers are printed with
// fmt "{}" (shortest round-trip); a statistic that does not exist (the mean
// of D_1 without any stick, a std of one sample) is "nan".
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/estimates.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/precision/crn_slopes.hpp"
#include "stickslip/record_schema.hpp"
#include "writers_detail.hpp"

namespace stickslip::io {
namespace detail {

// A derived estimate's columns: quantity q's estimate of `row` at index i.
struct csv_estimate_column {
  const estimate_info* row;
  const quantity_info* q;
  std::size_t index;
  std::string name;  // "R_dmean_dlambda", "R_cv", "R_dmean_dgenerator_1_2"
};

namespace {

// A quantity sampled other than once per realization: its sample count is
// a column of its own.
bool pooled(const quantity_info& q) { return q.sampled != sampling::per_realization; }

// A statistic's four columns: mean, std and the ends of the 95% interval
// of the mean (mean_estimate, as in every output).
void print_statistic(text_sink& out, const mean_variance& mv) {
  const auto e = mean_estimate(mv);
  const double half = e.ci95_half_width();
  out.print(",{},{},{},{}", e.value, mv.std_dev(), e.value - half, e.value + half);
}

// The estimate table's columns (estimates.hpp), as results.nc's variables
// but named by the summary name (R_dmean_dlambda, R_cv_mean,
// R_dmean_dlambda_crn_pairs) and a generator's entries one by one
// (R_dmean_dgenerator_<i>_<j>, levels from 1): each only when some point has
// it.
std::vector<csv_estimate_column> csv_estimate_columns(const result_set& rs,
                                              const std::vector<estimate_source>& sources) {
  std::vector<csv_estimate_column> out;
  const std::size_t levels = rs.spec.base.levels().size();
  for (const auto& row : estimate_kinds())
    for (const auto& q : quantities()) {
      if (!selects(rs.spec.statistics, row, q)) continue;
      for (const auto i : estimate_indices(row, rs.spec)) {
        if (std::none_of(sources.begin(), sources.end(),
                         [&](const auto& s) { return row.at(s, q, i).has_value(); }))
          continue;
        auto name = estimate_variable(row, q.summary_name, estimate_index_name(row, rs.spec, i));
        if (row.index == estimate_index::generator_entry)
          name += fmt::format("_{}_{}", i / levels + 1, i % levels + 1);
        out.push_back({&row, &q, i, std::move(name)});
      }
    }
  return out;
}

void print_estimate_header(text_sink& out, const csv_estimate_column& c) {
  out.print(",{0}{1},{0}_ci95_low,{0}_ci95_high", c.name, c.row->value_suffix);
  if (c.row->extra != estimate_extra::none) out.print(",{}_{}", c.name, extra_name(c.row->extra));
}

// The value and the ends of its interval ("nan" where the point has no such
// estimate), then the extra (pairs 0 there).
void print_estimate(text_sink& out, const csv_estimate_column& c, const estimate_source& src) {
  const auto v = c.row->at(src, *c.q, c.index);
  const estimate e = v ? v->value : estimate{};
  out.print(",{},{},{}", e.value, e.value - e.ci95_half_width(), e.value + e.ci95_half_width());
  switch (c.row->extra) {
    case estimate_extra::none: break;
    case estimate_extra::variance_reduction:
      out.print(",{}", v ? v->variance_reduction : std::nan(""));
      break;
    case estimate_extra::pairs: out.print(",{}", v ? v->pairs : 0); break;
  }
}

}  // namespace

// Columns: the point's parameters, realizations, then for every quantity of
// the schema its mean, std and 95% CI, then the sample counts of the
// quantities not sampled once per realization, then every counter, the
// level quantities per level, and the derived estimates (those some point
// of `sources` has).
summary_csv_rows::summary_csv_rows(text_sink& out, const result_set& rs,
                                   const std::vector<estimate_source>& sources)
    : out_(out), symbols_(point_parameter_symbols(rs)) {
  for (const auto& sym : symbols_) out.print("{},", sym);
  out.write("realizations");
  // The burn-in T, only with one (every statistic is over [T, t_a]).
  if (rs.spec.burn_in != 0.0) out.write(",burn_in");
  // The selected statistics only (statistics_groups.hpp).
  const auto& sel = rs.spec.statistics;
  for (const auto& q : quantities())
    if (selects(sel, q)) out.print(",{0}_mean,{0}_std,{0}_ci95_low,{0}_ci95_high", q.summary_name);
  for (const auto& q : quantities())
    if (pooled(q) && selects(sel, q)) out.print(",{}_count", q.name);
  for (const auto& c : counters()) out.print(",{}", c.summary_name);
  // Level quantities: the four columns per level j = 1..n. Joint histograms
  // are not in the CSV (results.nc and summary.json hold them).
  const std::size_t levels = rs.spec.base.levels().size();
  for (const auto& q : level_quantities())
    for (std::size_t i = 1; i <= levels && selects(sel, q); ++i)
      out.print(",{0}_{1}_mean,{0}_{1}_std,{0}_{1}_ci95_low,{0}_{1}_ci95_high", q.summary_name, i);
  estimates_ = csv_estimate_columns(rs, sources);
  for (const auto& c : estimates_) print_estimate_header(out, c);
  out.put('\n');
}

void summary_csv_rows::print(const result_set& rs, const std::vector<estimate_source>& sources) {
  auto& out = out_;
  const auto& sel = rs.spec.statistics;
  const bool burn_in = rs.spec.burn_in != 0.0;
  for (const auto& src : sources) {
    const auto& p = src.point;
    const auto& s = p.stats;
    for (const auto& sym : symbols_) out.print("{},", parameter_value(p.parameters, sym));
    out.print("{}", s.realizations);
    if (burn_in) out.print(",{}", rs.spec.burn_in);
    for (const auto& q : quantities()) {
      if (!selects(sel, q)) continue;
      print_statistic(out, s.*q.moments);
    }
    for (const auto& q : quantities())
      if (pooled(q) && selects(sel, q)) out.print(",{}", (s.*q.moments).count());
    for (const auto& c : counters()) out.print(",{}", c.value(s));
    for (const auto& q : level_quantities()) {
      if (!selects(sel, q)) continue;
      for (const auto& mv : s.*q.moments) print_statistic(out, mv);
    }
    for (const auto& c : estimates_) print_estimate(out, c, src);
    out.put('\n');
  }
}

summary_csv_rows::~summary_csv_rows() = default;

void summary_csv_rows::print(const result_set& rs) {
  print(rs, estimate_sources(rs, {}));
}

void fill_summary_csv(text_sink& out, const result_set& rs) {
  check_shape(rs);
  std::vector<std::vector<crn_slope>> slopes;  // read from the records only for the estimates
  if (selects_estimates(rs.spec.statistics)) slopes = precision::crn_slopes(rs);
  const auto sources = estimate_sources(rs, slopes);
  summary_csv_rows csv(out, rs, sources);
  csv.print(rs, sources);
}

namespace {

// The record columns of records.csv: the identity and outcome rows of the
// record table (record_schema.hpp), in its order.
template <class F>
void for_each_records_csv_field(F&& f) {
  for (const auto& field : record_table)
    if (field.role != record_role::internal) f(field);
}

}  // namespace

void fill_records_csv(text_sink& out, const result_set& rs) {
  check_shape(rs);
  const auto symbols = swept_symbols(rs.spec);
  out.write("point,");
  for (const auto& sym : symbols) out.print("{},", sym);
  // The values each realization drew for the uncertain parameters.
  for (const auto& u : rs.spec.uncertain) out.print("{},", u.symbol);
  const char* separator = "";
  for_each_records_csv_field([&](const record_field& field) {
    out.print("{}{}", separator, field.name);
    separator = ",";
  });
  out.put('\n');
  // The fields of the family statistics (pieces of motion) are nan without
  // them, which the lanes and the reference alike do not sum.
  const bool family = rs.spec.family_statistics;
  for (std::size_t i = 0; i < rs.records.size(); ++i) {
    // The point's coordinates once, reused for every one of its records.
    std::string prefix = fmt::format("{},", i);
    for (const auto& sym : symbols)
      prefix += fmt::format("{},", parameter_value(rs.points[i].parameters, sym));
    for (const auto& r : rs.records[i]) {
      out.write(prefix);
      for (double v : r.drawn_values) out.print("{},", v);
      // -1 marks "no D_1" for first_stick_start/duration, as in realization_record
      // (with a burn-in a row can have sticks = 1 and -1 here: its stick is the
      // left-truncated one).
      separator = "";
      for_each_records_csv_field([&](const record_field& field) {
        out.write(separator);
        separator = ",";
        if (field.needs_family && !family) {
          out.write("nan");
          return;
        }
        visit_field(field, r, [&](const auto& v) {
          if constexpr (std::is_same_v<std::remove_cvref_t<decltype(v)>, bool>)
            out.put(v ? '1' : '0');
          else
            out.print("{}", v);
        });
      });
      out.put('\n');
    }
  }
}

}  // namespace detail

std::string summary_csv(const result_set& rs) {
  detail::text_sink out;
  detail::fill_summary_csv(out, rs);
  return out.str();
}

void write_summary_csv(const result_set& rs, const std::string& path) {
  detail::write_text_atomically(path,
                                [&](detail::text_sink& out) { detail::fill_summary_csv(out, rs); });
}

void write_records_csv(const result_set& rs, const std::string& path) {
  if (!rs.spec.keep_records)
    throw invalid_value("records.csv", path, "only when the sweep keeps raw per-realization records (keep_records)");
  detail::write_text_atomically(path,
                                [&](detail::text_sink& out) { detail::fill_records_csv(out, rs); });
}

}  // namespace stickslip::io
