// What makes a sweep spec valid: its grid axes, the constraints between
// them and the parameters' own, the statistics it selects, the burn-in and
// observe times, and the event bound at the worst point.
#include "stickslip/sweep.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "stickslip/error.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"
#include "stickslip/uncertainty/uncertain_realization.hpp"

namespace stickslip {
namespace {

// Two equal values on one axis would give two grid points with the same
// point_key, hence the same random streams: not independent replicates, and
// a coordinate that cannot be selected from.
void check_distinct(const axis& ax) {
  std::vector<double> sorted = ax.values;
  std::sort(sorted.begin(), sorted.end());
  const auto dup = std::adjacent_find(sorted.begin(), sorted.end());
  if (dup == sorted.end()) return;
  std::vector<std::size_t> at;
  for (std::size_t i = 0; i < ax.values.size(); ++i)
    if (ax.values[i] == *dup) at.push_back(i + 1);
  throw invalid_parameter(
      "grid axis " + ax.name, *dup,
      fmt::format("each value once; {} is entry #{} and #{}: equal grid points share one "
                  "random stream, so they are not independent replicates",
                  *dup, at[0], at[1]));
}

// An axis over a parameter that the base overrides would change nothing:
// refuse it rather than compute identical points.
void check_has_effect(const model_parameters& base, const std::string& sym) {
  if (const auto why = overridden_by_base(base, sym); !why.empty())
    throw invalid_value("grid axis", sym, fmt::format("an axis that has an effect: {}", why));
}

// Friction coefficients and belt levels and rates constrain each other
// (mu_k <= mu_s, distinct levels): every combination of their axes is
// checked, with the other axes at their first value.
void check_coupled_axes(const sweep_spec& s, const model_parameters& first) {
  std::vector<const axis*> coupled;
  double combinations = 1.0;
  for (const auto& ax : s.axes) {
    const std::string sym = canonical_symbol(ax.name);
    if (sym == "mu_s" || sym == "mu_k" || sym[0] == 'v' || sym[0] == 'r') {
      coupled.push_back(&ax);
      combinations *= static_cast<double>(ax.values.size());
    }
  }
  if (coupled.size() < 2 || combinations > 1e6) return;
  std::vector<std::size_t> at(coupled.size(), 0);
  while (true) {
    model_parameters p = first;
    for (std::size_t i = 0; i < coupled.size(); ++i)
      set_parameter(p, coupled[i]->name, coupled[i]->values[at[i]]);
    validate(p);
    std::size_t i = 0;
    while (i < coupled.size() && ++at[i] == coupled[i]->values.size()) at[i++] = 0;
    if (i == coupled.size()) return;
  }
}

// The survival grid of a run: its ends resolved (resolve_survival_grid).
void validate_survival_grid(const survival_spec& g) {
  if (g.bins < 1 || g.bins > max_histogram_bins)
    throw invalid_value("survival bins", std::to_string(g.bins),
                        "1 .. " + std::to_string(max_histogram_bins));
  for (const auto& l : survival_laws())
    if (const double upper = g.*l.upper; !(upper > 0) || !std::isfinite(upper))
      throw invalid_parameter(std::string("survival ") + l.coordinate + "_max", upper,
                              "finite and > 0 (0 = automatic is resolved by "
                              "resolve_survival_grid before a run)");
}

}  // namespace

void resolve_survival_grid(sweep_spec& s) {
  if (!s.statistics.survival) return;
  // The rest of the spec first: its points must exist (and be few enough)
  // before they are visited.
  sweep_spec rest = s;
  rest.statistics.survival = false;
  validate(rest);
  double stick = 0.0, slip = 0.0;
  for (std::size_t i = 0; i < point_count(s); ++i) {
    const model_parameters p = histogram_parameters(s, i);
    stick = std::max(stick, p.max_stick_duration());
    slip = std::max(slip, p.window);
  }
  if (s.survival.stick_duration_max == 0.0) s.survival.stick_duration_max = stick;
  if (s.survival.slip_duration_max == 0.0) s.survival.slip_duration_max = slip;
}


namespace {
// The smallest t_a of the grid.
double shortest_window(const sweep_spec& s) {
  double shortest = s.base.window;
  for (const auto& ax : s.axes)
    if (canonical_symbol(ax.name) == "ta")
      shortest = *std::min_element(ax.values.begin(), ax.values.end());
  return shortest;
}

// The smallest window a realization can have: the smallest t_a of the grid,
// or with a law on t_a the low end of its support (0 for gamma and
// lognormal, which no positive burn-in or observe time fits).
std::pair<double, std::string> smallest_window(const sweep_spec& s) {
  for (const auto& u : s.uncertain)
    if (u.symbol == "ta")
      return {support(u.law).first,
              fmt::format("the low end of the support of t_a's law {}", to_string(u.law))};
  return {shortest_window(s), "the shortest window of the sweep"};
}

// 0 <= T < t_a at every point and for every draw of a law on t_a.
void validate_burn_in(const sweep_spec& s) {
  if (s.burn_in == 0.0) return;
  const auto [shortest, what] = smallest_window(s);
  if (shortest == 0.0 && s.burn_in > 0.0)
    throw invalid_parameter("burn_in", s.burn_in,
                            fmt::format("0: {} is 0, so a draw can be shorter than any burn-in "
                                        "(use a law on t_a with min > T: uniform, truncnormal, "
                                        "beta, loguniform)",
                                        what));
  if (!(s.burn_in > 0.0) || !(s.burn_in < shortest))
    throw invalid_parameter("burn_in", s.burn_in,
                            fmt::format("0 <= burn_in < t_a = {} ({}; 0 = no burn-in)", shortest,
                                        what));
}

// Observe times: ascending, in [0, t_a] at every point (and every draw of a
// law on t_a), at most max_observe_times; not in a sensitivity study; fewer
// than 2^32 realizations (the quantile sketches count in 32 bits).
void validate_observe_times(const sweep_spec& s) {
  const auto& t = s.observe_times;
  if (t.empty()) return;
  if (t.size() > max_observe_times)
    throw invalid_parameter("observe_times", static_cast<double>(t.size()),
                            fmt::format("at most {} times", max_observe_times));
  const auto [shortest, what] = smallest_window(s);
  for (std::size_t j = 0; j < t.size(); ++j) {
    if (!(t[j] >= 0.0) || std::signbit(t[j]) || !(t[j] <= shortest))
      throw invalid_parameter("observe_times", t[j],
                              fmt::format("0 <= t <= t_a = {} ({})", shortest, what));
    if (j > 0 && !(t[j] > t[j - 1]))
      throw invalid_parameter("observe_times", t[j],
                              fmt::format("times in increasing order, each once (it follows {})",
                                          t[j - 1]));
  }
  if (!s.sensitivity_statistic.empty())
    throw invalid_value("observe_times", fmt::format("{} times", t.size()),
                        "none in a sensitivity study (its design rows keep one value per "
                        "realization, not states over time)");
  if (s.realizations >= (std::uint64_t{1} << 32))
    throw invalid_parameter("realizations", static_cast<double>(s.realizations),
                            "< 2^32 = 4294967296 with observe times");
}
}  // namespace

void validate(const sweep_spec& s) {
  // The first grid point stands for the base: a base value that every axis
  // replaces (mu_k = mu = 5 above a swept mu_s) must not make the grid fail.
  model_parameters first = s.base;
  for (const auto& ax : s.axes)
    if (!ax.values.empty() && is_parameter_symbol(ax.name))
      set_parameter(first, canonical_symbol(ax.name), ax.values.front());
  // Uncertain parameters: their laws first; then their medians stand for
  // them (the base's values of them are not used).
  validate_uncertain_points(s);
  if (!s.uncertain.empty()) first = with_medians(first, s.uncertain);
  validate(first);
  validate(s.initial);
  const std::size_t levels = s.base.levels().size();
  validate_belt_start(s.initial.belt_start, levels, true);
  std::set<std::string> seen;
  for (const auto& ax : s.axes) {
    const std::string sym = canonical_symbol(ax.name);  // throws on unknown names
    if (!seen.insert(sym).second)
      throw invalid_value("grid axis", ax.name, "each parameter swept at most once");
    if (ax.values.empty())
      throw invalid_value("grid axis " + ax.name, "(empty list)", "at least one value");
    check_has_effect(s.base, sym);
    check_distinct(ax);
    for (double v : ax.values) {
      model_parameters p = first;
      set_parameter(p, sym, v);
      if (!std::isfinite(v)) throw invalid_parameter(sym, v, "finite");
      validate(p);
    }
  }
  check_coupled_axes(s, first);
  validate_sensitivity(s);
  for (const auto& ax : s.axes) {
    const auto refinements = refinements_of(canonical_symbol(ax.name));
    for (const auto& other : s.axes)
      if (std::find(refinements.begin(), refinements.end(), canonical_symbol(other.name)) !=
          refinements.end())
        throw invalid_value("grid axis", ax.name,
                            fmt::format("not together with a {} axis: {} sets {} both", other.name,
                                        canonical_symbol(ax.name), fmt::join(refinements, " and ")));
  }
  if (s.realizations < 1)
    throw invalid_parameter("realizations", static_cast<double>(s.realizations), ">= 1");
  if (is_sensitivity(s) && s.target_halfwidth != 0.0 &&
      (!(s.target_halfwidth > 0.0) || !std::isfinite(s.target_halfwidth)))
    throw invalid_parameter("target half-width", s.target_halfwidth, "finite and > 0");
  // The derivatives differentiate the selected means (R, S_T/t_a, S_L/t_a).
  if (s.statistics.derivatives &&
      std::none_of(quantities().begin(), quantities().end(), [&](const quantity_info& q) {
        return q.score && selects(s.statistics, q);
      }))
    throw invalid_value("statistics", to_string(s.statistics),
                        "the derivatives with a mean they differentiate: paper,derivatives or "
                        "R,derivatives (R, sticks_per_time, slips_per_time)");
  if (const quantity_info* q = target_quantity(s)) {
    if (!selects(s.statistics, *q))
      throw invalid_value("target CI statistic", s.target_statistic,
                          fmt::format("one of the selected statistics (--statistics {})",
                                      to_string(s.statistics)));
    if (!(s.target_halfwidth > 0.0) || !std::isfinite(s.target_halfwidth))
      throw invalid_parameter("target CI half-width", s.target_halfwidth, "finite and > 0");
    if (s.min_realizations < 2 || s.min_realizations > s.realizations)
      throw invalid_value("min_realizations", std::to_string(s.min_realizations),
                          "2 .. the maximum realizations per point (" +
                              std::to_string(s.realizations) +
                              "): lower min_realizations (1000 unless given) or raise the "
                              "maximum");
  }
  if (s.realizations > max_realizations)
    throw invalid_value("realizations", std::to_string(s.realizations),
                        "1 .. 2^40 = " + std::to_string(max_realizations));
  if (s.block_size < 1 || s.block_size > max_block_size)
    throw invalid_value("block_size", std::to_string(s.block_size),
                        "1 .. 2^24 = " + std::to_string(max_block_size));
  if (s.histograms.bins < 1 || s.histograms.bins > max_histogram_bins)
    throw invalid_value("bins", std::to_string(s.histograms.bins),
                        "1 .. " + std::to_string(max_histogram_bins));
  if (!(s.histograms.stick_duration_max >= 0) || !std::isfinite(s.histograms.stick_duration_max))
    throw invalid_parameter("stick_duration_max", s.histograms.stick_duration_max,
                            "finite and >= 0 (0 = d_max)");
  if (!(s.histograms.slip_duration_max >= 0) || !std::isfinite(s.histograms.slip_duration_max))
    throw invalid_parameter("slip_duration_max", s.histograms.slip_duration_max,
                            "finite and >= 0 (0 = automatic)");
  if (s.statistics.survival) validate_survival_grid(s.survival);
  // 2^53: event counts are exact in doubles up to there (the lane engine
  // keeps them in SIMD registers); no realization comes near it.
  if (s.max_events < 1 || s.max_events > max_event_bound)
    throw invalid_value("max_events", std::to_string(s.max_events), "1 .. 2^53 = 9007199254740992");
  validate_burn_in(s);
  validate_observe_times(s);
  // Product of the axis sizes in floating point: point_count() would wrap.
  double points = 1.0;
  for (const auto& ax : s.axes) points *= static_cast<double>(ax.values.size());
  if (points > 1e7) throw invalid_parameter("number of grid points", points, "<= 1e7");
  if (s.keep_records && points * static_cast<double>(s.realizations) > 5e7)
    throw invalid_parameter("points x realizations with raw records", points * s.realizations,
                            "<= 5e7 (records are held in memory)");
  // Expected belt switches per realization must fit the event bound, at the
  // worst point: the largest rate of leaving a level times the largest t_a.
  auto largest = [&](const char* symbol) {
    double v = parameter_value(s.base, symbol);
    for (const auto& ax : s.axes)
      if (canonical_symbol(ax.name) == symbol)
        v = *std::max_element(ax.values.begin(), ax.values.end());
    for (const auto& u : s.uncertain)
      if (u.symbol == symbol) v = largest_draw(u.law);
    return v;
  };
  double fastest = 0.0;
  if (!s.base.belt_generator.empty()) {
    const std::vector<double> q = s.base.generator();
    for (std::size_t i = 0; i < levels; ++i) fastest = std::max(fastest, -q[i * levels + i]);
  } else if (!s.base.belt_rates.empty() || seen.contains("r1") || seen.contains("r2") ||
             std::any_of(s.uncertain.begin(), s.uncertain.end(),
                         [](const auto& u) { return u.symbol == "r1" || u.symbol == "r2"; })) {
    fastest = std::max(largest("r1"), largest("r2"));
  } else {
    fastest = largest("lambda");
  }
  const double expected = fastest * largest("ta");
  if (expected > 0.5 * static_cast<double>(s.max_events))
    throw invalid_parameter("lambda * ta (the largest belt rate times t_a: expected belt "
                            "switches per realization)",
                            expected, "<= max_events / 2 = " + std::to_string(s.max_events / 2));
}

}  // namespace stickslip
