// Uncertain parameters in a sweep spec (io/config.hpp: set_law, drop_law):
// the one place where flags, TOML keys and Python keywords turn a law into
// sweep_spec::uncertain.
#include <algorithm>
#include <iterator>
#include <string>

#include "stickslip/io/config.hpp"

namespace stickslip::io {
namespace {

// The canonical order: the recorded scalars in their table's order, then the
// belt levels v1..vN, then the rates r1, r2.
std::size_t law_rank(const std::string& symbol) {
  const auto* at = std::find_if(std::begin(recorded_parameter_names),
                                std::end(recorded_parameter_names),
                                [&](const char* s) { return symbol == s; });
  if (at != std::end(recorded_parameter_names))
    return static_cast<std::size_t>(at - std::begin(recorded_parameter_names));
  std::size_t index = 0;  // vI, rI (canonical symbols only)
  for (std::size_t i = 1; i < symbol.size() && index < 1'000; ++i)
    index = 10 * index + static_cast<std::size_t>(symbol[i] - '0');
  return (!symbol.empty() && symbol[0] == 'v' ? 1'000 : 1'000'000) + index;
}

// The base value of a scalar back to its default (model_parameters{}), as
// given: a law of mu leaves mu_s and mu_k as they are. A belt level or rate
// keeps its value, which to_toml writes in belt_levels or belt_rates as it is.
void reset_base_value(model_parameters& p, const std::string& symbol) {
  for (const auto& row : scalar_parameters)
    if (symbol == row.symbol) p.*row.field = model_parameters{}.*row.field;
}

}  // namespace

void sort_laws(std::vector<uncertain_parameter>& laws) {
  std::stable_sort(laws.begin(), laws.end(),
                   [](const uncertain_parameter& a, const uncertain_parameter& b) {
                     return law_rank(a.symbol) < law_rank(b.symbol);
                   });
}

void set_law(sweep_spec& s, const std::string& symbol, parameter_law law) {
  std::erase_if(s.axes, [&](const axis& a) { return canonical_symbol(a.name) == symbol; });
  drop_law(s, symbol);
  reset_base_value(s.base, symbol);
  s.uncertain.push_back({symbol, std::move(law)});
  sort_laws(s.uncertain);
}

void drop_law(sweep_spec& s, std::string_view symbol) {
  std::erase_if(s.uncertain, [&](const uncertain_parameter& u) { return u.symbol == symbol; });
}

const parameter_law* find_law(const sweep_spec& s, std::string_view symbol) noexcept {
  for (const auto& u : s.uncertain)
    if (u.symbol == symbol) return &u.law;
  return nullptr;
}

}  // namespace stickslip::io
