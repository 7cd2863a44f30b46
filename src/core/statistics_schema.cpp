// The table of statistics (see statistics_schema.hpp). The order of the rows
// is the order of the serialized accumulators and of the output columns.
#include "stickslip/statistics_schema.hpp"

#include <algorithm>
#include <array>
#include <string_view>

namespace stickslip {
namespace {

using ps = point_statistics;
using rec = const realization_record&;

constexpr std::array<quantity_info, 6> quantity_table{{
    {"stick_fraction", "R", "R", "1", "stick fraction",
     "total stick time in [0, t_a] divided by t_a, one value per realization", "realizations",
     sampling::per_realization, [](rec r, double) noexcept { return r.stick_fraction; },
     &ps::stick_fraction, &ps::stick_fraction_hist, histogram_range::unit_interval},
    {"sticks_per_time", "sticks_per_time", "S_T/t_a", "1/s", "stick rate",
     "number of sticks of positive length beginning in [0, t_a) (a stick cut off by t_a "
     "counts), divided by t_a, one value per realization",
     "realizations", sampling::per_realization,
     [](rec r, double window) noexcept { return r.sticks / window; }, &ps::sticks_per_time,
     nullptr, histogram_range::none},
    {"slips_per_time", "slips_per_time", "S_L/t_a", "1/s", "slip rate",
     "number of slips beginning after the first stick (the slip before the first stick is "
     "not counted), divided by t_a, one value per realization",
     "realizations", sampling::per_realization,
     [](rec r, double window) noexcept { return r.slips / window; }, &ps::slips_per_time,
     nullptr, histogram_range::none},
    {"stick_duration", "stick_duration", "D", "s", "stick duration",
     "duration D_i of every stick, pooled over all sticks of all realizations (a stick cut "
     "off by t_a enters clipped)",
     "sticks, over all realizations", sampling::per_stick, nullptr, &ps::stick_duration,
     &ps::stick_duration_hist, histogram_range::stick_duration},
    {"first_stick_duration", "first_stick_duration", "D_1", "s", "first stick duration",
     "duration of the first stick, over the realizations that have a stick (see "
     "no_stick_count); it may be censored by t_a (see first_stick_censored_count)",
     "realizations with at least one stick", sampling::per_realization_with_stick,
     [](rec r, double) noexcept { return r.first_stick_duration; }, &ps::first_stick_duration,
     &ps::first_stick_duration_hist, histogram_range::stick_duration},
    {"slip_duration", "slip_duration", "H", "s", "slip duration",
     "duration H_i of every counted slip (those beginning after the first stick), pooled "
     "over all realizations",
     "counted slips, over all realizations", sampling::per_counted_slip, nullptr,
     &ps::slip_duration, &ps::slip_duration_hist, histogram_range::slip_duration},
}};

constexpr std::array<counter_info, 6> counter_table{{
    {"no_stick_count", "no_stick", nullptr, "no-stick realizations",
     "realizations with no stick of positive length in [0, t_a) (no D_1)",
     [](rec r) noexcept -> std::uint64_t { return r.sticks == 0; },
     [](ps& s) noexcept -> std::uint64_t& { return s.no_stick; }},
    {"first_stick_censored_count", "first_stick_censored", nullptr, "censored first sticks",
     "realizations whose first stick was still going on at t_a (D_1 clipped)",
     [](rec r) noexcept -> std::uint64_t { return r.sticks > 0 && r.first_stick_censored; },
     [](ps& s) noexcept -> std::uint64_t& { return s.first_stick_censored; }},
    {"belt_switches", "belt_switches", "events", "belt switches",
     "belt direction switches, summed over realizations",
     [](rec r) noexcept { return r.events.belt_switches; },
     [](ps& s) noexcept -> std::uint64_t& { return s.events.belt_switches; }},
    {"stick_onsets", "stick_onsets", "events", "stick onsets",
     "transitions slip -> stick, summed over realizations",
     [](rec r) noexcept { return r.events.stick_onsets; },
     [](ps& s) noexcept -> std::uint64_t& { return s.events.stick_onsets; }},
    {"stick_breaks", "stick_breaks", "events", "stick breaks",
     "transitions stick -> slip, summed over realizations",
     [](rec r) noexcept { return r.events.stick_breaks; },
     [](ps& s) noexcept -> std::uint64_t& { return s.events.stick_breaks; }},
    {"slip_reversals", "slip_reversals", "events", "slip reversals",
     "reversals of the slip direction without sticking, summed over realizations",
     [](rec r) noexcept { return r.events.slip_reversals; },
     [](ps& s) noexcept -> std::uint64_t& { return s.events.slip_reversals; }},
}};

struct fnv1a {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  void add(std::string_view s) {
    for (char c : s) byte(static_cast<unsigned char>(c));
    byte(0);  // separator: "ab","c" differs from "a","bc"
  }
  void byte(unsigned char c) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
};

}  // namespace

std::span<const quantity_info> quantities() noexcept { return quantity_table; }
std::span<const counter_info> counters() noexcept { return counter_table; }

std::uint64_t statistics_schema_id() noexcept {
  static const std::uint64_t id = [] {
    fnv1a f;
    for (const auto& q : quantity_table) {
      f.add("quantity");
      f.add(q.name);
      f.byte(static_cast<unsigned char>(q.sampled));
      f.byte(static_cast<unsigned char>(q.range));
    }
    for (const auto& c : counter_table) {
      f.add("counter");
      f.add(c.name);
    }
    return f.h;
  }();
  return id;
}

double histogram_upper(histogram_range range, const model_parameters& p,
                       const histogram_spec& h) noexcept {
  switch (range) {
    case histogram_range::unit_interval: return 1.0;
    case histogram_range::stick_duration:
      return h.stick_duration_max > 0 ? h.stick_duration_max : p.max_stick_duration();
    case histogram_range::slip_duration:
      return h.slip_duration_max > 0 ? h.slip_duration_max
                                     : std::min(p.window, 5.0 / p.switch_rate);
    case histogram_range::none: break;
  }
  return 1.0;
}

}  // namespace stickslip
