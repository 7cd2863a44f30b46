// The identity of the statistics schema and the histogram range rules (the
// table itself is in statistics_schema.hpp).
#include "stickslip/statistics_schema.hpp"

#include <algorithm>
#include <array>
#include <string_view>

namespace stickslip {
namespace {

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
