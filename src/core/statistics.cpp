#include "stickslip/statistics.hpp"

#include <algorithm>

namespace stickslip {

point_statistics::point_statistics(const model_parameters& p, const histogram_spec& h) {
  const double dmax = h.stick_duration_max > 0 ? h.stick_duration_max : p.max_stick_duration();
  const double hmax =
      h.slip_duration_max > 0 ? h.slip_duration_max : std::min(p.window, 5.0 / p.switch_rate);
  stick_fraction_hist = histogram(0.0, 1.0, h.bins);
  stick_duration_hist = histogram(0.0, dmax, h.bins);
  first_stick_duration_hist = histogram(0.0, dmax, h.bins);
  slip_duration_hist = histogram(0.0, hmax, h.bins);
}

void point_statistics::add(const realization_record& r, const std::vector<double>& sticks,
                           const std::vector<double>& slips, double window) {
  ++realizations;
  stick_fraction.add(r.stick_fraction);
  stick_fraction_hist.add(r.stick_fraction);
  sticks_per_time.add(r.sticks / window);
  slips_per_time.add(r.slips / window);
  stick_duration.add_batch(sticks.data(), sticks.data() + sticks.size());
  for (double d : sticks) stick_duration_hist.add(d);
  slip_duration.add_batch(slips.data(), slips.data() + slips.size());
  for (double h : slips) slip_duration_hist.add(h);
  if (r.sticks == 0) {
    ++no_stick;
  } else {
    first_stick_duration.add(r.first_stick_duration);
    first_stick_duration_hist.add(r.first_stick_duration);
    if (r.first_stick_censored) ++first_stick_censored;
  }
  events += r.events;
}

point_statistics& point_statistics::operator+=(const point_statistics& o) {
  stick_fraction += o.stick_fraction;
  sticks_per_time += o.sticks_per_time;
  slips_per_time += o.slips_per_time;
  stick_duration += o.stick_duration;
  first_stick_duration += o.first_stick_duration;
  slip_duration += o.slip_duration;
  stick_fraction_hist += o.stick_fraction_hist;
  stick_duration_hist += o.stick_duration_hist;
  first_stick_duration_hist += o.first_stick_duration_hist;
  slip_duration_hist += o.slip_duration_hist;
  realizations += o.realizations;
  no_stick += o.no_stick;
  first_stick_censored += o.first_stick_censored;
  events += o.events;
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
