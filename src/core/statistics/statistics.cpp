#include "stickslip/statistics.hpp"

#include "stickslip/error.hpp"
#include "stickslip/initial_conditions.hpp"
#include "stickslip/model/oscillator_model.hpp"
#include "stickslip/statistics_schema.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <utility>

namespace stickslip {

// The histogram of each binned quantity on [0, upper end of its range rule].
point_statistics::point_statistics(const model_parameters& p, const histogram_spec& h,
                                   bool family, bool stationary_start_, bool means_only_)
    : point_statistics(p, h, family, stationary_start_, means_only_, family || means_only_) {}

point_statistics::point_statistics(const model_parameters& p, const histogram_spec& h,
                                   bool family, bool stationary_start_, bool means_only_,
                                   bool causal_score) {
  causal_score_kept = causal_score;
  expected_switches = p.switch_rate * p.window;
  stationary_start = stationary_start_;
  family_statistics = family;
  means_only = means_only_;
  if (p.belt_rates.size() == 2) belt_rates = {p.belt_rates[0], p.belt_rates[1]};
  if (!p.belt_generator.empty()) {
    generator = p.belt_generator;
    if (stationary_start) generator_start_terms = stationary_score_terms(generator);
    for (const auto& q : quantities())
      if (q.generator_score) (this->*q.generator_score).assign(generator.size(), {});
  }
  for (const auto& q : quantities())
    if (q.density)
      this->*q.density =
          histogram(histogram_lower(q.range, p, h), histogram_upper(q.range, p, h), h.bins);
  for (const auto& l : level_quantities()) (this->*l.moments).assign(p.levels().size(), {});
  // The joint histograms pair each stick with its onset position, which only
  // the family statistics collect: without them they would stay zero, so
  // they are not allocated ((bins + 2)^2 cells each, 21 KB at 50 bins, in
  // every unit and point).
  if (family && !means_only)
    for (const auto& j : joint_histograms())
      this->*j.counts = histogram2d(this->*quantity_table[j.x].density,
                                    this->*quantity_table[j.y].density);
}

void point_statistics::select_survival(const survival_spec& g) {
  for (const auto& l : survival_laws()) this->*l.counts = survival_counts(g.*l.upper, g.bins);
}

void point_statistics::select_observe_times(const std::vector<double>& times, std::size_t levels) {
  observed = times.empty() ? time_statistics{} : time_statistics(times, levels);
}

namespace {

// A two-level belt alternates: of its N switches, ceil(N/2) leave the start
// level and floor(N/2) the other. The jumps out of the first and the second
// level.
std::array<std::uint64_t, 2> two_level_jumps(std::size_t start_level,
                                             std::uint64_t switches) noexcept {
  const std::uint64_t out_first = start_level == 0 ? (switches + 1) / 2 : switches / 2;
  return {out_first, switches - out_first};
}

}  // namespace

std::array<double, 2> belt_rate_scores(const std::array<double, 2>& rates,
                                       std::size_t start_level, std::uint64_t switches,
                                       const std::array<double, 2>& time,
                                       bool stationary_start) noexcept {
  const auto out = two_level_jumps(start_level, switches);
  std::array<double, 2> k{};
  const double total = rates[0] + rates[1];
  for (std::size_t j = 0; j < 2; ++j) {
    k[j] = static_cast<double>(out[j]) - rates[j] * time[j];
    if (stationary_start)
      k[j] += start_level == j ? -rates[j] / total : rates[1 - j] / total;
  }
  return k;
}

std::vector<double> stationary_score_terms(const std::vector<double>& generator) {
  const auto n = static_cast<std::size_t>(std::lround(std::sqrt(static_cast<double>(generator.size()))));
  markov_belt belt{std::vector<double>(n, 0.0), generator};
  for (std::size_t i = 0; i < n; ++i) belt.levels[i] = static_cast<double>(i);  // only Q counts
  const std::vector<double> pi = stationary_law(belt);
  std::vector<double> terms(n * n * n, 0.0);  // [s0 n^2 + i n + j]
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      const double q = generator[i * n + j];
      if (i == j || !(q > 0.0)) continue;
      const std::vector<double> dpi = stationary_law_derivative(belt, i, j);
      for (std::size_t s0 = 0; s0 < n; ++s0) terms[s0 * n * n + i * n + j] = q * dpi[s0] / pi[s0];
    }
  return terms;
}

