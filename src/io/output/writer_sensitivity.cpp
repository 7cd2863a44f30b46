// The outputs of a sensitivity study (uncertainty/sensitivity_design.hpp):
// sensitivity.nc (an `input` dimension: first- and total-order indices of
// the mean response with their 95 % intervals, the first-order indices in
// the response, the shares) and summary.json (what `--format json` prints,
// with the run's metadata). The numbers come from sobol_indices() of the
// merged design; nothing here estimates anything.
#include <netcdf>

#include <fmt/format.h>

#include <string>
#include <vector>

#include "../netcdf_file.hpp"
#include "json_emitter.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"
#include "stickslip/uncertainty/sobol.hpp"
#include "stickslip/uncertainty/uncertain_draws.hpp"
#include "writers_detail.hpp"

namespace stickslip::io {
namespace nc = netCDF;

namespace detail {
namespace {

const point_statistics& design_of(const result_set& rs) {
  if (!is_sensitivity(rs.spec) || rs.points.size() != 1)
    throw error(exit_code::internal, "sensitivity outputs of a result set that is not a design");
  return rs.points.front().stats;
}

void emit_interval(json_emitter& j, std::string_view name, const interval_estimate& e) {
  j.member(name, e.value);
  j.key(std::string(name) + "_ci95");
  j.begin_array();
  j.value(e.low);
  j.value(e.high);
  j.end_array();
}

void emit_sensitivity(json_emitter& j, const result_set& rs) {
  const auto& stats = design_of(rs);
  const sobol_estimates est = sobol_indices(stats.sensitivity);
  const auto& q = sensitivity_quantity(rs.spec);
  j.member("statistic", q.summary_name);
  j.member("realizations", stats.realizations * runs_per_row(rs.spec));
  j.member("samples", est.rows);
  j.member("elapsed_seconds", rs.elapsed_seconds);
  j.member("seed", rs.spec.seed);
  j.key("laws");
  j.begin_object();
  for (const auto& u : rs.spec.uncertain) j.member(u.symbol, to_string(u.law));
  j.end_object();
  // The fixed parameters, as a sweep's summary.json writes its
  // parameters.base (null for those the laws set; a new user found k = 40
  // only in the command line).
  emit_base(j, rs, symbols_set_by_laws(rs.spec.uncertain));
  j.member("mean", est.mean);
  j.member("variance", est.variance);
  j.member("intrinsic_variance", est.intrinsic_variance);
  if (rs.spec.target_halfwidth > 0.0) {  // --target-halfwidth, and whether it was reached
    j.member("target_halfwidth", rs.spec.target_halfwidth);
    j.member("target_met", study_target_met(rs.spec, est));
  }
  if (const auto note = study_warning(rs.spec, est); !note.empty()) j.member("warning", note);
  j.key("indices");
  j.begin_array(layout::multi_line);
  for (std::size_t i = 0; i < rs.spec.uncertain.size(); ++i) {
    j.begin_object();
    j.member("input", rs.spec.uncertain[i].symbol);
    j.member("of", "mean");
    emit_interval(j, "first_order", est.first_order[i]);
    emit_interval(j, "total_order", est.total_order[i]);
    j.end_object();
  }
  for (std::size_t i = 0; i < rs.spec.uncertain.size(); ++i) {
    j.begin_object();
    j.member("input", rs.spec.uncertain[i].symbol);
    j.member("of", "response");
    emit_interval(j, "first_order", est.response_first_order[i]);
    j.end_object();
  }
  j.end_array();
  j.key("shares");
  j.begin_object();
  emit_interval(j, "parameters", est.parameter_share);
  emit_interval(j, "intrinsic", est.intrinsic_share);
  j.end_object();
}

void put_indices(nc::NcFile& f, const nc::NcDim& input, const std::string& name,
                 const std::vector<interval_estimate>& v, const std::string& long_name) {
  std::vector<double> value, low, high;
  for (const auto& e : v) {
    value.push_back(e.value);
    low.push_back(e.low);
    high.push_back(e.high);
  }
  auto put = [&](const std::string& n, const std::vector<double>& x, const std::string& what) {
    auto var = f.addVar(n, nc::ncDouble, input);
    var.putAtt("units", "1");
    var.putAtt("long_name", what);
    var.putAtt("coordinates", "input");
    if (!x.empty()) var.putVar(x.data());
  };
  put(name, value, long_name);
  put(name + "_ci95_low", low, long_name + ", lower end of the 95 % interval");
  put(name + "_ci95_high", high, long_name + ", upper end of the 95 % interval");
}

void put_scalar(nc::NcFile& f, const std::string& name, double x, const std::string& units,
                const std::string& long_name) {
  auto var = f.addVar(name, nc::ncDouble, std::vector<nc::NcDim>{});
  var.putAtt("units", units);
  var.putAtt("long_name", long_name);
  var.putVar(&x);
}

void write_sensitivity_file(const result_set& rs, const run_metadata& meta,
                            const std::string& file) {
  const auto& stats = design_of(rs);
  const sobol_estimates est = sobol_indices(stats.sensitivity);
  const auto& q = sensitivity_quantity(rs.spec);
  nc_file f(file, nc::NcFile::replace, nc::NcFile::nc4);
  f.putAtt("title", fmt::format("stickslip sensitivity: Sobol' indices of {}", q.summary_name));
  f.putAtt("Conventions", "CF-1.8");
  f.putAtt("source", fmt::format("stickslip {} (git {})", meta.version, meta.git_revision));
  f.putAtt("history", fmt::format("{}: {}", meta.created_utc, meta.command_line));
  f.putAtt("version", meta.version);
  f.putAtt("git_revision", meta.git_revision);
  f.putAtt("command_line", meta.command_line);
  f.putAtt("created_utc", meta.created_utc);
  f.putAtt("resolved_config", meta.resolved_config);
  f.putAtt("statistic", q.summary_name);
  f.putAtt("statistic_long_name", q.long_name);
  f.putAtt("statistic_units", q.units);
  f.putAtt("seed", nc::ncUint64, static_cast<unsigned long long>(rs.spec.seed));
  f.putAtt("samples", nc::ncUint64, static_cast<unsigned long long>(est.rows));
  f.putAtt("realizations", nc::ncUint64, static_cast<unsigned long long>(stats.realizations * runs_per_row(rs.spec)));
  f.putAtt("threads", nc::ncInt, static_cast<int>(rs.threads));
  f.putAtt("ranks", nc::ncInt, static_cast<int>(rs.ranks));
  f.putAtt("elapsed_seconds", nc::ncDouble, rs.elapsed_seconds);
  if (rs.spec.target_halfwidth > 0.0) {
    f.putAtt("target_halfwidth", nc::ncDouble, rs.spec.target_halfwidth);
    f.putAtt("target_met", nc::ncInt, study_target_met(rs.spec, est) ? 1 : 0);  // as keep_records
  }
  if (const auto note = study_warning(rs.spec, est); !note.empty()) f.putAtt("warning", note);
  f.putAtt("estimators",
           "first order: OpenTURNS's Saltelli form, centred by the mean of all outputs "
           "(Saltelli 2010's uncentred form estimates the same quantity); total order: Jansen "
           "(1999); intrinsic variance from "
           "a replicate at the same parameters; 95 % intervals by the delta method "
           "(docs/uncertainty.md)");
  const auto d = rs.spec.uncertain.size();
  const auto input = f.addDim("input", d);
  auto names = f.addVar("input", nc::ncString, input);
  names.putAtt("long_name", "uncertain model parameter");
  auto laws = f.addVar("law", nc::ncString, input);
  laws.putAtt("long_name", "the parameter's probability law");
  for (std::size_t i = 0; i < d; ++i) {
    const char* sym = rs.spec.uncertain[i].symbol.c_str();
    const std::string law = to_string(rs.spec.uncertain[i].law);
    const char* law_c = law.c_str();
    names.putVar(std::vector<std::size_t>{i}, &sym);
    laws.putVar(std::vector<std::size_t>{i}, &law_c);
  }
  put_indices(f, input, "first_order", est.first_order,
              "first-order Sobol' index of the mean response E[STAT | theta]");
  put_indices(f, input, "total_order", est.total_order,
              "total-order Sobol' index of the mean response E[STAT | theta]");
  put_indices(f, input, "response_first_order", est.response_first_order,
              "Var E[STAT | theta_i] / Var STAT");
  auto share = [&](const std::string& name, const interval_estimate& e, const std::string& what) {
    put_scalar(f, name, e.value, "1", what);
    put_scalar(f, name + "_ci95_low", e.low, "1", what + ", lower end of the 95 % interval");
    put_scalar(f, name + "_ci95_high", e.high, "1", what + ", upper end of the 95 % interval");
  };
  share("parameter_share", est.parameter_share, "Var E[STAT | theta] / Var STAT");
  share("intrinsic_share", est.intrinsic_share, "E Var(STAT | theta) / Var STAT");
  put_scalar(f, "statistic_mean", est.mean, q.units, "mean of STAT over parameters and realizations");
  // UDUNITS: the statistic's units squared ("1" stays "1").
  const std::string u = q.units;
  const std::string squared = u == "1" ? u : "(" + u + ")^2";
  put_scalar(f, "statistic_variance", est.variance, squared, "Var STAT");
  put_scalar(f, "intrinsic_variance", est.intrinsic_variance, squared, "E Var(STAT | theta)");
  f.close();
}

}  // namespace

void write_sensitivity_temporary(const result_set& rs, const run_metadata& meta,
                                 const std::string& path) {
  write_netcdf_temporary_with(
      path, [&](const std::string& tmp) { write_sensitivity_file(rs, meta, tmp); });
}

void fill_sensitivity_json(text_sink& out, const result_set& rs, const run_metadata* meta) {
  json_emitter j(out);
  j.begin_object(layout::multi_line);
  emit_sensitivity(j, rs);
  if (meta) {
    j.key("run");
    j.begin_object(layout::multi_line);
    j.member("version", meta->version);
    j.member("git_revision", meta->git_revision);
    j.member("command_line", meta->command_line);
    j.member("created_utc", meta->created_utc);
    j.member("threads", static_cast<std::uint64_t>(rs.threads));
    j.member("ranks", static_cast<std::uint64_t>(rs.ranks));
    j.end_object();
  }
  j.end_object();
  out.put('\n');
}

}  // namespace detail

std::string sensitivity_json(const result_set& rs) {
  detail::text_sink out;
  detail::fill_sensitivity_json(out, rs, nullptr);
  return out.str();
}

}  // namespace stickslip::io
