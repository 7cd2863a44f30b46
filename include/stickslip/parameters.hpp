// The model description: the one value that says which oscillator is
// simulated (docs/model.md, docs/models.md).
//
// The paper's model:  m x'' + k x = f  on a belt whose velocity is a telegraph
// process (+V / -V, sign flips at Poisson times of rate lambda). Friction is
// Coulomb: |f| <= mu m g while sticking, f = mu m g sgn(v - x') while slipping.
//
// The model family adds, with defaults that give the paper's model:
//   viscous damping c:       m x'' + c x' + k x = f;
//   static and kinetic friction mu_s >= mu_k (a stick holds while
//     |k x + c v| <= mu_s m g, a slip feels mu_k m g);
//   a Markov belt: levels v_1..v_n (n >= 2, distinct, any sign, zero allowed)
//     with a generator Q; for two levels, the rates of leaving each level.
// The engines consume this through model_of(), its engine form
// (model/oscillator_model.hpp, which knows nothing of this description);
// when the resolved model is the paper's (is_paper_model), the lane engine
// runs it with the bits of 0.1.0.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "stickslip/model/oscillator_model.hpp"

namespace stickslip {

struct model_parameters {
  double mass = 1.0;                  // m   [kg]
  double stiffness = 4.0;             // k   [N/m]
  double gravity = 9.81;              // g   [m/s^2]
  double friction_coefficient = 5.0;  // mu  [-]
  double belt_speed = 1.0;            // V   [m/s]
  double switch_rate = 1.0;           // lambda [1/s]
  double window = 50.0;               // t_a [s]

  // The model family. Each default keeps the paper's model.
  double damping = 0.0;               // c     [N s/m], >= 0
  double static_friction = 0.0;       // mu_s  [-]; 0 = mu
  double kinetic_friction = 0.0;      // mu_k  [-]; 0 = mu
  std::vector<double> belt_levels{};  // v_1..v_n [m/s]; empty = (+V, -V)
  std::vector<double> belt_rates{};   // two levels: rate of leaving each [1/s]; empty = lambda
  std::vector<double> belt_generator{};// Q, n x n row-major [1/s]; empty = from belt_rates

  // Resolved values: mu_s and mu_k default to mu.
  [[nodiscard]] double mu_s() const noexcept {
    return static_friction > 0.0 ? static_friction : friction_coefficient;
  }
  [[nodiscard]] double mu_k() const noexcept {
    return kinetic_friction > 0.0 ? kinetic_friction : friction_coefficient;
  }
  // The belt levels: belt_levels, or (+V, -V).
  [[nodiscard]] std::vector<double> levels() const {
    return belt_levels.empty() ? std::vector<double>{belt_speed, -belt_speed} : belt_levels;
  }
  // The generator Q (n x n, row-major): belt_generator, or for two levels
  // [[-r1, r1], [r2, -r2]] with r = belt_rates, or (lambda, lambda).
  [[nodiscard]] std::vector<double> generator() const;
  // Whether the resolved model is the paper's: c = 0, mu_s = mu_k, levels
  // (+V, -V) for some V > 0 and both rates equal.
  [[nodiscard]] bool is_paper_model() const;

