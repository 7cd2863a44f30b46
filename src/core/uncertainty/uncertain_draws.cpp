// The values an uncertain realization draws (uncertainty/uncertain_draws.hpp).
#include "stickslip/uncertainty/uncertain_draws.hpp"

#include <bit>

#include "fnv1a.hpp"
#include "stickslip/random_stream.hpp"

namespace stickslip {
namespace {

// splitmix64 finalizer (Steele, Lea, Flood 2014), as in point_key.
constexpr std::uint64_t mix(std::uint64_t z) noexcept {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// FNV-1a of a text (the canonical law text and its symbol).
constexpr std::uint64_t text_hash(std::string_view s) noexcept { return detail::fnv1a_of(s); }

}  // namespace

std::vector<double> uncertain_uniforms(std::uint64_t seed, std::uint64_t key,
                                       std::uint64_t realization, std::size_t offset,
                                       std::size_t count) {
  std::vector<double> u(count);
  random_stream rs(seed, key, realization, substream::uncertain_parameters);
  // Word w is word w % 4 of block w / 4; blocks come in order from 0.
  random_stream::philox::ctr_type block{};
  std::size_t blocks_drawn = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t word = offset + i;
    while (blocks_drawn <= word / 4) {
      block = rs.next_block();
      ++blocks_drawn;
    }
    u[i] = random_stream::open_uniform(block.v[word % 4]);
  }
  return u;
}

model_parameters with_values(const model_parameters& base,
                             std::span<const uncertain_parameter> laws,
                             std::span<const double> values) {
  model_parameters p = base;
  for (std::size_t i = 0; i < laws.size() && i < values.size(); ++i)
    set_parameter(p, laws[i].symbol, values[i]);
  return p;
}

std::vector<double> draw_values(std::span<const uncertain_parameter> laws, std::uint64_t seed,
                                std::uint64_t key, std::uint64_t realization,
                                std::size_t offset) {
  std::vector<double> v = uncertain_uniforms(seed, key, realization, offset, laws.size());
  for (std::size_t i = 0; i < laws.size(); ++i) v[i] = quantile(laws[i].law, v[i]);
  return v;
}

double smallest_draw(const parameter_law& law) {
  return quantile(law, random_stream::open_uniform(0));
}
double largest_draw(const parameter_law& law) {
  return quantile(law, random_stream::open_uniform(~std::uint64_t{0}));
}

model_parameters with_medians(const model_parameters& base,
                              std::span<const uncertain_parameter> laws) {
  std::vector<double> m(laws.size());
  for (std::size_t i = 0; i < laws.size(); ++i) m[i] = quantile(laws[i].law, 0.5);
  model_parameters p = with_values(base, laws, m);
  return p.is_paper_model() ? paper_form(p) : p;
}

std::vector<std::string> symbols_set_by_laws(std::span<const uncertain_parameter> laws) {
  std::vector<std::string> out;
  for (const auto& u : laws) {
    out.push_back(u.symbol);
    const auto refinements = refinements_of(u.symbol);
    out.insert(out.end(), refinements.begin(), refinements.end());
  }
  return out;
}

std::uint64_t uncertain_point_key(const model_parameters& base,
                                  std::span<const uncertain_parameter> laws) noexcept {
  // The base at the medians: its other values enter as in point_key, the
  // uncertain ones only through their laws' texts.
  std::uint64_t h = point_key(with_medians(base, laws));
  h = mix(h ^ 0x554e43455254ULL);  // "UNCERT": no point with laws shares a key with one without
  for (const auto& u : laws) {
    h = mix(h ^ text_hash(u.symbol));
    h = mix(h ^ text_hash(to_string(u.law)));
  }
  return h;
}

}  // namespace stickslip
