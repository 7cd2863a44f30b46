#include "stickslip/statistics.hpp"

#include "stickslip/statistics_schema.hpp"

namespace stickslip {

// The histogram of each binned quantity on [0, upper end of its range rule].
point_statistics::point_statistics(const model_parameters& p, const histogram_spec& h) {
  for (const auto& q : quantities())
    if (q.density) this->*q.density = histogram(0.0, histogram_upper(q.range, p, h), h.bins);
}

// Each quantity's samples go to its own accumulators in realization order, so
// the bits depend only on the samples' order, not on the order of the rows.
// Per-realization values go in one at a time (Welford); the pooled D_i and
// H_i of a realization as one batch (mean_variance::add_batch).
void point_statistics::add(const realization_record& r, const std::vector<double>& sticks,
                           const std::vector<double>& slips, double window) {
  ++realizations;
  for (const auto& q : quantities()) {
    mean_variance& moments = this->*q.moments;
    histogram* density = q.density ? &(this->*q.density) : nullptr;
    switch (q.sampled) {
      case sampling::per_realization_with_stick:
        if (r.sticks == 0) break;
        [[fallthrough]];
      case sampling::per_realization: {
        const double x = q.value(r, window);
        moments.add(x);
        if (density) density->add(x);
        break;
      }
      case sampling::per_stick:
      case sampling::per_counted_slip: {
        const auto& xs = q.sampled == sampling::per_stick ? sticks : slips;
        moments.add_batch(xs.data(), xs.data() + xs.size());
        if (density)
          for (double x : xs) density->add(x);
        break;
      }
    }
  }
  for (const auto& c : counters()) c.of(*this) += c.increment(r);
}

point_statistics& point_statistics::operator+=(const point_statistics& o) {
  for (const auto& q : quantities()) {
    this->*q.moments += o.*q.moments;
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