void belt_generator_scores(const std::vector<double>& generator, std::size_t start_level,
                           const std::vector<std::uint32_t>& jumps,
                           const std::vector<double>& level_time,
                           const std::vector<double>* stationary_terms,
                           std::vector<double>& k) noexcept {
  const std::size_t n = level_time.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      const double q = generator[i * n + j];
      double& kij = k[i * n + j];
      if (i == j || !(q > 0.0)) {
        kij = 0.0;
        continue;
      }
      kij = static_cast<double>(jumps[i * n + j]) - q * level_time[i];
      if (stationary_terms) kij += (*stationary_terms)[start_level * n * n + i * n + j];
    }
}

namespace {

// One row of the schema, resolved at compile time (the row's value function
// is inlined: this runs once per realization).
template <std::size_t I>
void add_quantity(point_statistics& s, const realization_samples& in, double window) noexcept {
  constexpr const quantity_info& q = quantity_table[I];
  if constexpr (I >= paper_quantity_count) {
    if (!s.family_statistics) return;
  }
  const realization_record& r = in.record;
  mean_variance& moments = s.*q.moments;
  if constexpr (!per_realization(q.sampled)) {
    if (s.means_only) return;
  }
  if constexpr (per_realization(q.sampled)) {
    if constexpr (q.sampled == sampling::per_realization_with_stick) {
      if (!has_first_stick(r)) return;
    }
    const double x = q.value(r, window);
    moments.add(x);
    if constexpr (q.score != nullptr)
      (s.*q.score).add(x, static_cast<double>(r.events.belt_switches) - s.expected_switches);
    if constexpr (q.density != nullptr) {
      if (!s.means_only) (s.*q.density).add(x);
    }
  } else {
    const auto& xs = q.sampled == sampling::per_stick         ? in.sticks
                     : q.sampled == sampling::per_stick_onset ? in.onsets
                                                              : in.slips;
    moments.add_batch(xs.data(), xs.data() + xs.size());
    if constexpr (q.density != nullptr) (s.*q.density).add_all(xs.data(), xs.data() + xs.size());
  }
}

// The generator scores K_ij of one realization against its per-realization
// values (belt_generator_scores). Two levels alternate, so their jumps
// follow from N and the start; on more, the observer counts them (none
// without the family statistics: then nothing is added).
void add_generator_scores(point_statistics& s, const realization_samples& in, double window) {
  const std::size_t n = in.level_fractions.size();
  if (s.generator.empty() || s.generator.size() != n * n) return;
  const realization_record& r = in.record;
  const std::size_t start = level_of_belt_start(r.belt_start);
  thread_local std::vector<double> k, time;
  thread_local std::vector<std::uint32_t> alternating(4);
  if (n == 2) {
    const auto out = two_level_jumps(start, r.events.belt_switches);
    alternating = {0, static_cast<std::uint32_t>(out[0]), static_cast<std::uint32_t>(out[1]), 0};
  }
  const auto& jumps = n == 2 ? alternating : in.jumps;
  if (jumps.size() != n * n) return;
  k.resize(n * n);
  time.resize(n);
  for (std::size_t i = 0; i < n; ++i) time[i] = in.level_fractions[i] * window;
  belt_generator_scores(s.generator, start, jumps, time,
                        s.stationary_start ? &s.generator_start_terms : nullptr, k);
  for (const auto& q : quantities())
    if (q.generator_score) {
      auto& m = s.*q.generator_score;
      const double x = q.value(r, window);
      for (std::size_t ij = 0; ij < m.size(); ++ij)
        if (ij / n != ij % n && s.generator[ij] > 0.0) m[ij].add(x, k[ij]);
    }
}

}  // namespace

