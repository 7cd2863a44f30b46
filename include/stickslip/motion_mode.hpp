// The two modes of motion of the block: stuck to the belt (x' = v) or
// slipping over it. The event steps (event_physics.hpp) decide between them;
// episodes and segments (episode.hpp) carry them.
#pragma once

namespace stickslip {

enum class mode : unsigned char { stick, slip };

inline constexpr const char* to_string(mode m) noexcept {
  return m == mode::stick ? "stick" : "slip";
}

}  // namespace stickslip
