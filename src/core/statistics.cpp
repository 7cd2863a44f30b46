#include "stickslip/statistics.hpp"

#include "stickslip/statistics_schema.hpp"

#include <utility>

namespace stickslip {

// The histogram of each binned quantity on [0, upper end of its range rule].
point_statistics::point_statistics(const model_parameters& p, const histogram_spec& h)
    : expected_switches(p.switch_rate * p.window) {
  for (const auto& q : quantities())
    if (q.density) this->*q.density = histogram(0.0, histogram_upper(q.range, p, h), h.bins);
}

namespace {

// One row of the schema, resolved at compile time (the row's value function
// is inlined: this runs once per realization).
template <std::size_t I>
void add_quantity(point_statistics& s, const realization_record& r,
                  const std::vector<double>& sticks, const std::vector<double>& slips,
                  double window) noexcept {
  constexpr const quantity_info& q = quantity_table[I];
  mean_variance& moments = s.*q.moments;
  if constexpr (q.sampled == sampling::per_realization ||
                q.sampled == sampling::per_realization_with_stick) {
    if constexpr (q.sampled == sampling::per_realization_with_stick) {
      if (r.sticks == 0) return;
    }
    const double x = q.value(r, window);
    moments.add(x);
    if constexpr (q.score != nullptr)
      (s.*q.score).add(x, static_cast<double>(r.events.belt_switches) - s.expected_switches);
    if constexpr (q.density != nullptr) (s.*q.density).add(x);
  } else {
    const auto& xs = q.sampled == sampling::per_stick ? sticks : slips;
    moments.add_batch(xs.data(), xs.data() + xs.size());
    if constexpr (q.density != nullptr)
      for (double x : xs) (s.*q.density).add(x);
  }
}

}  // namespace

// Each quantity's samples go to its own accumulators in realization order, so
// the bits depend only on the samples' order, not on the order of the rows.
// Per-realization values go in one at a time (Welford); the pooled D_i and
// H_i of a realization as one batch (mean_variance::add_batch).
void point_statistics::add(const realization_record& r, const std::vector<double>& sticks,
                           const std::vector<double>& slips, double window) {
  ++realizations;
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (add_quantity<I>(*this, r, sticks, slips, window), ...);
  }(std::make_index_sequence<quantity_table.size()>{});
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    ((counter_table[I].of(*this) += counter_table[I].increment(r)), ...);
  }(std::make_index_sequence<counter_table.size()>{});
}

point_statistics& point_statistics::operator+=(const point_statistics& o) {
  for (const auto& q : quantities()) {
    this->*q.moments += o.*q.moments;
    if (q.score) this->*q.score += o.*q.score;
    if (q.density) this->*q.density += o.*q.density;
  }
  realizations += o.realizations;
  for (const auto& c : counters()) c.of(*this) += c.value(o);
  return *this;
}

void point_statistics::record_convergence() {
  convergence.push_back({realizations, stick_fraction.mean(), stick_fraction.ci95_half_width(),
                         stick_duration.mean(), stick_duration.ci95_half_width()});
}

void realization_observer::reset(std::uint64_t realization, double x0, double xdot0, int belt) {
  total_stick_ = 0;
  rec_ = realization_record{};
  rec_.realization = realization;
  rec_.x0 = x0;
  rec_.xdot0 = xdot0;
  rec_.belt_start = belt;
  sticks_.clear();
  slips_.clear();
}

void realization_observer::finish() noexcept { rec_.stick_fraction = total_stick_ / window_; }

}  // namespace stickslip
