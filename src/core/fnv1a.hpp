// FNV-1a, 64 bit: the one hash of the identities the core computes (the
// serialized layout, the statistics schema, a sweep's fingerprint, the
// stream key of an uncertain parameter's law). Not a random stream: the
// draws hash with splitmix64 (random_stream.hpp). Private to the core.
#pragma once
#include <cstdint>
#include <string_view>

namespace stickslip::detail {

struct fnv1a {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  constexpr void byte(unsigned char c) noexcept {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  // The bytes of s, and nothing after them.
  constexpr void bytes(std::string_view s) noexcept {
    for (const char c : s) byte(static_cast<unsigned char>(c));
  }
  // The bytes of s and a 0 after them, so that "ab", "c" and "a", "bc" differ.
  constexpr void add(std::string_view s) noexcept {
    bytes(s);
    byte(0);
  }
  // The 8 bytes of x, least significant first.
  constexpr void u64(std::uint64_t x) noexcept {
    for (int i = 0; i < 8; ++i) byte(static_cast<unsigned char>(x >> (8 * i)));
  }
};

// The hash of the bytes of s.
[[nodiscard]] constexpr std::uint64_t fnv1a_of(std::string_view s) noexcept {
  fnv1a f;
  f.bytes(s);
  return f.h;
}

}  // namespace stickslip::detail
