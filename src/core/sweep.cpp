#include "stickslip/sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <numbers>
#include <set>
#include <thread>

#include "stickslip/detail/fast_block.hpp"
#include "stickslip/error.hpp"
#include "stickslip/model/model_realization.hpp"
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
  const char* why = nullptr;
  if (sym == "V" && !base.belt_levels.empty()) why = "the belt levels are given";
  if (sym == "lambda" && (!base.belt_rates.empty() || !base.belt_generator.empty()))
    why = "the belt rates are given";
  if (sym == "mu" && (base.static_friction > 0.0 || base.kinetic_friction > 0.0))
    why = "mu sets mu_s and mu_k both, and one of them is given";
  if (why) throw invalid_value("grid axis", sym, fmt::format("an axis that has an effect: {}", why));
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

void apply_statistics_selection(sweep_spec& s) {
  s.family_statistics = needs_family_statistics(s.statistics);
  s.means_only = needs_means_only(s.statistics);
}

void select_statistics(point_statistics& stats, const sweep_spec& s) {
  if (s.statistics.survival) stats.select_survival(s.survival);
  if (!s.observe_times.empty()) stats.select_observe_times(s.observe_times, s.base.levels().size());
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
  for (const auto& ax : s.axes)
    for (const auto& other : s.axes)
      if (canonical_symbol(ax.name) == "mu" &&
          (canonical_symbol(other.name) == "mu_s" || canonical_symbol(other.name) == "mu_k"))
        throw invalid_value("grid axis", ax.name,
                            "not together with a " + other.name +
                                " axis: mu sets mu_s and mu_k both");
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
                              std::to_string(s.realizations) + ")");
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
  // worst point: the largest lambda times the largest t_a over the grid.
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

std::size_t point_count(const sweep_spec& s) noexcept {
  std::size_t n = 1;
  for (const auto& ax : s.axes) n *= ax.values.size();
  return n;
}

std::vector<std::size_t> point_index(const sweep_spec& s, std::size_t point) {
  std::vector<std::size_t> idx(s.axes.size());
  for (std::size_t k = s.axes.size(); k-- > 0;) {
    idx[k] = point % s.axes[k].values.size();
    point /= s.axes[k].values.size();
  }
  return idx;
}

model_parameters point_parameters(const sweep_spec& s, std::size_t point) {
  model_parameters p = s.base;
  const auto idx = point_index(s, point);
  for (std::size_t k = 0; k < s.axes.size(); ++k)
    set_parameter(p, s.axes[k].name, s.axes[k].values[idx[k]]);
  if (!s.uncertain.empty()) return with_medians(p, s.uncertain);  // what the point stands for
  return p.is_paper_model() ? paper_form(p) : p;
}

model_parameters histogram_parameters(const sweep_spec& s, std::size_t point) {
  model_parameters p = point_parameters(s, point);
  if (s.uncertain.empty()) return p;
  for (const auto& u : s.uncertain) {
    const auto& sym = u.symbol;
    const bool smaller = sym == "k" || sym == "V" || sym == "lambda" || sym == "r1" || sym == "r2";
    const bool larger = sym == "mu" || sym == "mu_s" || sym == "mu_k" || sym == "m" ||
                        sym == "g" || sym == "c" || sym == "ta";
    if (smaller || larger) set_parameter(p, sym, quantile(u.law, smaller ? 0.001 : 0.999));
  }
  return p;
}

std::uint64_t blocks_per_point(const sweep_spec& s) noexcept {
  return (s.realizations + s.block_size - 1) / s.block_size;
}
std::uint64_t unit_count(const sweep_spec& s) noexcept {
  return point_count(s) * blocks_per_point(s);
}
work_unit unit_at(const sweep_spec& s, std::uint64_t i) noexcept {
  const auto b = blocks_per_point(s);
  return {static_cast<std::size_t>(i / b), i % b};
}

// The paper's model: the lane engine or simulate() (the reference). The
// family: the lane engine for the models it runs (detail::runs_in_lanes:
// undamped two-level belts), simulate_model otherwise
// and for sweep_engine::reference.
block_result simulate_block(const sweep_spec& s, const work_unit& u) {
  if (is_sensitivity(s)) return simulate_block_sensitivity(s, u);
  if (!s.uncertain.empty()) return simulate_block_uncertain(s, u);
  const auto p = point_parameters(s, u.point);
  if (!p.is_paper_model()) {
    if (s.engine == sweep_engine::fast && detail::runs_in_lanes(p))
      return detail::simulate_block_lanes(s, u);
    return simulate_block_family(s, u);
  }
  if (s.engine == sweep_engine::reference) return simulate_block_reference(s, u);
  return detail::simulate_block_lanes(s, u);
}

