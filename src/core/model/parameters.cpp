#include "stickslip/parameters.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdlib>

#include "stickslip/error.hpp"

namespace stickslip {
namespace {

// The indexed rows: a belt level vI and the rate rI of leaving level I.
constexpr parameter_info belt_level_info{"v", "belt-level", "belt velocity level v_I", "m/s",
                                         nullptr, parameter_domain::any};
constexpr parameter_info belt_rate_info{"r", "belt-rate",
                                        "rate of leaving belt level I (two-level belt)", "1/s"};

// "v3" -> 3 (prefix 'v'); 0 when `symbol` is not prefix + a positive integer.
std::size_t indexed(std::string_view symbol, char prefix) {
  if (symbol.size() < 2 || symbol[0] != prefix) return 0;
  std::size_t i = 0;
  const auto* end = symbol.data() + symbol.size();
  const auto [ptr, ec] = std::from_chars(symbol.data() + 1, end, i);
  if (ec != std::errc{} || ptr != end || symbol[1] == '0') return 0;
  return i;
}

// "mu_s (static friction)": a row as messages name it.
std::string message_name(const parameter_info& row) {
  std::string words = row.long_name;
  std::replace(words.begin(), words.end(), '-', ' ');
  return fmt::format("{} ({})", row.symbol, words);
}

const parameter_info* row_of(std::string_view name) {
  for (const auto& row : scalar_parameters)
    if (name == row.symbol || name == row.long_name) return &row;
  return nullptr;
}

void require_positive_finite(const char* name, double value) {
  if (!std::isfinite(value) || value <= 0.0)
    throw invalid_parameter(name, value, "finite and > 0");
}

// The closed form squares products such as (omega y)^2 and x'^2: magnitudes
// beyond this range overflow or underflow to inf/0 and would yield NaN event
// times (found by fuzz_simulator). No physical study comes near it.
void require_representable(const char* name, double value) {
  require_positive_finite(name, value);
  if (value < min_magnitude || value > max_magnitude)
    throw invalid_parameter(name, value, "between 1e-60 and 1e60");
}

// A row's checks: its name is spelled out only for a refusal (validate runs
// for every point and drawn model).
void require_positive_finite(const parameter_info& row, double value) {
  if (!std::isfinite(value) || value <= 0.0) require_positive_finite(message_name(row).c_str(), value);
}
void require_representable(const parameter_info& row, double value) {
  if (!(value >= min_magnitude && value <= max_magnitude))
    require_representable(message_name(row).c_str(), value);
}

void validate_family(const model_parameters& p) {
  for (const auto& row : scalar_parameters) {
    const double v = p.*row.field;
    if (row.domain == parameter_domain::non_negative && (!std::isfinite(v) || v < 0.0))
      throw invalid_parameter(message_name(row), v, "a finite number >= 0");
    if (row.domain == parameter_domain::positive_or_unset && (!std::isfinite(v) || v < 0.0))
      throw invalid_parameter(message_name(row), v, "a finite number > 0 (or unset: mu)");
    if (row.domain == parameter_domain::any && (!std::isfinite(v) || std::abs(v) > max_magnitude))
      throw invalid_parameter(message_name(row), v, "a finite number with |value| <= 1e60");
  }
  if (p.mu_k() > p.mu_s())
    throw invalid_parameter("mu_k (kinetic friction)", p.mu_k(),
                            fmt::format("<= mu_s = {} (kinetic friction cannot exceed static)",
                                        p.mu_s()));
  if (!p.belt_levels.empty() && p.belt_levels.size() < 2)
    throw invalid_parameter("belt-levels (count)", static_cast<double>(p.belt_levels.size()),
                            "at least 2 levels");
  for (std::size_t i = 0; i < p.belt_levels.size(); ++i) {
    const double v = p.belt_levels[i];
    if (!std::isfinite(v) || std::abs(v) > max_magnitude)
      throw invalid_parameter(fmt::format("belt level v{}", i + 1), v,
                              "a finite number with |value| <= 1e60");
    for (std::size_t j = 0; j < i; ++j)
      if (p.belt_levels[j] == v)
        throw invalid_parameter(fmt::format("belt level v{}", i + 1), v,
                                fmt::format("distinct from every other level (equals v{})", j + 1));
  }
  const std::size_t n = p.levels().size();
  if (!p.belt_rates.empty() && !p.belt_generator.empty())
    throw invalid_value("belt-rates", "given with a belt generator",
                        "one of them: rates for two levels, a generator for any number");
  if (!p.belt_rates.empty() && n != 2)
    throw invalid_parameter("belt-rates (count)", static_cast<double>(p.belt_rates.size()),
                            fmt::format("rates only for a two-level belt; this belt has {} levels: "
                                        "give a generator matrix (--belt-generator, or belt_generator in TOML)",
                                        n));
  if (!p.belt_rates.empty() && p.belt_rates.size() != 2)
    throw invalid_parameter("belt-rates (count)", static_cast<double>(p.belt_rates.size()),
                            "exactly 2: the rate of leaving each level");
  for (std::size_t i = 0; i < p.belt_rates.size(); ++i)
    if (!std::isfinite(p.belt_rates[i]) || !(p.belt_rates[i] > 0.0))
      throw invalid_parameter(fmt::format("belt-rates r{}", i + 1), p.belt_rates[i],
                              "a finite rate > 0");
  if (n > 2 && p.belt_generator.empty())
    throw invalid_value("belt generator", "(missing)",
                        fmt::format("a {} x {} rate matrix for {} belt levels (--belt-generator, "
                                    "or belt_generator in TOML [model])",
                                    n, n, n));
  if (!p.belt_generator.empty() && p.belt_generator.size() != n * n)
    throw invalid_parameter("belt generator (entries)",
                            static_cast<double>(p.belt_generator.size()),
                            fmt::format("exactly n x n = {} rates for {} levels", n * n, n));
  validate(model_of(p));
}

}  // namespace

oscillator_model model_of(const model_parameters& p) {
  oscillator_model m;
  m.mass = p.mass;
  m.stiffness = p.stiffness;
  m.damping = p.damping;
  m.gravity = p.gravity;
  m.static_friction = p.mu_s();
  m.kinetic_friction = p.mu_k();
  m.belt = markov_belt{p.levels(), p.generator()};
  m.window = p.window;
  return m;
}

std::vector<double> model_parameters::generator() const {
  if (!belt_generator.empty()) return belt_generator;
  // validate() asks for this (via max_stick_duration) before it counts the
  // rates, so a single rate must not be read past: it then stands for both.
  const double r1 = belt_rates.empty() ? switch_rate : belt_rates[0];
  const double r2 = belt_rates.size() < 2 ? r1 : belt_rates[1];
  return {-r1, r1, r2, -r2};
}

double model_parameters::max_stick_duration() const {
  if (belt_levels.empty()) return 2.0 * band_half_width() / belt_speed;
  const std::vector<double> q = generator();
  const std::size_t n = belt_levels.size();
  double slowest = 0.0, zero_level = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double v = std::abs(belt_levels[i]);
    if (v > 0.0 && (slowest == 0.0 || v < slowest)) slowest = v;
    if (v == 0.0 && q.size() == n * n) zero_level = std::max(zero_level, 5.0 / -q[i * n + i]);
  }
  const double moving = slowest > 0.0 ? 2.0 * band_half_width() / slowest : 0.0;
  return std::max(moving, zero_level);
}

