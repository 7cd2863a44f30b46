#include "stickslip/random_stream.hpp"

#include <bit>

namespace stickslip {
namespace {
// splitmix64 finalizer (Steele, Lea, Flood 2014): a bijective 64-bit mixer.
constexpr std::uint64_t mix(std::uint64_t z) noexcept {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
}  // namespace

std::uint64_t point_key(const model_parameters& p) noexcept {
  std::uint64_t h = 0x5354494b4b534c50ULL;  // "STICKSLP"
  for (double v : {p.mass, p.stiffness, p.gravity, p.friction_coefficient, p.belt_speed,
                   p.switch_rate, p.window})
    h = mix(h ^ std::bit_cast<std::uint64_t>(v));
  return h;
}

}  // namespace stickslip