  // a = mu_s m g / k: the stick band is |x| <= a (spring force within max
  // friction); with damping it is |x + c v / k| <= a at belt level v.
  [[nodiscard]] double band_half_width() const noexcept { return mu_s() * mass * gravity / stiffness; }
  // omega = sqrt(k/m).
  [[nodiscard]] double natural_frequency() const noexcept { return std::sqrt(stiffness / mass); }
  // d_max = 2a/V: a stick that starts at one band edge and runs to the other.
  // On a Markov belt, 2a / (smallest nonzero |v_i|); a stick at a level
  // v = 0 lasts until the belt leaves it, so with such a level the scale is
  // at least 5 / (its rate of leaving), the 99.3 % quantile of that wait.
  [[nodiscard]] double max_stick_duration() const;
  friend bool operator==(const model_parameters&, const model_parameters&) = default;
};

// The paper's model with the same resolved values, written with the seven
// paper parameters only (mu, V, lambda). Precondition: p.is_paper_model().
// Two descriptions of one model (--mu 5 and --mu-s 5 --mu-k 5; levels 2,-2
// and V = 2) thereby get the same point_key and the same bits.
[[nodiscard]] model_parameters paper_form(const model_parameters& p);

// The engine form of a model description: the resolved mu_s, mu_k, c, belt
// levels and generator. For the paper's parameters this is the paper's model
// inside the family: mu_s = mu_k = mu, c = 0, levels (+V, -V), both rates
// lambda. No validation (validate(p) calls validate() of the result).
[[nodiscard]] oscillator_model model_of(const model_parameters& p);

// Throws stickslip::error naming the first invalid parameter, its value and
// the allowed range. The paper's parameters must be finite and > 0, and they
// and the derived scales (a, omega, d_max, omega a, V/omega) must lie in
// [min_magnitude, max_magnitude]; c finite and >= 0; mu_s, mu_k finite and
// > 0 when given, mu_k <= mu_s; belt levels: none or n >= 2 distinct finite
// values; belt rates: none or one per level of a two-level belt, finite and
// > 0; a generator: n x n with rows summing to 0; not both rates and a
// generator; then validate(model_of(p)) (model/oscillator_model.hpp, with
// min_magnitude and max_magnitude).
void validate(const model_parameters& p);

// What values a scalar parameter takes (validate), and a grid of it.
enum class parameter_domain {
  positive,           // finite and > 0, within [min_magnitude, max_magnitude]
  non_negative,       // finite and >= 0
  positive_or_unset,  // finite and > 0, or 0: unset (mu_s, mu_k resolve to mu)
  any,                // finite, |value| <= max_magnitude
};

// One parameter's descriptor: every reader and writer of parameters (the
// CLI's flags, TOML keys, Python keywords, validation, the stream key,
// checkpoints, the output columns and attributes) iterates these rows.
struct parameter_info {
  const char* symbol;       // "mu_s": the output column, TOML key, Python keyword, --mu-s
  const char* long_name;    // "static-friction": the flag's alias; in messages "static friction"
  const char* description;
  const char* units;
  // The value as given (not resolved: mu_s = 0 is unset); its default is
  // that of model_parameters{}. Null for the indexed rows vI and rI.
  double model_parameters::*field = nullptr;
  parameter_domain domain = parameter_domain::positive;
  // Its place in the random streams' point key (random_stream.hpp): the
  // paper's parameters hash first, as in 0.1.0; the family's after them,
  // only for a model that is not the paper's, in this order.
  unsigned key_position = 0;
  // Assigned before the others (CLI, TOML and Python alike): mu sets mu_s
  // and mu_k both, which may then refine it whatever their written order.
  bool sets_others = false;
  // The Python keyword where the symbol is one of Python's reserved words
  // (lambda: "lam"); null: the symbol itself.
  const char* python_keyword = nullptr;
};

// The scalar parameters, the paper's seven first, in the order of the output
// columns and of a checkpoint's layout.
inline constexpr parameter_info scalar_parameters[] = {
    {"m", "mass", "mass of the oscillator", "kg", &model_parameters::mass,
     parameter_domain::positive, 0},
    {"k", "stiffness", "spring stiffness", "N/m", &model_parameters::stiffness,
     parameter_domain::positive, 1},
    {"g", "gravity", "acceleration of gravity", "m/s^2", &model_parameters::gravity,
     parameter_domain::positive, 2},
    {"mu", "friction-coefficient", "Coulomb friction coefficient (sets mu_s and mu_k)", "1",
     &model_parameters::friction_coefficient, parameter_domain::positive, 3, true},
    {"V", "belt-speed", "belt speed magnitude (levels +V, -V)", "m/s",
     &model_parameters::belt_speed, parameter_domain::positive, 4},
    {"lambda", "switch-rate", "Poisson rate of belt direction switches (both levels)", "1/s",
     &model_parameters::switch_rate, parameter_domain::positive, 5, false, "lam"},
    {"ta", "window", "analysis window t_a", "s", &model_parameters::window,
     parameter_domain::positive, 6},
    {"c", "damping", "viscous damping coefficient", "N s/m", &model_parameters::damping,
     parameter_domain::non_negative, 9},
    {"mu_s", "static-friction", "static friction coefficient (default mu)", "1",
     &model_parameters::static_friction, parameter_domain::positive_or_unset, 7},
    {"mu_k", "kinetic-friction", "kinetic friction coefficient (default mu)", "1",
     &model_parameters::kinetic_friction, parameter_domain::positive_or_unset, 8},
};
// The paper's parameters: the first rows, the seven keys of 0.1.0's streams.
inline constexpr std::size_t paper_parameter_count = 7;

// The scalar parameters' symbols: as they appear on the command line, in
// config files, as NetCDF coordinates and attributes, and as output columns.
inline constexpr auto recorded_parameter_names = [] {
  std::array<const char*, std::size(scalar_parameters)> names{};
  for (std::size_t i = 0; i < names.size(); ++i) names[i] = scalar_parameters[i].symbol;
  return names;
}();
// The paper's seven: m, k, g, mu, V, lambda, ta.
inline constexpr auto parameter_names = [] {
  std::array<const char*, paper_parameter_count> names{};
  for (std::size_t i = 0; i < names.size(); ++i) names[i] = scalar_parameters[i].symbol;
  return names;
}();

// The order of grid axes where nothing else orders them (a TOML [grid]
// without `order`), every row once: the leading axes first (the paper's
// grid, lambda then mu: the CLI and the writers put them first too), then
// the refinements of mu, the damping, and the rest; belt levels vI and
// rates rI come after every row, in the order of their names.
inline constexpr const char* default_axis_order[] = {"lambda", "mu", "mu_s", "mu_k", "c",
                                                     "m",      "k",  "g",    "V",    "ta"};
inline constexpr std::size_t leading_axis_count = 2;
static_assert(
    [] {
      if (std::size(default_axis_order) != std::size(scalar_parameters)) return false;
      for (const auto& row : scalar_parameters) {
        int seen = 0;
        for (const char* s : default_axis_order) seen += std::string_view(s) == row.symbol;
        if (seen != 1) return false;
      }
      return true;
    }(),
    "default_axis_order names every scalar parameter once");
// The rank of a canonical symbol in default_axis_order (vI, rI, long aliases
// and unknown names after every row).
[[nodiscard]] constexpr std::size_t axis_rank(std::string_view symbol) noexcept {
  for (std::size_t i = 0; i < std::size(default_axis_order); ++i)
    if (symbol == default_axis_order[i]) return i;
  return std::size(default_axis_order);
}

// Access by symbol. Besides the names above (and their long aliases), a
// belt level is "v1".."vN" and the rate of leaving a level of a two-level
// belt is "r1", "r2". Reading gives the resolved value (mu_s of a model
// without one is mu); writing "mu" sets mu_s and mu_k both (clears the
// separate values), writing "vI" or "rI" first spells out the default levels
// (+V, -V) or rates (lambda, lambda). Throws on an unknown name or index.
[[nodiscard]] double parameter_value(const model_parameters& p, std::string_view symbol);
void set_parameter(model_parameters& p, std::string_view symbol, double value);
// A row's resolved value: its field, or mu for an unset mu_s, mu_k.
[[nodiscard]] inline double resolved_value(const model_parameters& p, const parameter_info& row) {
  const double v = p.*row.field;
  return row.domain == parameter_domain::positive_or_unset && v == 0.0 ? p.friction_coefficient : v;
}
// Whether `symbol` names a parameter (a fixed one, or vI / rI with I >= 1).
[[nodiscard]] bool is_parameter_symbol(std::string_view symbol);
// The canonical symbol of a name or long alias ("friction-coefficient" -> "mu").
[[nodiscard]] std::string canonical_symbol(std::string_view name);

// Throws on a name that is not a fixed symbol or long alias; the info of
// "vI" and "rI" is that of "belt-level" and "belt-rate".
const parameter_info& info_for(const std::string& symbol);
// The domain of a symbol: its row's, a belt level's (any) or rate's (positive).
[[nodiscard]] parameter_domain domain_of(std::string_view symbol);
// How the command line and messages name a parameter: "--mu-s" for mu_s; a
// belt level or rate by its symbol ("v1", "r2"), which has no flag.
[[nodiscard]] std::string flag_of(std::string_view symbol);

// Every name a parameter can have, for messages: "m, k, ..., mu_k, v1..vN
// (belt levels), r1, r2 (belt rates)".
[[nodiscard]] std::string allowed_parameter_names();
// Whether `row` refines `of`: `of` sets others (mu) and `row`'s unset value
// resolves to it (mu_s, mu_k). The one rule behind refinements_of, and what
// set_parameter clears when `of` is written.
[[nodiscard]] constexpr bool refines(const parameter_info& row, const parameter_info& of) noexcept {
  return of.sets_others && row.domain == parameter_domain::positive_or_unset;
}
// The symbols a row that sets others also sets (the rows that refine it):
// for mu, mu_s and mu_k; empty for any other symbol.
[[nodiscard]] std::vector<std::string> refinements_of(std::string_view symbol);
// A parameter as a command's flag or a call's keyword gave it: its symbol
// and its text ("5", a grid "0.5,1", a law).
struct given_parameter {
  std::string symbol;
  std::string text;
  bool from_config_file = false;  // set by a --config file's axis or law, not given here
};
// A note (one line, named by flags; the Python layer words it with
// keywords) when a symbol that sets others (mu) is given as one number
// beside all its refinements (mu_s, mu_k; a given 0, which would leave one
// unset, is refused by assign_value): mu then sets no friction
// coefficient, yet unless the model is the paper's (whose key is its seven
// values, mu_k for mu) it still enters the point's stream key
// (random_stream.hpp, point_key), so it changes the draws but not the
// model. Not refused: a run recorded with it (its command line, its
// resolved configuration, which writes mu beside them) must replay with it.
// Empty when there is none (a grid or a law over mu beside a refinement is
// refused elsewhere: overridden_by_base). A refinement marked
// from_config_file is one a --config file set (an axis or a law), and the
// note says so.
[[nodiscard]] std::string only_in_the_stream_key(const std::vector<given_parameter>& given);
// Why a grid axis or an uncertain law over `symbol` would change nothing on
// top of `base`, because the base overrides it: V under given belt levels,
// lambda under given belt rates or a generator, mu when a refinement of it
// (mu_s, mu_k) is given. Empty when it has an effect.
[[nodiscard]] std::string overridden_by_base(const model_parameters& base,
                                             std::string_view symbol);

// One assignment of a number to a parameter, as a flag, a TOML key or a
// Python keyword gives it.
struct parameter_assignment {
  std::string symbol;  // a symbol or long alias
  double value = 0.0;
};
// Whether assignments to `symbol` come first: its row sets others (mu).
[[nodiscard]] bool assigned_first(std::string_view symbol);
// The one order in which assignments apply, shared by the CLI, TOML and
// Python: the rows that set others (mu) first, then the rest as given
// (stable), so that mu_s and mu_k refine mu whatever their written order.
// `symbol_of(item)` gives an item's symbol.
template <class Item, class SymbolOf>
void order_assignments(std::vector<Item>& items, SymbolOf symbol_of) {
  std::stable_partition(items.begin(), items.end(),
                        [&](const Item& item) { return assigned_first(symbol_of(item)); });
}
// set_parameter for a number a user wrote (a flag, a TOML key, a Python
// keyword): a row whose 0 means unset (mu_s, mu_k resolve to mu) takes only
// a value > 0 there, because an explicit 0 would silently stand for mu (a
// new user asked for mu_k = 0 and got mu_k = mu = 5). Throws invalid_input
// naming the row, the value and what is allowed, before `p` changes. (In
// C++ a 0 field still means unset.) Not validated.
void assign_value(model_parameters& p, std::string_view symbol, double value);
// `base` with the assignments applied in that order (assign_value), not
// validated.
[[nodiscard]] model_parameters assign(model_parameters base,
                                      std::vector<parameter_assignment> assignments);

}  // namespace stickslip