// Each quantity's samples go to its own accumulators in realization order, so
// the bits depend only on the samples' order, not on the order of the rows.
// Per-realization values go in one at a time (Welford); the pooled D_i and
// H_i of a realization as one batch (mean_variance::add_batch).
// The level fractions one realization at a time per level (Welford); every
// stick's (D_i, X_i) to the joint histograms.
void point_statistics::add(const realization_samples& in, double window) {
  const realization_record& r = in.record;
  // The rates and fractions are over the observed window [T, t_a]
  // (burn_in.hpp); the scores of the belt's path over all of [0, t_a].
  const double window_seen = in.observed_window > 0.0 ? in.observed_window : window;
  ++realizations;
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (add_quantity<I>(*this, in, window_seen), ...);
  }(std::make_index_sequence<quantity_table.size()>{});
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    ((counter_table[I].of(*this) += counter_table[I].increment(r)), ...);
  }(std::make_index_sequence<counter_table.size()>{});
  if (this->observed.selected()) {
    if (!in.observed_states || in.observed_states->size() != this->observed.times().size())
      throw error(exit_code::internal,
                  "internal error: a realization without its state at every observe time");
    this->observed.add(*in.observed_states);
  }
  for (const auto& l : survival_laws())
    if (auto& counts = this->*l.counts; counts.selected()) {
      const bool sticks = l.sampled == sampling::per_stick;
      const auto& xs = sticks ? in.sticks : in.slips;
      const bool cut = sticks ? in.last_stick_censored : in.last_slip_censored;
      // Kaplan-Meier over the episodes that start in the window: a
      // left-truncated stick (in progress at the burn-in) is left out.
      const std::size_t first = sticks && in.first_stick_left_truncated ? 1 : 0;
      for (std::size_t i = first; i < xs.size(); ++i) counts.add(xs[i], cut && i + 1 == xs.size());
    }
  if (keeps_causal_score() && expected_switches > 0.0 && belt_rates[0] == 0.0 &&
      generator.empty()) {
    // The causal score of R (causal_score_moments): M(t) = N(t)/lambda - t,
    // Z = int stick(t) M(t) dt / t_a, Y = int M(t) dt / t_a with
    // int_0^t_a N(t) dt = N t_a - (sum of the switch times).
    // With a burn-in T, Z is over [T, t_a] (/ (t_a - T)): stick(t) for t >= T
    // is still decided by the path up to t; Y, over [0, t_a], is still a
    // control of mean 0.
    const double lambda = expected_switches / window;
    const double z = (r.stick_switch_moment / lambda - r.stick_time_moment) / window_seen;
    const double n = static_cast<double>(r.events.belt_switches);
    const double y =
        ((n * window - r.events.switch_time_sum) / lambda - 0.5 * window * window) / window;
    stick_fraction_causal_score.add(z, y);
  }
  if (!family_statistics) return;
  // The scores of the rates and of the generator need the time at each
  // level over all of [0, t_a]; the level fractions of a burn-in are over
  // [T, t_a], so these derivatives are not estimated with a burn-in.
  const bool whole_window = window_seen == window;
  if (whole_window && belt_rates[0] > 0.0 && in.level_fractions.size() == 2) {
    const auto k = belt_rate_scores(
        belt_rates, level_of_belt_start(r.belt_start), r.events.belt_switches,
        {in.level_fractions[0] * window, in.level_fractions[1] * window}, stationary_start);
    for (const auto& q : quantities())
      if (q.rate_score)
        for (std::size_t j = 0; j < 2; ++j) (this->*q.rate_score)[j].add(q.value(r, window), k[j]);
  }
  if (whole_window) add_generator_scores(*this, in, window);
  for (const auto& l : level_quantities()) {
    auto& moments = this->*l.moments;
    for (std::size_t i = 0; i < moments.size(); ++i) moments[i].add(in.level_fractions[i]);
  }
  if (means_only) return;
  // A left-truncated stick has no onset: pair the onsets with the sticks
  // after it.
  const std::size_t truncated = in.first_stick_left_truncated && !in.sticks.empty() ? 1 : 0;
  auto samples_of = [&](sampling k) {
    return k == sampling::per_stick ? std::span<const double>(in.sticks).subspan(truncated)
                                    : std::span<const double>(in.onsets);
  };
  for (const auto& j : joint_histograms()) {
    if ((this->*j.counts).cells().empty()) continue;  // not allocated: no family statistics
    const auto xs = samples_of(j.x_sampled), ys = samples_of(j.y_sampled);
    const std::size_t n = std::min(xs.size(), ys.size());
    for (std::size_t i = 0; i < n; ++i) (this->*j.counts).add(xs[i], ys[i]);
  }
}