bool model_parameters::is_paper_model() const {
  if (damping != 0.0 || mu_s() != mu_k()) return false;
  const std::vector<double> v = levels();
  if (v.size() != 2 || !(v[0] > 0.0) || v[1] != -v[0]) return false;
  const std::vector<double> q = generator();
  return q[1] == q[2] && q[0] == -q[1] && q[3] == -q[2];
}

model_parameters paper_form(const model_parameters& p) {
  model_parameters out;
  out.mass = p.mass;
  out.stiffness = p.stiffness;
  out.gravity = p.gravity;
  out.friction_coefficient = p.mu_k();
  out.belt_speed = p.levels()[0];
  out.switch_rate = p.generator()[1];
  out.window = p.window;
  return out;
}

void validate(const model_parameters& p) {
  for (const auto& row : scalar_parameters)
    if (row.domain == parameter_domain::positive)
      require_positive_finite(row, p.*row.field);
  for (const auto& row : scalar_parameters)
    if (row.domain == parameter_domain::positive)
      require_representable(row, p.*row.field);
  // Derived quantities can still overflow or underflow (e.g. mu*m*g = inf).
  const double a = p.band_half_width(), w = p.natural_frequency();
  require_representable("a = mu m g / k (band half-width)", a);
  require_representable("omega = sqrt(k/m) (natural frequency)", w);
  require_representable("d_max = 2a/V (max stick duration)", p.max_stick_duration());
  require_representable("omega a (speed scale of the band)", w * a);
  require_representable("V / omega (slip amplitude scale)", p.belt_speed / w);
  validate_family(p);
}

