#include "stickslip/serial_bytes.hpp"

#include <array>
#include <fmt/format.h>

#include "stickslip/parameters.hpp"
#include "stickslip/statistics_schema.hpp"

namespace stickslip {

error detail::corrupt(std::string_view what) {
  return error(exit_code::io_failure, fmt::format("corrupt serialized data: {}", what));
}

std::uint64_t layout_id() noexcept {
  static const std::uint64_t id = [] {
    std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a 64
    const auto byte = [&h](unsigned char c) {
      h ^= c;
      h *= 0x100000001b3ULL;
    };
    const auto schema = statistics_schema_id();
    for (int i = 0; i < 8; ++i) byte(static_cast<unsigned char>(schema >> (8 * i)));
    for (const char* name : recorded_parameter_names) {
      for (const char* c = name; *c; ++c) byte(static_cast<unsigned char>(*c));
      byte(0);
    }
    for (const char* c = "belt_levels|belt_rates|belt_generator"; *c; ++c)
      byte(static_cast<unsigned char>(*c));
    return h;
  }();
  return id;
}

std::uint32_t crc32(std::string_view data, std::uint32_t crc) noexcept {
  static constexpr auto table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  crc = ~crc;
  for (char ch : data) crc = table[(crc ^ static_cast<std::uint8_t>(ch)) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

}  // namespace stickslip
