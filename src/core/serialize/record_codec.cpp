// The codec of a realization's raw record (point_accumulators.hpp): its fields in the
// order of the record table (record_schema.hpp), each in its own width (the
// belt start as a signed byte, a flag as a byte), then the drawn values.
#include <fmt/format.h>

#include <type_traits>

#include "serialize/codecs.hpp"
#include "stickslip/record_schema.hpp"

namespace stickslip::serial {
namespace {

void put_field(writer& w, std::uint64_t v) { w.u64(v); }
void put_field(writer& w, std::uint32_t v) { w.u32(v); }
void put_field(writer& w, double v) { w.f64(v); }
void put_field(writer& w, int v) { w.u8(static_cast<std::uint8_t>(static_cast<std::int8_t>(v))); }
void put_field(writer& w, bool v) { w.u8(v ? 1 : 0); }
void get_field(reader& r, std::uint64_t& v, const char* name) { v = r.u64(name); }
void get_field(reader& r, std::uint32_t& v, const char* name) { v = r.u32(name); }
void get_field(reader& r, double& v, const char* name) { v = r.f64(name); }
void get_field(reader& r, int& v, const char* name) { v = static_cast<std::int8_t>(r.u8(name)); }
void get_field(reader& r, bool& v, const char* name) { v = r.boolean(name); }

}  // namespace

std::size_t record_bytes() noexcept {
  static const std::size_t n = [] {
    std::size_t bytes = 8;  // the count of drawn values
    realization_record x;
    for (const auto& field : record_table)
      bytes += visit_field(field, x, [](const auto& v) -> std::size_t {
        using type = std::remove_cvref_t<decltype(v)>;
        return std::is_same_v<type, int> || std::is_same_v<type, bool> ? 1 : sizeof(type);
      });
    return bytes;
  }();
  return n;
}

void put(writer& w, const realization_record& x) {
  for (const auto& field : record_table)
    visit_field(field, x, [&](const auto& v) { put_field(w, v); });
  put_values(w, x.drawn_values);
}
realization_record get_record(reader& r) {
  realization_record x;
  for (const auto& field : record_table)
    visit_field(field, x, [&](auto& v) { get_field(r, v, field.name); });
  // +1 / -1 on a two-level belt, the level number 1..n on more levels
  // (model_realization.hpp, recorded_belt_start).
  if (x.belt_start == 0 || x.belt_start < -1)
    throw corrupt(fmt::format("record belt start {} is not +1, -1 or a level number",
                              x.belt_start));
  x.drawn_values = get_values(r, "record drawn values");
  return x;
}

}  // namespace stickslip::serial