const parameter_info& info_for(const std::string& symbol) {
  if (const auto* row = row_of(symbol)) return *row;
  if (indexed(symbol, 'v') > 0) return belt_level_info;
  if (indexed(symbol, 'r') > 0) return belt_rate_info;
  throw invalid_value("parameter name", symbol, allowed_parameter_names());
}

bool is_parameter_symbol(std::string_view symbol) {
  return row_of(symbol) || indexed(symbol, 'v') > 0 || indexed(symbol, 'r') > 0;
}

std::string canonical_symbol(std::string_view name) {
  if (indexed(name, 'v') > 0 || indexed(name, 'r') > 0) return std::string(name);
  return info_for(std::string(name)).symbol;
}

parameter_domain domain_of(std::string_view symbol) {
  if (const auto* row = row_of(symbol)) return row->domain;
  return indexed(symbol, 'v') > 0 ? belt_level_info.domain : belt_rate_info.domain;
}

std::string flag_of(std::string_view symbol) {
  if (!row_of(symbol)) return std::string(symbol);
  std::string flag = "--" + std::string(row_of(symbol)->symbol);
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

bool assigned_first(std::string_view symbol) {
  const auto* row = row_of(symbol);
  return row && row->sets_others;
}

std::string allowed_parameter_names() {
  std::string names;
  for (const auto& row : scalar_parameters) names += std::string(row.symbol) + ", ";
  return names + "v1..vN (belt levels), r1, r2 (belt rates)";
}

std::vector<std::string> refinements_of(std::string_view symbol) {
  std::vector<std::string> out;
  const auto* row = row_of(symbol);
  if (row)
    for (const auto& other : scalar_parameters)
      if (refines(other, *row)) out.emplace_back(other.symbol);
  return out;
}

std::string only_in_the_stream_key(const std::vector<given_parameter>& given) {
  const auto set_by_it = [&](const std::string& sym) {
    return std::any_of(given.begin(), given.end(),
                       [&](const given_parameter& g) { return canonical_symbol(g.symbol) == sym; });
  };
  // One fixed value: a grid or a law beside a refinement is refused anyway
  // (overridden_by_base), with its own message.
  const auto one_number = [](const std::string& text) {
    char* stop = nullptr;
    (void)std::strtod(text.c_str(), &stop);
    return !text.empty() && stop == text.c_str() + text.size();
  };
  for (const auto& g : given) {
    const std::string sym = canonical_symbol(g.symbol);
    const auto refinements = refinements_of(sym);
    if (refinements.empty() || !one_number(g.text) ||
        !std::all_of(refinements.begin(), refinements.end(), set_by_it))
      continue;
    // Who gives them: their flags, or the configuration file the flags
    // were applied to.
    std::vector<std::string> givers;
    bool from_file = false;
    for (const auto& r : refinements) {
      const auto it = std::find_if(given.begin(), given.end(), [&](const given_parameter& e) {
        return canonical_symbol(e.symbol) == r && !e.from_config_file;
      });
      if (it != given.end())
        givers.push_back(flag_of(r));
      else
        from_file = true;
    }
    if (from_file) givers.emplace_back("the --config file");
    return fmt::format(
        "{0} {1} sets neither {2}: {3} {4} them. Unless the model is the paper's (mu_s = "
        "mu_k, c = 0, the belt +-V), {0} still enters the random streams' key and changes the "
        "draws, not the model: keep it to replay a run made with it, drop it otherwise",
        flag_of(sym), g.text, fmt::join(refinements, " nor "), fmt::join(givers, " and "),
        givers.size() == 1 ? "gives" : "give");
  }
  return {};
}

std::string overridden_by_base(const model_parameters& base, std::string_view symbol) {
  const std::string sym = canonical_symbol(symbol);
  if (sym == "V" && !base.belt_levels.empty()) return "the belt levels are given";
  if (sym == "lambda" && (!base.belt_rates.empty() || !base.belt_generator.empty()))
    return "the belt rates are given";
  const auto refinements = refinements_of(sym);
  for (const auto& r : refinements)
    if (base.*row_of(r)->field > 0.0)
      return fmt::format("{} sets {} both, and one of them is given", sym,
                         fmt::join(refinements, " and "));
  return {};
}

void assign_value(model_parameters& p, std::string_view symbol, double value) {
  const auto* row = row_of(canonical_symbol(symbol));
  if (row && row->domain == parameter_domain::positive_or_unset && value == 0.0)
    throw invalid_parameter(message_name(*row), value,
                            fmt::format("a finite number > 0; leave {} out for {} = mu",
                                        row->symbol, row->symbol));
  set_parameter(p, symbol, value);
}

model_parameters assign(model_parameters base, std::vector<parameter_assignment> assignments) {
  order_assignments(assignments, [](const parameter_assignment& a) -> std::string_view {
    return a.symbol;
  });
  for (const auto& a : assignments) assign_value(base, a.symbol, a.value);
  return base;
}

double parameter_value(const model_parameters& p, std::string_view name) {
  const std::string s = canonical_symbol(name);
  if (const auto* row = row_of(s)) return resolved_value(p, *row);
  if (const std::size_t i = indexed(s, 'v'); i > 0) {
    const auto v = p.levels();
    if (i > v.size())
      throw invalid_value("parameter name", s, fmt::format("v1..v{} (the belt has {} levels)", v.size(), v.size()));
    return v[i - 1];
  }
  const std::size_t i = indexed(s, 'r');
  const auto q = p.generator();
  const std::size_t n = p.levels().size();
  if (i > n || (n > 2 && p.belt_rates.empty()))
    throw invalid_value("parameter name", s,
                        n == 2 ? "r1, r2 (rates of leaving the two levels)"
                               : "no rI: a belt of more than two levels has a generator matrix");
  return -q[(i - 1) * n + (i - 1)];
}

void set_parameter(model_parameters& p, std::string_view name, double value) {
  const std::string s = canonical_symbol(name);
  if (const auto* row = row_of(s)) {
    p.*row->field = value;
    // mu: the values it sets are no longer given separately
    for (const auto& other : scalar_parameters)
      if (refines(other, *row)) p.*other.field = 0.0;
  }
  else if (const std::size_t i = indexed(s, 'v'); i > 0) {
    if (p.belt_levels.empty()) p.belt_levels = p.levels();
    if (i > p.belt_levels.size())
      throw invalid_value("parameter name", s,
                          fmt::format("v1..v{} (the belt has {} levels)", p.belt_levels.size(),
                                      p.belt_levels.size()));
    p.belt_levels[i - 1] = value;
  } else {
    const std::size_t j = indexed(s, 'r');
    if (p.levels().size() != 2 || !p.belt_generator.empty())
      throw invalid_value("parameter name", s,
                          "r1, r2 only for a two-level belt without a generator matrix");
    if (j > 2) throw invalid_value("parameter name", s, "r1 or r2");
    if (p.belt_rates.empty()) p.belt_rates = {p.switch_rate, p.switch_rate};
    if (p.belt_rates.size() != 2)  // not yet validated: never write past the rates
      throw invalid_parameter("belt-rates (count)", static_cast<double>(p.belt_rates.size()),
                              "exactly 2: the rate of leaving each level");
    p.belt_rates[j - 1] = value;
  }
}

}  // namespace stickslip
