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
  // The paper's model, however it is written, hashes its seven values as in
  // 0.1.0 (same streams, same bits).
  const bool paper = p.is_paper_model();
  const model_parameters q = paper ? paper_form(p) : p;
  for (double v : {q.mass, q.stiffness, q.gravity, q.friction_coefficient, q.belt_speed,
                   q.switch_rate, q.window})
    h = mix(h ^ std::bit_cast<std::uint64_t>(v));
  if (paper) return h;
  // The family: the resolved friction, damping and belt, after a separator
  // so that no family model shares a key with a paper model by construction.
  h = mix(h ^ 0x46414d494c59ULL);  // "FAMILY"
  for (double v : {p.mu_s(), p.mu_k(), p.damping}) h = mix(h ^ std::bit_cast<std::uint64_t>(v));
  const auto levels = p.levels();
  const auto q_matrix = p.generator();
  h = mix(h ^ levels.size());
  for (double v : levels) h = mix(h ^ std::bit_cast<std::uint64_t>(v));
  for (double v : q_matrix) h = mix(h ^ std::bit_cast<std::uint64_t>(v));
  return h;
}

}  // namespace stickslip
