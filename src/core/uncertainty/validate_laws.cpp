// validate_laws (uncertainty/parameter_law.hpp): whether every draw of the
// uncertain parameters gives a valid model. Checked on the laws' supports
// (the mathematical ones, so that a normal for a positive quantity is
// refused even though no double draw reaches 0), then, as a backstop, on
// the model at the extreme values a draw can take (the quantiles of the
// smallest and largest open uniform).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "stickslip/error.hpp"
#include "stickslip/random_stream.hpp"
#include "stickslip/uncertainty/parameter_law.hpp"
#include "stickslip/uncertainty/uncertain_draws.hpp"

namespace stickslip {
namespace {

// The domain of each symbol (parameters.hpp, domain_of): rates and the
// paper's parameters are > 0, damping >= 0, belt levels any finite value.
enum class domain : unsigned char { positive, nonnegative, finite };

domain law_domain(const std::string& symbol) {
  switch (domain_of(symbol)) {
    case parameter_domain::non_negative: return domain::nonnegative;
    case parameter_domain::any: return domain::finite;
    default: return domain::positive;
  }
}

error invalid_law(const uncertain_parameter& u, const std::string& problem) {
  return {exit_code::invalid_input,
          fmt::format("{}: {} {}", flag_of(u.symbol), to_string(u.law), problem)};
}

void check_domain(const uncertain_parameter& u) {
  const auto [low, high] = support(u.law);
  const bool closed_low =
      u.law.family != law_family::lognormal && u.law.family != law_family::gamma;
  switch (law_domain(u.symbol)) {
    case domain::positive:
      if (low < 0.0 || (low == 0.0 && closed_low))
        throw invalid_law(
            u, fmt::format("can give values <= 0; {} must be > 0 ({})", u.symbol,
                           u.law.family == law_family::normal
                               ? "use truncnormal, lognormal or gamma"
                               : "use a law with min > 0, or lognormal, gamma or loguniform"));
      break;
    case domain::nonnegative:
      if (low < 0.0)
        throw invalid_law(u, fmt::format("can give values < 0; {} must be >= 0 (use a law with "
                                         "min >= 0, or lognormal or gamma)",
                                         u.symbol));
      break;
    case domain::finite:
      break;
  }
  (void)high;
}

// Symbols whose law would be overwritten or would override a value given
// otherwise (overridden_by_base, the rule of a grid axis too), and belt
// levels or rates the belt does not have.
void check_has_effect(const model_parameters& base, const uncertain_parameter& u) {
  std::string why = overridden_by_base(base, u.symbol);
  if (u.symbol[0] == 'v' && u.symbol != "V") {
    const std::size_t i = std::stoul(u.symbol.substr(1));
    if (i > base.levels().size())
      why = "the belt has fewer levels";
  }
  if (u.symbol[0] == 'r' && (base.levels().size() != 2 || !base.belt_generator.empty()))
    why = "r1, r2 are the rates of a two-level belt without a generator matrix";
  if (u.symbol[0] == 'r' && u.symbol != "r1" && u.symbol != "r2") why = "only r1 and r2 exist";
  if (!why.empty()) throw invalid_law(u, fmt::format("has no effect on the model: {}", why));
}

// mu_k <= mu_s for every draw: the largest mu_k a draw can give against the
// smallest mu_s (each the law's support, or the resolved value when fixed).
void check_friction_order(const model_parameters& base,
                          std::span<const uncertain_parameter> laws) {
  const uncertain_parameter* s = nullptr;
  const uncertain_parameter* k = nullptr;
  for (const auto& u : laws) {
    if (u.symbol == "mu_s") s = &u;
    if (u.symbol == "mu_k") k = &u;
  }
  if (!s && !k) return;
  const double s_low = s ? support(s->law).first : base.mu_s();
  const double k_high = k ? support(k->law).second : base.mu_k();
  if (!(k_high > s_low)) return;
  const std::string rule = "mu_k must be <= mu_s";
  if (s && k)
    throw invalid_law(*k, fmt::format("can exceed {}: {}; {} (make mu_k's largest value <= "
                                      "mu_s's smallest)",
                                      flag_of("mu_s"), to_string(s->law), rule));
  if (k)
    throw invalid_law(*k, fmt::format("can exceed mu_s = {} (its fixed value); {} (give mu_k a "
                                      "law with max <= {}, or a larger --mu-s)",
                                      s_low, rule, s_low));
  throw invalid_law(*s, fmt::format("can fall below mu_k = {} (its fixed value); {} (give mu_s a "
                                    "law with min >= {}, or a smaller --mu-k)",
                                    k_high, rule, k_high));
}

// The model at the extreme draws: every combination of each law's smallest
// and largest value for up to 10 laws (1024 models), else each law alone.
void check_extreme_models(const model_parameters& base,
                          std::span<const uncertain_parameter> laws) {
  std::vector<double> low(laws.size()), high(laws.size()), median(laws.size());
  for (std::size_t i = 0; i < laws.size(); ++i) {
    low[i] = smallest_draw(laws[i].law);
    high[i] = largest_draw(laws[i].law);
    median[i] = quantile(laws[i].law, 0.5);
  }
  auto check = [&](const std::vector<double>& values) {
    try {
      validate(with_values(base, laws, values));
    } catch (const error& e) {
      std::string at;
      for (std::size_t i = 0; i < laws.size(); ++i)
        at += fmt::format("{}{} = {}", i ? ", " : "", laws[i].symbol, values[i]);
      throw error(exit_code::invalid_input,
                  fmt::format("{}: {} can give a model that is not valid: at {} (values the "
                              "laws can draw): {}",
                              flag_of(laws.front().symbol), to_string(laws.front().law), at,
                              e.what()));
    }
  };
  std::vector<double> values(laws.size());
  if (laws.size() <= 10) {
    for (std::size_t corner = 0; corner < (std::size_t{1} << laws.size()); ++corner) {
      for (std::size_t i = 0; i < laws.size(); ++i) values[i] = (corner >> i) & 1 ? high[i] : low[i];
      check(values);
    }
    return;
  }
  for (std::size_t i = 0; i < laws.size(); ++i) {
    values = median;
    values[i] = low[i];
    check(values);
    values[i] = high[i];
    check(values);
  }
}

}  // namespace

void validate_laws(const model_parameters& base, std::span<const uncertain_parameter> laws,
                   std::span<const std::string> axis_symbols) {
  std::set<std::string> seen, axes;
  for (const auto& a : axis_symbols)
    axes.insert(is_parameter_symbol(a) ? canonical_symbol(a) : a);
  for (const auto& u : laws) {
    if (!is_parameter_symbol(u.symbol))
      throw error(exit_code::invalid_input,
                  fmt::format("{}: {}: unknown parameter; allowed: {}", u.symbol,
                              to_string(u.law), allowed_parameter_names()));
    if (u.symbol != canonical_symbol(u.symbol))
      throw invalid_law(u, fmt::format("names {} by its long name; use the symbol {}", u.symbol,
                                       canonical_symbol(u.symbol)));
    if (!seen.insert(u.symbol).second)
      throw invalid_law(u, "is the second law for this parameter; give each parameter one law");
    if (axes.contains(u.symbol))
      throw invalid_law(u, "is given for a parameter that is also a grid axis; give either a "
                           "law or a grid");
    const auto refinements = refinements_of(u.symbol);
    for (const auto& other : refinements)
      if (axes.contains(other) ||
          std::any_of(laws.begin(), laws.end(), [&](const auto& o) { return o.symbol == other; })) {
        const auto both = fmt::format("{}", fmt::join(refinements, " and "));
        throw invalid_law(u, fmt::format("is given together with {}: {} sets {} both; give {} "
                                         "instead",
                                         flag_of(other), u.symbol, both, both));
      }
    check_has_effect(base, u);
    check_domain(u);
  }
  check_friction_order(base, laws);
  if (!laws.empty()) check_extreme_models(base, laws);
}

}  // namespace stickslip