std::uint64_t units_per_batch(const sweep_spec& s) noexcept {
  // Points with laws (and sensitivity designs) run on the scalar engine:
  // one unit per batch, no lanes to keep busy, a finer grain for the stop
  // rules.
  if (!s.uncertain.empty()) return 1;
  return s.engine == sweep_engine::fast ? 20 : 1;  // 20 x 50 realizations
}

std::vector<block_result> simulate_units(const sweep_spec& s, const std::vector<work_unit>& units) {
  const bool lanes = units_per_batch(s) > 1;
  std::vector<block_result> results;
  results.reserve(units.size());
  for (std::size_t a = 0; a < units.size();) {
    std::size_t b = a + 1;  // units[a, b): consecutive blocks of one point
    while (b < units.size() && units[b].point == units[a].point &&
           units[b].block == units[b - 1].block + 1)
      ++b;
    if (lanes && s.uncertain.empty() && detail::runs_in_lanes(point_parameters(s, units[a].point))) {
      auto r = detail::simulate_blocks_lanes(s, units[a].point, units[a].block, b - a);
      for (auto& x : r) results.push_back(std::move(x));
    } else {
      for (std::size_t c = a; c < b; ++c) results.push_back(simulate_block(s, units[c]));
    }
    a = b;
  }
  return results;
}

// Where the statistics keep no causal score (point_statistics::
// keeps_causal_score: the paper study's configuration, whose lane observer
// skips the bookkeeping), the reference engines drop theirs, so that the
// records are the same bits.
namespace {
void drop_causal_score(realization_record& r) noexcept {
  r.stick_switch_moment = r.stick_time_moment = 0.0;
  r.events.switch_time_sum = 0.0;
}
}  // namespace

// One realization at a time: simulate with poisson_switches, statistics
// through realization_observer and point_statistics::add in realization order.
block_result simulate_block_reference(const sweep_spec& s, const work_unit& u) {
  const auto p = point_parameters(s, u.point);
  block_result out;
  out.stats = point_statistics(p, s.histograms, s.family_statistics, s.initial.belt_start == 0,
                               s.means_only);
  select_statistics(out.stats, s);
  const std::uint64_t first = u.block * s.block_size;
  const std::uint64_t last = std::min(s.realizations, first + s.block_size);
  if (s.keep_records) out.records.reserve(last - first);
  const auto key = stream_key(s, p);
  realization_observer obs(p, s.family_statistics, s.burn_in, &s.observe_times);
  state_sampling_observer with_states(obs);
  for (std::uint64_t r = first; r < last; ++r) {
    const auto ic = draw_initial_conditions(s.initial, s.seed, key, r);
    poisson_switches sw(p.switch_rate, s.seed, key, r);
    obs.reset(r, ic.position, ic.velocity, ic.belt_direction);
    const auto counts = obs.observes_times() ? simulate(p, ic, sw, with_states, s.max_events)
                                             : simulate(p, ic, sw, obs, s.max_events);
    obs.finish();
    obs.record().events = counts;
    if (!out.stats.keeps_causal_score()) drop_causal_score(obs.record());
    out.stats.add(obs.samples(), p.window);
    if (s.keep_records) out.records.push_back(obs.record());
  }
  return out;
}

// The model family: simulate_model one realization at a time with the Markov
// belt (model/model_realization.hpp), into the same observer and statistics.
block_result simulate_block_family(const sweep_spec& s, const work_unit& u) {
  const auto p = point_parameters(s, u.point);
  const family_point fp(p, stream_key(s, p));
  block_result out;
  out.stats = point_statistics(p, s.histograms, s.family_statistics, s.initial.belt_start == 0,
                               s.means_only);
  select_statistics(out.stats, s);
  const std::uint64_t first = u.block * s.block_size;
  const std::uint64_t last = std::min(s.realizations, first + s.block_size);
  if (s.keep_records) out.records.reserve(last - first);
  const std::size_t levels = fp.model.belt.level_count();
  realization_observer obs(p, s.family_statistics, s.burn_in, &s.observe_times);
  state_sampling_observer with_states(obs);
  for (std::uint64_t r = first; r < last; ++r) {
    const model_initial_state start = draw_model_initial_state(fp, s.initial, s.seed, r);
    obs.reset(r, start.position, start.velocity, recorded_belt_start(start.level, levels));
    const auto counts =
        obs.observes_times()
            ? simulate_family_realization(fp, start, s.seed, r, s.max_events, with_states)
            : simulate_family_realization(fp, start, s.seed, r, s.max_events, obs);
    obs.finish();
    obs.record().events = counts;
    if (!out.stats.keeps_causal_score()) drop_causal_score(obs.record());
    out.stats.add(obs.samples(), p.window);
    if (s.keep_records) out.records.push_back(obs.record());
  }
  return out;
}

