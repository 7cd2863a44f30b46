// The rows of the estimate table (estimates.hpp) and the names they give.
#include "stickslip/estimates.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <stdexcept>

namespace stickslip {
namespace {

using source = const estimate_source&;
using quantity = const quantity_info&;
using value = std::optional<estimate_value>;

// Units of a derivative over a rate in 1/s (lambda, r_j), as results.nc has
// always spelled them: a pure number per 1/s is s, 1/s per 1/s is 1, else
// "<units> s".
std::string per_rate(quantity q, std::string_view) {
  const std::string u = q.units;
  return u == "1" ? "s" : u == "1/s" ? "1" : u + " s";
}

// The units of d(quantity)/d(parameter): "1" over "1/s" is "s", the same
// units cancel, else "(q) / (p)".
std::string per_unit_of(quantity q, std::string_view per) {
  const std::string u = q.units, p(per);
  if (u == p) return "1";
  if (p == "1") return u;
  if (u == "1" && p == "1/s") return "s";
  return "(" + u + ") / (" + p + ")";
}

std::string same_units(quantity q, std::string_view) { return q.units; }

bool has_score(quantity q) noexcept { return q.score != nullptr; }
bool has_rate_score(quantity q) noexcept { return q.rate_score != nullptr; }
bool has_generator_score(quantity q) noexcept { return q.generator_score != nullptr; }
// The causal score is R's only (point_statistics::stick_fraction_causal_score).
bool is_stick_fraction(quantity q) noexcept {
  return &q == &quantity_table[quantity_row("stick_fraction")];
}
// One value per realization of every realization: what CRN pairs.
bool per_realization_value(quantity q) noexcept {
  return q.sampled == sampling::per_realization && q.value != nullptr;
}

bool poisson(source s) noexcept { return has_poisson_switching(s.point.parameters); }
bool own_rates(source s) noexcept { return s.point.stats.belt_rates[0] > 0.0; }
bool own_generator(source s) noexcept { return !s.point.stats.generator.empty(); }
bool crn(source s) noexcept { return !s.crn_slopes.empty(); }

value lambda_derivative(source s, quantity q, std::size_t) noexcept {
  if (!poisson(s)) return std::nullopt;
  const auto& p = s.point;
  return estimate_value{score_derivative(p.stats.*q.score, p.stats.*q.moments,
                                         p.parameters.switch_rate)};
}

value causal_derivative(source s, quantity, std::size_t) noexcept {
  if (!poisson(s)) return std::nullopt;
  return estimate_value{causal_score_derivative(s.point.stats.stick_fraction_causal_score)};
}

value control_variate(source s, quantity q, std::size_t) noexcept {
  if (!poisson(s)) return std::nullopt;
  const auto c = control_variate_mean(s.point.stats.*q.score, s.point.stats.*q.moments);
  return estimate_value{c.mean, c.variance_reduction};
}

value rate_derivative(source s, quantity q, std::size_t j) noexcept {
  if (!own_rates(s)) return std::nullopt;
  return estimate_value{belt_rate_derivative(s.point.stats, q, j)};
}

// Index i n + j: q_ij; nothing for i = j and where q_ij = 0.
value generator_derivative(source s, quantity q, std::size_t ij) noexcept {
  const auto& st = s.point.stats;
  const std::size_t n = st.level_fraction.size();
  if (!own_generator(s) || n == 0 || st.generator.size() != n * n) return std::nullopt;
  const std::size_t i = ij / n, j = ij % n;
  if (i == j || !(st.generator[ij] > 0.0)) return std::nullopt;
  return estimate_value{belt_generator_derivative(st, q, i, j)};
}

value crn_slope_over(source s, quantity q, std::size_t axis) noexcept {
  for (const auto& c : s.crn_slopes)
    if (c.axis == axis && c.quantity == &q) return estimate_value{c.slope, NAN, c.pairs};
  return std::nullopt;
}

constexpr const char* score_error = "its delta-method standard error";
constexpr auto derivatives = &statistics_selection::derivatives;

// In the order summary.json writes them.
const std::array<estimate_info, 6> estimate_table{{
    {"dmean_dlambda", "{q}_dmean_dlambda", "", "value", estimate_index::none,
     estimate_extra::none, derivatives, "slope", "", "d mean/d lambda: ", score_error,
     "likelihood-ratio (score) estimate of d E[{sym}]/d lambda: mean of (X - mean X)(N/lambda "
     "- t_a), N the belt switches of the realization in [0, t_a]",
     per_rate, has_score, poisson, lambda_derivative},
    {"dmean_dlambda_causal", "{q}_dmean_dlambda_causal", "", "value", estimate_index::none,
     estimate_extra::none, derivatives, "slope", " causal", "d mean/d lambda: ",
     "the residual standard error",
     "causal likelihood-ratio estimate of d E[{sym}]/d lambda: mean of Z - beta Y, Z = (1/t_a) "
     "int stick(t) M(t) dt with M(t) = N(t)/lambda - t the score of the switching observed up "
     "to t, Y = (1/t_a) int M(t) dt (mean 0) its control, beta = Cov(Z, Y)/Var(Y); the slope "
     "of dmean_dlambda with far less variance (docs/precision.md)",
     per_rate, is_stick_fraction, poisson, causal_derivative},
    {"control_variate", "{q}_cv", "_mean", "mean", estimate_index::none,
     estimate_extra::variance_reduction, derivatives, "CV mean", "", "",
     "the residual standard error",
     "control-variate mean of {sym}: mean X - beta (mean N - lambda t_a), beta = Cov(X, N)/"
     "Var(N) (N the belt switches, known mean lambda t_a)",
     same_units, has_score, poisson, control_variate},
    {"dmean_drates", "{q}_dmean_d{i}", "", "value", estimate_index::belt_rate,
     estimate_extra::none, derivatives, "slope", " {i}", "d mean/d {i}: ", score_error,
     "likelihood-ratio (score) estimate of d E[{sym}]/d {i} for a two-level belt given its own "
     "rates: mean of (X - mean X) K/{i}, K = N_j - {i} T_j (+ the stationary start's term), "
     "N_j the jumps out of level j and T_j the time there; NaN at points without belt rates",
     per_rate, has_rate_score, own_rates, rate_derivative},
    {"dmean_dgenerator", "{q}_dmean_dgenerator", "", "value", estimate_index::generator_entry,
     estimate_extra::none, derivatives, "slope", " {i}", "d mean/d {i}: ", score_error,
     "likelihood-ratio (score) estimate of d E[{sym}]/d q_ij, q_ij the belt's rate of jumping "
     "from level i (belt_level) to level j (belt_level_to): mean of (X - mean X) K_ij/q_ij, "
     "K_ij = N_ij - q_ij T_i (+ the stationary start's term), N_ij the jumps from i to j and "
     "T_i the time at level i; NaN for i = j and where q_ij = 0",
     per_unit_of, has_generator_score, own_generator, generator_derivative},
    {"crn_slopes", "{q}_dmean_d{i}_crn", "", "value", estimate_index::axis,
     estimate_extra::pairs, derivatives, "slope", " {i}", "d mean/d {i}: ",
     "its standard error",
     "common-random-number difference of the point's neighbours on the {i} axis, paired per "
     "realization: mean (X_r(b) - X_r(a)) / ({i}_b - {i}_a); one-sided at the axis ends; the "
     "interval holds the sampling error only",
     per_unit_of, per_realization_value, crn, crn_slope_over},
}};

std::string fill(const char* pattern, const quantity_info& q, std::string_view index) {
  return fmt::format(fmt::runtime(pattern), fmt::arg("q", q.name), fmt::arg("sym", q.symbol),
                     fmt::arg("i", index));
}

}  // namespace

std::span<const estimate_info> estimate_kinds() noexcept { return estimate_table; }

std::vector<estimate_source> estimate_sources(const result_set& rs,
                                              const std::vector<std::vector<crn_slope>>& slopes) {
  std::vector<estimate_source> out;
  out.reserve(rs.points.size());
  for (std::size_t i = 0; i < rs.points.size(); ++i)
    out.push_back({rs.spec, rs.points[i],
                   i < slopes.size() ? std::span<const crn_slope>(slopes[i])
                                     : std::span<const crn_slope>{}});
  return out;
}

const estimate_info& estimate_kind(std::string_view name) {
  for (const auto& row : estimate_table)
    if (name == row.name) return row;
  throw std::out_of_range("estimate_kind: no row of the estimate table is named " +
                          std::string(name));
}

bool selects_estimates(const statistics_selection& s) noexcept {
  return std::any_of(estimate_table.begin(), estimate_table.end(),
                     [&](const estimate_info& row) { return s.*row.group; });
}

bool selects(const statistics_selection& s, const estimate_info& row,
             const quantity_info& q) noexcept {
  return s.*row.group && row.has(q) && selects(s, q);
}

std::vector<std::size_t> estimate_indices(const estimate_info& row, const sweep_spec& spec) {
  std::vector<std::size_t> out;
  switch (row.index) {
    case estimate_index::none: out = {0}; break;
    case estimate_index::belt_rate: out = {0, 1}; break;
    case estimate_index::generator_entry: {
      const std::size_t n = spec.base.levels().size();
      for (std::size_t ij = 0; ij < n * n; ++ij) out.push_back(ij);
      break;
    }
    case estimate_index::axis:
      for (std::size_t k = 0; k < spec.axes.size(); ++k)
        if (spec.axes[k].values.size() >= 2) out.push_back(k);
      break;
  }
  return out;
}

std::string estimate_index_name(const estimate_info& row, const sweep_spec& spec,
                                std::size_t i) {
  switch (row.index) {
    case estimate_index::none: return "";
    case estimate_index::belt_rate: return i == 0 ? "r1" : "r2";
    case estimate_index::generator_entry: return "q_ij";
    case estimate_index::axis: return spec.axes.at(i).name;
  }
  return "";
}

std::string estimate_variable(const estimate_info& row, std::string_view quantity,
                              std::string_view index) {
  return fmt::format(fmt::runtime(row.variable), fmt::arg("q", quantity), fmt::arg("i", index));
}

std::string estimate_long_name(const estimate_info& row, const quantity_info& q,
                               std::string_view index, int side) {
  const char* end = side < 0 ? " low" : side > 0 ? " high" : "";
  return fmt::format("{}{} {}{}", row.label, end, q.symbol, fill(row.tail, q, index));
}

std::string estimate_description(const estimate_info& row, const quantity_info& q,
                                 std::string_view index, int side) {
  const std::string definition = fill(row.definition, q, index);
  if (side == 0) return fill(row.value_intro, q, index) + definition;
  return fmt::format("{} {} 1.96 x {}; {}", row.value_member, side < 0 ? '-' : '+', row.error,
                     definition);
}

std::string estimate_units(const estimate_info& row, const quantity_info& q,
                           std::string_view index) {
  const bool over_axis = row.index == estimate_index::axis;
  return row.units(q, over_axis ? info_for(std::string(index)).units : "1/s");
}

const char* extra_name(estimate_extra e) noexcept {
  switch (e) {
    case estimate_extra::none: return "";
    case estimate_extra::variance_reduction: return "variance_reduction";
    case estimate_extra::pairs: return "pairs";
  }
  return "";
}

std::string extra_long_name(const estimate_info& row, const quantity_info& q,
                            std::string_view index) {
  switch (row.extra) {
    case estimate_extra::none: break;
    case estimate_extra::variance_reduction: return fmt::format("CV gain {}", q.symbol);
    case estimate_extra::pairs:
      return fmt::format("pairs {}{}", q.symbol, fill(row.tail, q, index));
  }
  return "";
}

std::string extra_description(const estimate_info& row, const quantity_info& q,
                              std::string_view index) {
  switch (row.extra) {
    case estimate_extra::none: break;
    case estimate_extra::variance_reduction:
      return "Var(X) / residual variance = 1/(1 - rho^2), rho = corr(X, N): how many times "
             "fewer realizations the control-variate mean needs";
    case estimate_extra::pairs:
      return "realizations paired in the slope (those both neighbours ran); " +
             fill(row.definition, q, index);
  }
  return "";
}

}  // namespace stickslip
