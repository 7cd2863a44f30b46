// The codec of a realization's raw record (statistics.hpp), field by field,
// with its event counts (episode.hpp).
#include "serialize/codecs.hpp"

#include <fmt/format.h>

namespace stickslip::serial {
namespace {

void put(writer& w, const event_counts& e) {
  w.u64(e.belt_switches);
  w.u64(e.stick_onsets);
  w.u64(e.stick_breaks);
  w.u64(e.slip_reversals);
  w.f64(e.switch_time_sum);
}
event_counts get_counts(reader& r) {
  event_counts e;
  e.belt_switches = r.u64("event counts");
  e.stick_onsets = r.u64("event counts");
  e.stick_breaks = r.u64("event counts");
  e.slip_reversals = r.u64("event counts");
  e.switch_time_sum = r.f64("switch time sum");
  return e;
}

}  // namespace

void put(writer& w, const realization_record& x) {
  w.u64(x.realization);
  w.f64(x.x0);
  w.f64(x.xdot0);
  w.u8(static_cast<std::uint8_t>(static_cast<std::int8_t>(x.belt_start)));
  w.u32(x.sticks);
  w.u32(x.slips);
  w.f64(x.stick_fraction);
  w.f64(x.first_stick_start);
  w.f64(x.first_stick_duration);
  w.u8(x.first_stick_censored ? 1 : 0);
  w.f64(x.friction_power);
  w.f64(x.damping_power);
  w.f64(x.stick_switch_moment);
  w.f64(x.stick_time_moment);
  put(w, x.events);
  put_values(w, x.drawn_values);
}
realization_record get_record(reader& r) {
  realization_record x;
  x.realization = r.u64("record");
  x.x0 = r.f64("record");
  x.xdot0 = r.f64("record");
  x.belt_start = static_cast<std::int8_t>(r.u8("record"));
  // +1 / -1 on a two-level belt, the level number 1..n on more levels
  // (model_realization.hpp, recorded_belt_start).
  if (x.belt_start == 0 || x.belt_start < -1)
    throw corrupt(fmt::format("record belt start {} is not +1, -1 or a level number",
                              x.belt_start));
  x.sticks = r.u32("record");
  x.slips = r.u32("record");
  x.stick_fraction = r.f64("record");
  x.first_stick_start = r.f64("record");
  x.first_stick_duration = r.f64("record");
  x.first_stick_censored = r.boolean("record censoring flag");
  x.friction_power = r.f64("record");
  x.damping_power = r.f64("record");
  x.stick_switch_moment = r.f64("record");
  x.stick_time_moment = r.f64("record");
  x.events = get_counts(r);
  x.drawn_values = get_values(r, "record drawn values");
  return x;
}

}  // namespace stickslip::serial