const quantity_info* target_quantity(const sweep_spec& s) {
  if (s.target_statistic.empty()) return nullptr;
  if (const auto* q = find_mean_statistic(s.target_statistic)) return q;
  throw invalid_value("target CI statistic", s.target_statistic,
                      "a statistic with one value per realization: " + mean_statistic_names());
}

bool meets_target(const sweep_spec& s, const point_statistics& p) {
  if (is_sensitivity(s)) return meets_sensitivity_target(s, p);
  const quantity_info* q = target_quantity(s);
  if (!q || p.realizations < s.min_realizations) return false;
  return (p.*q->moments).ci95_half_width() <= s.target_halfwidth;
}

ordered_merger::ordered_merger(const sweep_spec& s)
    : spec_(&s), records_(point_count(s)), next_block_(point_count(s), 0),
      finished_(point_count(s)) {
  points_.reserve(point_count(s));
  for (std::size_t i = 0; i < point_count(s); ++i) {
    points_.emplace_back(histogram_parameters(s, i), s.histograms, s.family_statistics);
    select_statistics(points_.back(), s);
  }
}

bool records_convergence_after(std::uint64_t b, std::uint64_t total) noexcept {
  if (b <= 64 || b == total) return true;
  // Above 64 blocks keep 32 trace points per doubling of n: the stride is
  // 2^(bit_width(b) - 6), so the trace grows with log N, not N.
  return b % (std::uint64_t{1} << (std::bit_width(b) - 6)) == 0;
}

void ordered_merger::add(const work_unit& u, block_result r) {
  if (discard_) {
    ++merged_;
    return;
  }
  if (point_finished(u.point)) return;  // a block after the point met its target
  pending_.emplace(u, std::move(r));
  const auto nb = blocks_per_point(*spec_);
  auto it = pending_.find(work_unit{u.point, next_block_[u.point]});
  while (it != pending_.end()) {
    auto& dst = points_[u.point];
    dst += it->second.stats;
    const std::uint64_t merged_blocks = next_block_[u.point] + 1;
    const bool stop = merged_blocks < nb && meets_target(*spec_, dst);
    if (records_convergence_after(merged_blocks, nb) || stop) dst.record_convergence();
    auto& rec = records_[u.point];
    rec.insert(rec.end(), std::make_move_iterator(it->second.records.begin()),
               std::make_move_iterator(it->second.records.end()));
    pending_.erase(it);
    ++merged_;
    if (++next_block_[u.point] >= nb) {
      finished_[u.point].store(1, std::memory_order_relaxed);
      break;
    }
    if (stop) {
      // The blocks this point no longer needs count as done; any of them
      // computed ahead (pending now or arriving later) are dropped.
      merged_ += nb - next_block_[u.point];
      finished_[u.point].store(1, std::memory_order_relaxed);
      std::erase_if(pending_, [&](const auto& kv) { return kv.first.point == u.point; });
      break;
    }
    it = pending_.find(work_unit{u.point, next_block_[u.point]});
  }
}

void ordered_merger::restore(merged_prefix p) {
  const auto nb = blocks_per_point(*spec_);
  points_[p.point] = std::move(p.stats);
  next_block_[p.point] = p.blocks;
  merged_ += p.blocks;
  // The stop rule as add() applied it after the prefix's last block.
  const bool stop = p.blocks < nb && meets_target(*spec_, points_[p.point]);
  if (stop) merged_ += nb - p.blocks;
  if (stop || p.blocks >= nb) finished_[p.point].store(1, std::memory_order_relaxed);
}

bool ordered_merger::complete() const noexcept { return merged_ == unit_count(*spec_); }