point_statistics& point_statistics::operator+=(const point_statistics& o) {
  for (const auto& q : quantities()) {
    this->*q.moments += o.*q.moments;
    if (q.score) this->*q.score += o.*q.score;
    if (q.rate_score)
      for (std::size_t j = 0; j < 2; ++j) (this->*q.rate_score)[j] += (o.*q.rate_score)[j];
    if (q.generator_score) {
      auto& mine = this->*q.generator_score;
      const auto& theirs = o.*q.generator_score;
      if (mine.empty()) mine.resize(theirs.size());  // a default-constructed merger
      if (mine.size() == theirs.size())
        for (std::size_t j = 0; j < mine.size(); ++j) mine[j] += theirs[j];
    }
    if (q.density) this->*q.density += o.*q.density;
  }
  for (const auto& l : level_quantities())
    for (std::size_t i = 0; i < (this->*l.moments).size(); ++i)
      (this->*l.moments)[i] += (o.*l.moments)[i];
  for (const auto& j : joint_histograms()) {
    auto& mine = this->*j.counts;
    const auto& theirs = o.*j.counts;
    if (mine.cells().empty())
      mine = theirs;  // a default-constructed merger, or neither holds one
    else if (!theirs.cells().empty())
      mine += theirs;
  }
  for (const auto& l : survival_laws()) this->*l.counts += o.*l.counts;
  if (!observed.selected())
    observed = o.observed;  // a default-constructed merger
  else if (o.observed.selected())
    observed += o.observed;
  if (generator.empty()) {
    generator = o.generator;
    generator_start_terms = o.generator_start_terms;
  }
  realizations += o.realizations;
  stick_fraction_causal_score += o.stick_fraction_causal_score;
  for (const auto& c : counters()) c.of(*this) += c.value(o);
  if (sensitivity.inputs() == 0)
    sensitivity = o.sensitivity;  // a default-constructed merger, or no design
  else if (o.sensitivity.inputs() == sensitivity.inputs())
    sensitivity += o.sensitivity;
  return *this;
}

void point_statistics::record_convergence() {
  convergence.push_back({realizations, stick_fraction.mean(), stick_fraction.ci95_half_width(),
                         stick_duration.mean(), stick_duration.ci95_half_width()});
}

realization_observer::realization_observer(const model_parameters& p, bool family,
                                           double burn_in,
                                           const std::vector<double>* observe_times)
    : window_(p.window - burn_in),
      kinetic_force_(p.mu_k() * p.mass * p.gravity),
      damping_(p.damping),
      mass_(p.mass),
      stiffness_(p.stiffness),
      family_(family),
      burn_in_(p, burn_in),
      level_time_(p.levels().size(), 0.0),
      level_fraction_(p.levels().size(), 0.0),
      jumps_(family && p.levels().size() > 2 && !p.belt_generator.empty()
                 ? p.levels().size() * p.levels().size()
                 : 0,
             0) {
  if (observe_times && !observe_times->empty())
    sampler_ = state_sampler(*observe_times, p.levels(), p.window, p.mass, p.stiffness);
}

void realization_observer::reserve_episodes(const model_parameters& p) {
  // So that the lists do not grow by doubling in every observer of every
  // work unit (the lane engine makes 64 per unit). An estimate, not a
  // bound: on the paper's belt about one stick and one slip per switch,
  // whose count is Poisson with mean rate * t_a; four standard deviations
  // over it, at most 4,096 each. (Periodic stick-slip at a steady belt, or a
  // generator's faster rates, can have more: the lists then grow as before.)
  // 6,400 points of 100 realizations: ~4 % less CPU.
  double rate = p.switch_rate;
  for (const double r : p.belt_rates) rate = std::max(rate, r);
  const double expected = rate * p.window;
  if (std::isfinite(expected) && expected > 0.0) {
    const auto n = static_cast<std::size_t>(
        std::min(expected + 4.0 * std::sqrt(expected) + 8.0, 4096.0));
    sticks_.reserve(n);
    slips_.reserve(n);
    if (family_) onsets_.reserve(n);
  }
}

void realization_observer::reset(std::uint64_t realization, double x0, double xdot0, int belt) {
  total_stick_ = slip_travel_ = damping_work_ = 0;
  std::fill(level_time_.begin(), level_time_.end(), 0.0);
  std::fill(jumps_.begin(), jumps_.end(), 0u);
  last_level_ = static_cast<std::size_t>(-1);
  onsets_.clear();
  rec_ = realization_record{};
  rec_.realization = realization;
  rec_.x0 = x0;
  rec_.xdot0 = xdot0;
  rec_.belt_start = belt;
  sticks_.clear();
  slips_.clear();
  stick_cut_ = slip_cut_ = stick_left_truncated_ = false;
  sampler_.reset();
}

void realization_observer::finish() noexcept {
  rec_.stick_fraction = total_stick_ / window_;
  rec_.friction_power = kinetic_force_ * slip_travel_ / window_;
  rec_.damping_power = damping_work_ / window_;
  for (std::size_t i = 0; i < level_time_.size(); ++i)
    level_fraction_[i] = level_time_[i] / window_;
}

}  // namespace stickslip
