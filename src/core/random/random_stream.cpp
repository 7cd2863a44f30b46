#include "stickslip/random_stream.hpp"

#include <array>
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
  // The rows in the order of their key positions: the paper's seven of q,
  // then the family's resolved values (mu_s of a model without one is mu).
  std::array<const parameter_info*, std::size(scalar_parameters)> rows{};
  for (const auto& row : scalar_parameters) rows[row.key_position] = &row;
  for (std::size_t i = 0; i < paper_parameter_count; ++i)
    h = mix(h ^ std::bit_cast<std::uint64_t>(q.*rows[i]->field));
  if (paper) return h;
  // The family: the resolved friction, damping and belt, after a separator
  // so that no family model shares a key with a paper model by construction.
  h = mix(h ^ 0x46414d494c59ULL);  // "FAMILY"
  for (std::size_t i = paper_parameter_count; i < rows.size(); ++i)
    h = mix(h ^ std::bit_cast<std::uint64_t>(resolved_value(p, *rows[i])));
  const auto levels = p.levels();
  const auto q_matrix = p.generator();
  h = mix(h ^ levels.size());
  for (double v : levels) h = mix(h ^ std::bit_cast<std::uint64_t>(v));
  for (double v : q_matrix) h = mix(h ^ std::bit_cast<std::uint64_t>(v));
  return h;
}

}  // namespace stickslip