result_set make_result_set(const sweep_spec& s, ordered_merger&& m) {
  result_set rs;
  rs.spec = s;
  for (std::size_t i = 0; i < point_count(s); ++i)
    rs.points.push_back({point_parameters(s, i), point_index(s, i), std::move(m.points()[i])});
  if (s.keep_records) rs.records = std::move(m.records());
  return rs;
}

double expected_events(const model_parameters& p) {
  // The family: the mean rate of leaving a level and the largest level stand
  // in for lambda and V (a cost model, not physics).
  double rate = p.switch_rate, speed = p.belt_speed;
  if (!p.belt_levels.empty() || !p.belt_rates.empty() || !p.belt_generator.empty()) {
    const auto v = p.levels();
    const auto q = p.generator();
    rate = speed = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) {
      rate += -q[i * v.size() + i] / static_cast<double>(v.size());
      speed = std::max(speed, std::abs(v[i]));
    }
  }
  const double switches = rate * p.window;
  const double tau = 2.0 * speed / (p.mu_k() * p.gravity);
  const double p_onset = 1.0 / (1.0 + rate * tau);
  const double p_break = p_onset * std::exp(-rate * p.max_stick_duration());
  return 2.0 + switches * (1.0 + p_onset + 1.5 * p_break);
}

double expected_unit_cost(const sweep_spec& s, const work_unit& u) {
  const std::uint64_t first = u.block * s.block_size;
  const std::uint64_t last = std::min(s.realizations, first + s.block_size);
  // A design row runs d + 3 realizations.
  const double runs = is_sensitivity(s) ? static_cast<double>(runs_per_row(s)) : 1.0;
  return runs * static_cast<double>(last - first) * expected_events(point_parameters(s, u.point));
}

std::vector<std::size_t> points_by_cost(const sweep_spec& s) {
  const std::size_t n = point_count(s);
  std::vector<double> cost(n);
  for (std::size_t i = 0; i < n; ++i) {
    cost[i] = expected_events(point_parameters(s, i));
  }
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return cost[a] > cost[b]; });
  return order;
}

void run_units(const sweep_spec& s, unsigned threads, ordered_merger& merger,
               const sweep_hooks& hooks) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  const std::uint64_t total = unit_count(s);
  const std::uint64_t nb = blocks_per_point(s);
  const auto order = points_by_cost(s);
  // i-th unit to start: block i % nb of the (i / nb)-th most expensive point.
  auto scheduled = [&](std::uint64_t i) {
    return work_unit{order[static_cast<std::size_t>(i / nb)], i % nb};
  };
  // Skipping the units of finished points (a precision target met) saves
  // work only; the merger drops whatever still arrives for them.
  const std::uint64_t batch = units_per_batch(s);
  std::atomic<std::uint64_t> next{0};
  std::mutex mu;
  std::exception_ptr failure;
  auto worker = [&] {
    std::vector<work_unit> units;
    std::vector<block_result> results;
    while (true) {
      const std::uint64_t i0 = next.fetch_add(batch);
      if (i0 >= total) return;
      const std::uint64_t i1 = std::min(total, i0 + batch);
      units.clear();
      for (std::uint64_t i = i0; i < i1; ++i) {
        const auto u = scheduled(i);
        if (merger.point_finished(u.point)) continue;
        if (!hooks.wanted || hooks.wanted(u)) units.push_back(u);
      }
      try {
        results = simulate_units(s, units);
      } catch (...) {
        std::lock_guard lock(mu);
        if (!failure) failure = std::current_exception();
        next.store(total);
        return;
      }
      std::lock_guard lock(mu);
      if (failure) return;
      try {
        for (std::size_t c = 0; c < units.size(); ++c) {
          if (hooks.unit_done) hooks.unit_done(units[c], results[c]);
          merger.add(units[c], std::move(results[c]));
          if (hooks.progress) hooks.progress(merger.merged_units(), total);
        }
      } catch (...) {
        failure = std::current_exception();
        next.store(total);
        return;
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& th : pool) th.join();
  if (failure) std::rethrow_exception(failure);
}

result_set run_sweep(const sweep_spec& s, unsigned threads, const sweep_hooks& hooks) {
  validate(s);
  const auto t0 = std::chrono::steady_clock::now();
  ordered_merger merger(s);
  run_units(s, threads, merger, hooks);
  auto rs = make_result_set(s, std::move(merger));
  rs.elapsed_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  rs.threads = threads ? threads : std::max(1u, std::thread::hardware_concurrency());
  return rs;
}

}  // namespace stickslip
