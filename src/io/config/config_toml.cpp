// The sweep configuration as TOML (schema: docs/config.md), both directions.
// Reading is strict: unknown tables and keys, wrong types and bad grid specs
// are errors that name the key and its position (file:line:col).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <toml++/toml.h>

#include "config_detail.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"

namespace stickslip::io {
namespace {

struct context {
  std::string_view origin;

  [[nodiscard]] std::string at(const toml::source_region& r) const {
    return fmt::format("{}:{}:{}", origin, r.begin.line, r.begin.column);
  }
  [[noreturn]] void unknown_key(const std::string& dotted, const toml::key& k,
                                const std::string& allowed) const {
    throw invalid_value(fmt::format("config key at {}", at(k.source())), dotted,
                        "a known key; here " + allowed);
  }
  [[noreturn]] void wrong(const std::string& dotted, const toml::node& n,
                          const std::string& expected) const;
};

const char* type_name(toml::node_type t) noexcept {
  switch (t) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a float";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date or time";
  }
}

std::string show(const toml::node& n) {
  if (n.is_string()) return n.as_string()->get();  // invalid_value adds the quotes
  std::ostringstream os;
  n.visit([&](auto&& v) { os << v; });
  std::string s = os.str();
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

void context::wrong(const std::string& dotted, const toml::node& n,
                    const std::string& expected) const {
  throw invalid_value(fmt::format("{} at {}", dotted, at(n.source())), show(n),
                      fmt::format("{}; got {}", expected, type_name(n.type())));
}

const toml::table& as_table(const context& cx, const std::string& name, const toml::node& n) {
  if (!n.is_table()) cx.wrong(name, n, "a table [" + name + "]");
  return *n.as_table();
}

double read_number(const context& cx, const std::string& dotted, const toml::node& n) {
  double v = 0;
  if (n.is_integer())
    v = static_cast<double>(n.as_integer()->get());
  else if (n.is_floating_point())
    v = n.as_floating_point()->get();
  else
    cx.wrong(dotted, n, "a number");
  if (!std::isfinite(v)) cx.wrong(dotted, n, "a finite number");
  return v;
}

// Unsigned 64-bit in [min, max]: an integer, or a string of digits for
// values above 2^63 - 1 (TOML integers are signed 64-bit).
std::uint64_t read_u64(const context& cx, const std::string& dotted, const toml::node& n,
                       std::uint64_t min = 0, std::uint64_t max = UINT64_MAX) {
  const auto allowed = fmt::format("an integer from {} to {}", min, limit_text(max));
  std::optional<std::uint64_t> v;
  if (n.is_integer() && n.as_integer()->get() >= 0) {
    v = static_cast<std::uint64_t>(n.as_integer()->get());
  } else if (n.is_string()) {
    const std::string& s = n.as_string()->get();
    std::uint64_t parsed = 0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), parsed);
    if (!s.empty() && ec == std::errc{} && ptr == s.data() + s.size()) v = parsed;
  }
  if (!v || *v < min || *v > max) cx.wrong(dotted, n, allowed);
  return *v;
}

bool read_bool(const context& cx, const std::string& dotted, const toml::node& n) {
  if (!n.is_boolean()) cx.wrong(dotted, n, "a boolean (true or false)");
  return n.as_boolean()->get();
}

std::vector<double> read_numbers(const context& cx, const std::string& dotted,
                                 const toml::node& n) {
  const auto* a = n.as_array();
  if (!a) cx.wrong(dotted, n, "an array of numbers");
  std::vector<double> values;
  for (std::size_t i = 0; i < a->size(); ++i)
    values.push_back(read_number(cx, fmt::format("{}[{}]", dotted, i), *a->get(i)));
  return values;
}

// The generator: an array of n rows of n rates (q_ii = -sum of the others).
std::vector<double> read_generator(const context& cx, const std::string& dotted,
                                   const toml::node& n) {
  const auto* a = n.as_array();
  if (!a || a->empty()) cx.wrong(dotted, n, "an array of rows [[q11, q12, ...], ...]");
  std::vector<double> q;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const auto row = read_numbers(cx, fmt::format("{}[{}]", dotted, i), *a->get(i));
    if (row.size() != a->size())
      cx.wrong(fmt::format("{}[{}]", dotted, i), *a->get(i),
               fmt::format("a row of {} rates (the matrix is n x n, n = {} rows)", a->size(),
                           a->size()));
    q.insert(q.end(), row.begin(), row.end());
  }
  return q;
}

// A [model] key holding a law (a string such as "gamma(mean=5,cv=0.2)"):
// parsed by parse_law, whose messages start with the key and its position.
void read_law(const context& cx, const std::string& key, const toml::node& n, sweep_spec& s) {
  const std::string& text = n.as_string()->get();
  if (!looks_like_law(text))
    cx.wrong("model." + key, n,
             "a number, or a law such as \"gamma(mean=5,cv=0.2)\" (docs/uncertainty.md)");
  const std::string where = fmt::format("model.{} at {}", key, cx.at(n.source()));
  parameter_law law = parse_law(text, where);
  if (std::any_of(s.axes.begin(), s.axes.end(), [&](const axis& a) { return a.name == key; }))
    throw invalid_value(where, text, "a law or a [grid] axis, not both: [grid] sweeps " + key);
  set_law(s, key, std::move(law));
}

// A recorded scalar (m, k, ..., mu_k): a number or a law; a belt level vI or
// rate rI: a law (its value goes in belt_levels or belt_rates).
void read_model_value(const context& cx, const std::string& key, const toml::node& n,
                      sweep_spec& s) {
  if (n.is_string()) return read_law(cx, key, n, s);
  drop_law(s, key);
  assign_value(s.base, key, read_number(cx, "model." + key, n));
}

// "m, k, g, mu, V, lambda, ta, c, mu_s, mu_k": the scalar keys.
std::string scalar_list() {
  return fmt::format("{}", fmt::join(recorded_parameter_names, ", "));
}

bool is_indexed_symbol(const std::string& key) {
  return key.size() > 1 && (key[0] == 'v' || key[0] == 'r') && is_parameter_symbol(key) &&
         key.find('-') == std::string::npos && canonical_symbol(key) == key;
}

void read_model(const context& cx, const toml::table& t, sweep_spec& s) {
  // The CLI's and Python's order (assigned_first, order_assignments): "mu"
  // sets mu_s and mu_k both, so it is read first, and mu_s and mu_k in the
  // same table refine it whatever their order in the file. The belt arrays
  // come before vI and rI (the table is ordered by key).
  // TOML keys are the symbols only: a long alias ("friction-coefficient")
  // is an unknown key, as it always was.
  const auto first = [](std::string_view key) {
    return assigned_first(key) && canonical_symbol(key) == key;
  };
  for (auto&& [k, n] : t)
    if (first(k.str())) read_model_value(cx, std::string(k.str()), n, s);
  for (auto&& [k, n] : t) {
    const std::string key(k.str());
    const std::string dotted = "model." + key;
    if (first(key)) continue;
    if (key == "belt_levels") {
      s.base.belt_levels = read_numbers(cx, dotted, n);
    } else if (key == "belt_rates") {
      s.base.belt_rates = read_numbers(cx, dotted, n);
    } else if (key == "belt_generator") {
      s.base.belt_generator = read_generator(cx, dotted, n);
    } else if (std::find_if(std::begin(recorded_parameter_names), std::end(recorded_parameter_names),
                            [&](const char* p) { return key == p; }) !=
               std::end(recorded_parameter_names)) {
      read_model_value(cx, key, n, s);
    } else if (is_indexed_symbol(key)) {
      if (!n.is_string())
        cx.wrong(dotted, n,
                 "a law string (a fixed belt level or rate goes in belt_levels or belt_rates)");
      read_law(cx, key, n, s);
    } else {
      cx.unknown_key(dotted, k,
                     fmt::format("[model] takes {} (each a number or a law), belt_levels, "
                                 "belt_rates, belt_generator, and laws of belt levels v1..vN "
                                 "and rates r1, r2",
                                 scalar_list()));
    }
  }
}

void read_range(const context& cx, const std::string& dotted, const toml::node& n, double& lo,
                double& hi) {
  const auto* a = n.as_array();
  if (!a || a->size() != 2) cx.wrong(dotted, n, "an array of two numbers [lo, hi]");
  lo = read_number(cx, dotted + "[0]", *a->get(0));
  hi = read_number(cx, dotted + "[1]", *a->get(1));
  if (lo > hi)
    cx.wrong(dotted, n, fmt::format("[lo, hi] with lo <= hi; here lo = {} > hi = {}", lo, hi));
}

void read_initial(const context& cx, const toml::table& t, initial_condition_law& law) {
  for (auto&& [k, n] : t) {
    const std::string key(k.str());
    const std::string dotted = "initial." + key;
    if (key == "x0") {
      read_range(cx, dotted, n, law.position_min, law.position_max);
    } else if (key == "xdot0") {
      read_range(cx, dotted, n, law.velocity_min, law.velocity_max);
    } else if (key == "belt_start") {
      // The level count is checked with the model (sweep validate).
      const auto* s = n.as_string();
      const std::string v = s ? s->get() : "";
      if (n.is_integer() && n.as_integer()->get() >= -1 && n.as_integer()->get() != 0 &&
          n.as_integer()->get() <= 1000000)
        law.belt_start = static_cast<int>(n.as_integer()->get());
      else if (v == "stationary" || v == "random")
        law.belt_start = 0;
      else if (v == "+1" || v == "1")
        law.belt_start = 1;
      else if (v == "-1")
        law.belt_start = -1;
      else if (!v.empty() && v.size() < 7 && std::all_of(v.begin(), v.end(), [](char c) {
                 return c >= '0' && c <= '9';
               }) && v[0] != '0')
        law.belt_start = std::stoi(v);
      else
        cx.wrong(dotted, n,
                 "\"stationary\", \"+1\" (first level), \"-1\" (second level), or a level "
                 "number 1..n");
    } else {
      cx.unknown_key(dotted, k, "[initial] takes x0, xdot0, belt_start");
    }
  }
}

std::vector<double> read_axis_values(const context& cx, const std::string& dotted,
                                     const toml::node& n, grid_domain domain) {
  if (n.is_string()) return parse_grid(fmt::format("{} at {}", dotted, cx.at(n.source())),
                                       n.as_string()->get(), domain);
  const auto* a = n.as_array();
  if (!a) cx.wrong(dotted, n, "a grid spec string (\"lin:a:b:n\", ...) or an array of numbers");
  if (a->empty()) cx.wrong(dotted, n, "a non-empty array of numbers (the list is empty)");
  std::vector<double> values;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const auto& item = *a->get(i);
    const double v = read_number(cx, fmt::format("{}[{}]", dotted, i), item);
    if (domain == grid_domain::positive && !(v > 0.0))
      cx.wrong(fmt::format("{}[{}]", dotted, i), item, "a number > 0");
    if (domain == grid_domain::non_negative && !(v >= 0.0))
      cx.wrong(fmt::format("{}[{}]", dotted, i), item, "a number >= 0");
    values.push_back(v);
  }
  return values;
}

// [sweep] statistics: an array of names, or one string (a name or a comma
// list of them, as --statistics).
std::vector<std::string> read_names(const context& cx, const std::string& dotted,
                                    const toml::node& n) {
  if (const auto* one = n.as_string()) return {one->get()};
  const auto* a = n.as_array();
  if (!a) cx.wrong(dotted, n, "an array of names, e.g. [\"survival\"]");
  std::vector<std::string> names;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const auto* s = a->get(i)->as_string();
    if (!s) cx.wrong(fmt::format("{}[{}]", dotted, i), *a->get(i), "a name string");
    names.push_back(s->get());
  }
  return names;
}

std::vector<std::string> read_order(const context& cx, const toml::node& n) {
  const auto* a = n.as_array();
  if (!a) cx.wrong("grid.order", n, "an array of parameter symbols");
  std::vector<std::string> order;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const auto* s = a->get(i)->as_string();
    if (!s) cx.wrong(fmt::format("grid.order[{}]", i), *a->get(i), "a parameter symbol string");
    order.push_back(s->get());
  }
  return order;
}

void read_grid(const context& cx, const toml::table& t, const sweep_spec& spec,
               std::vector<axis>& axes) {
  std::vector<axis> found;
  const toml::node* order_node = nullptr;
  for (auto&& [k, n] : t) {
    const std::string key(k.str());
    if (key == "order") {
      order_node = &n;
      continue;
    }
    const std::string dotted = "grid." + key;
    if (!is_parameter_symbol(key) || key.find('-') != std::string::npos)
      cx.unknown_key(dotted, k,
                     fmt::format("[grid] takes order and {}, belt levels v1..vN, two-level belt "
                                 "rates r1, r2",
                                 scalar_list()));
    if (find_law(spec, key))  // [model] was read first
      cx.wrong(dotted, n, "a law or a [grid] axis, not both: [model] gives " + key + " a law");
    found.push_back({key, read_axis_values(cx, dotted, n, grid_domain_of(key))});
  }
  std::vector<std::string> order;
  if (order_node) {
    order = read_order(cx, *order_node);
    std::set<std::string> seen;
    for (const auto& name : order) {
      const bool known = std::any_of(found.begin(), found.end(),
                                     [&](const axis& a) { return a.name == name; });
      if (!known || !seen.insert(name).second)
        cx.wrong("grid.order", *order_node,
                 "each swept parameter of [grid] exactly once ('" + name + "' is " +
                     (known ? "repeated" : "not a key of [grid]") + ")");
    }
    if (order.size() != found.size())
      cx.wrong("grid.order", *order_node, "every swept parameter of [grid] listed");
  } else {
    // TOML tables are unordered: default_axis_order (parameters.hpp), then
    // belt levels vI and rates rI in the order of their names.
    for (const char* s : default_axis_order) order.emplace_back(s);
    std::vector<std::string> indexed;
    for (const auto& a : found)
      if (std::find(order.begin(), order.end(), a.name) == order.end()) indexed.push_back(a.name);
    std::sort(indexed.begin(), indexed.end());
    order.insert(order.end(), indexed.begin(), indexed.end());
  }
  for (const auto& name : order)
    for (auto& a : found)
      if (a.name == name) axes.push_back(std::move(a));
}

void read_sweep(const context& cx, const toml::table& t, sweep_spec& s) {
  for (auto&& [k, n] : t) {
    const std::string key(k.str());
    const std::string dotted = "sweep." + key;
    if (key == "realizations")
      s.realizations = read_u64(cx, dotted, n, 1, max_realizations);
    else if (key == "seed")
      s.seed = read_u64(cx, dotted, n);
    else if (key == "block_size")
      s.block_size = read_u64(cx, dotted, n, 1, max_block_size);
    else if (key == "max_events")
      s.max_events = static_cast<std::int64_t>(
          read_u64(cx, dotted, n, 1, static_cast<std::uint64_t>(max_event_bound)));
    else if (key == "keep_records")
      s.keep_records = read_bool(cx, dotted, n);
    else if (key == "engine") {
      if (!n.is_string()) cx.wrong(dotted, n, "a string: \"fast\" or \"reference\"");
      s.engine = parse_engine(dotted, n.as_string()->get());
    } else if (key == "common_random_numbers") {
      s.common_random_numbers = read_bool(cx, dotted, n);
    } else if (key == "target_ci") {
      if (!n.is_string()) cx.wrong(dotted, n, "a string \"STAT:HALFWIDTH\", e.g. \"R:0.002\"");
      parse_target_ci(dotted, n.as_string()->get(), s);
    } else if (key == "min_realizations") {
      s.min_realizations = read_u64(cx, dotted, n, 2, max_realizations);
    } else if (key == "sensitivity_statistic") {
      // A sensitivity study (uncertainty/sensitivity_design.hpp): the
      // statistic whose Sobol' indices are estimated; realizations = rows.
      if (!n.is_string()) cx.wrong(dotted, n, "a string naming a statistic, e.g. \"R\"");
      s.sensitivity_statistic = n.as_string()->get();
    } else if (key == "statistics") {
      // One string is the CLI's comma list ("paper,survival"), an array its names.
      s.statistics = parse_statistics_selection(dotted, read_names(cx, dotted, n));
    } else if (key == "burn_in") {
      s.burn_in = read_number(cx, dotted, n);  // 0 <= T < t_a: validate()
    } else if (key == "observe_times") {
      // The axes' grid forms; ascending and <= t_a: validate().
      s.observe_times = read_axis_values(cx, dotted, n, grid_domain::non_negative);
    } else if (key == "target_halfwidth") {
      // The sensitivity study's stop rule (every index's 95 % half-width);
      // a sweep's is target_ci, which carries its own half-width.
      if (t.contains("target_ci"))
        cx.wrong(dotted, n, "absent when target_ci is given (its half-width is target_ci's)");
      s.target_halfwidth = read_number(cx, dotted, n);
      if (!(s.target_halfwidth > 0.0)) cx.wrong(dotted, n, "a number > 0");
    } else
      cx.unknown_key(dotted, k,
                     "[sweep] takes realizations, seed, block_size, max_events, keep_records, "
                     "engine, common_random_numbers, target_ci, min_realizations, "
                     "sensitivity_statistic, target_halfwidth, statistics, burn_in, "
                     "observe_times");
  }
}

// [histograms] and [survival] (histogram_spec, survival_spec): bins and the
// ends of the duration ranges (0 = automatic); validate() checks the ends.
template <class Grid>
void read_duration_grid(const context& cx, const toml::table& t, const std::string& table,
                        Grid& g) {
  for (auto&& [k, n] : t) {
    const std::string key(k.str());
    const std::string dotted = table + "." + key;
    if (key == "bins")
      g.bins = static_cast<std::size_t>(read_u64(cx, dotted, n, 1, max_histogram_bins));
    else if (key == "stick_duration_max")
      g.stick_duration_max = read_number(cx, dotted, n);
    else if (key == "slip_duration_max")
      g.slip_duration_max = read_number(cx, dotted, n);
    else
      cx.unknown_key(dotted, k, "[" + table + "] takes bins, stick_duration_max, slip_duration_max");
  }
}

// Shortest text that reads back to the same double, always a TOML float.
std::string toml_float(double v) {
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // "n": inf, nan
  return s;
}

std::string toml_u64(std::uint64_t v) {
  if (v > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
    return fmt::format("\"{}\"", v);
  return fmt::format("{}", v);
}

}  // namespace

sweep_spec parse_sweep_toml(std::string_view toml_text, std::string_view origin) {
  const context cx{origin};
  toml::table root;
  try {
    root = toml::parse(toml_text, origin);
  } catch (const toml::parse_error& e) {
    throw error(exit_code::invalid_input,
                fmt::format("{}: TOML syntax error: {}", cx.at(e.source()), e.description()));
  }
  sweep_spec s;
  for (auto&& [k, n] : root) {
    const std::string key(k.str());
    if (key == "model")
      read_model(cx, as_table(cx, key, n), s);
    else if (key == "initial")
      read_initial(cx, as_table(cx, key, n), s.initial);
    else if (key == "grid")
      read_grid(cx, as_table(cx, key, n), s, s.axes);
    else if (key == "sweep")
      read_sweep(cx, as_table(cx, key, n), s);
    else if (key == "histograms")
      read_duration_grid(cx, as_table(cx, key, n), key, s.histograms);
    else if (key == "survival")
      read_duration_grid(cx, as_table(cx, key, n), key, s.survival);
    else
      cx.unknown_key(key, k,
                     "the tables are [model], [initial], [grid], [sweep], [histograms], "
                     "[survival]");
  }
  return s;
}

sweep_spec read_sweep_toml_file(const std::string& path) {
  return parse_sweep_toml(read_text_file(path), path);
}

std::string to_toml(const sweep_spec& s) {
  std::string out = "# stickslip sweep configuration, fully resolved (docs/config.md)\n\n[model]\n";
  // An uncertain parameter's key holds its law (set_law left its base value
  // at the default, so nothing is lost).
  auto law_line = [&](const char* name) -> std::string {
    const parameter_law* law = find_law(s, name);
    return law ? fmt::format("{} = \"{}\"\n", name, to_string(*law)) : std::string();
  };
  // The values as given: the rows that cannot be unset always, the others
  // (an unset mu_s, mu_k) only when given, so that a configuration without
  // them reads and prints as before.
  // A swept parameter's value here is replaced at every point by its
  // [grid] axis: said beside it (a new user read summary.json's
  // `mu = 5.0` beside base's null for a swept mu as a contradiction).
  const auto swept = [&](const char* symbol) {
    return std::any_of(s.axes.begin(), s.axes.end(),
                       [&](const auto& ax) { return canonical_symbol(ax.name) == symbol; });
  };
  const auto& b = s.base;
  for (const auto& row : scalar_parameters) {
    const std::string line = law_line(row.symbol);
    const double v = b.*row.field;
    const bool always = row.domain == parameter_domain::positive ||
                        row.domain == parameter_domain::non_negative;
    if (!line.empty()) out += line;
    else if (always || v != model_parameters{}.*row.field)
      out += fmt::format("{} = {}{}\n", row.symbol, toml_float(v),
                         swept(row.symbol) ? "  # swept: [grid] gives its values" : "");
  }
  auto array = [](const std::vector<double>& v, std::size_t from, std::size_t count) {
    std::string a = "[";
    for (std::size_t i = 0; i < count; ++i) a += (i ? ", " : "") + toml_float(v[from + i]);
    return a + "]";
  };
  if (!b.belt_levels.empty())
    out += fmt::format("belt_levels = {}\n", array(b.belt_levels, 0, b.belt_levels.size()));
  if (!b.belt_rates.empty())
    out += fmt::format("belt_rates = {}\n", array(b.belt_rates, 0, b.belt_rates.size()));
  if (!b.belt_generator.empty()) {
    // The rows as given (r x r, whatever the number of levels: validate()
    // judges the sizes), so that every parsed generator prints back; a size
    // that is not a square (only from code) prints as one row, which the
    // reader refuses.
    std::size_t r = 1;
    while ((r + 1) * (r + 1) <= b.belt_generator.size()) ++r;
    if (r * r != b.belt_generator.size()) r = 1;
    const std::size_t width = r == 1 ? b.belt_generator.size() : r;
    out += "belt_generator = [";
    for (std::size_t i = 0; i < r; ++i)
      out += (i ? ", " : "") + array(b.belt_generator, i * width, width);
    out += "]\n";
  }
  for (const auto& u : s.uncertain)  // belt levels vI and rates rI
    if (is_indexed_symbol(u.symbol))
      out += fmt::format("{} = \"{}\"\n", u.symbol, to_string(u.law));

  const auto& law = s.initial;
  out += fmt::format("\n[initial]\nx0 = [{}, {}]\nxdot0 = [{}, {}]\nbelt_start = \"{}\"\n",
                     toml_float(law.position_min), toml_float(law.position_max),
                     toml_float(law.velocity_min), toml_float(law.velocity_max),
                     belt_start_text(law.belt_start));

  out += "\n[grid]\n";
  if (!s.axes.empty()) {
    out += "order = [";
    for (std::size_t i = 0; i < s.axes.size(); ++i)
      out += fmt::format("{}\"{}\"", i ? ", " : "", s.axes[i].name);
    out += "]\n";
  }
  for (const auto& ax : s.axes) {
    out += ax.name + " = [";
    for (std::size_t i = 0; i < ax.values.size(); ++i)
      out += (i ? ", " : "") + toml_float(ax.values[i]);
    out += "]\n";
  }

  // A study's realizations are its design's rows (--samples): say so beside
  // the key, which the reader keeps (a user read "realizations = 64" beside
  // sensitivity.nc's realizations = 256).
  const std::string rows_note =
      s.sensitivity_statistic.empty()
          ? std::string()
          : fmt::format("  # {} (--{}), {} realizations each",
                        s.target_halfwidth > 0.0 ? "at most this many of the design's rows"
                                                 : "the design's rows",
                        s.target_halfwidth > 0.0 ? "max-samples" : "samples", runs_per_row(s));
  out += fmt::format(
      "\n[sweep]\nrealizations = {}{}\nseed = {}\nblock_size = {}\nmax_events = {}\n"
      "keep_records = {}\nengine = \"{}\"\n",
      toml_u64(s.realizations), rows_note, toml_u64(s.seed), toml_u64(s.block_size), s.max_events,
      s.keep_records, to_string(s.engine));
  // Written only when set, so configurations without them read as before.
  if (s.common_random_numbers) out += "common_random_numbers = true\n";
  // A half-width without a target statistic is a sensitivity study's stop
  // rule; min_realizations whenever a stop rule or its own value needs it.
  if (!s.target_statistic.empty())
    out += fmt::format("target_ci = \"{}:{}\"\n", s.target_statistic, toml_float(s.target_halfwidth));
  else if (s.target_halfwidth != 0.0)
    out += fmt::format("target_halfwidth = {}\n", toml_float(s.target_halfwidth));
  if (!s.target_statistic.empty() || s.target_halfwidth != 0.0 ||
      s.min_realizations != sweep_spec{}.min_realizations)
    out += fmt::format("min_realizations = {}{}\n", toml_u64(s.min_realizations),
                       s.sensitivity_statistic.empty()
                           ? ""
                           : "  # the design's rows before the stop rule (--min-samples)");
  if (!s.sensitivity_statistic.empty())
    out += fmt::format("sensitivity_statistic = \"{}\"\n", s.sensitivity_statistic);
  if (!(s.statistics == statistics_selection{})) {
    out += "statistics = [";
    const auto names = selected_group_names(s.statistics);
    for (std::size_t i = 0; i < names.size(); ++i) out += fmt::format("{}\"{}\"", i ? ", " : "", names[i]);
    out += "]\n";
  }
  if (s.burn_in != 0.0) out += fmt::format("burn_in = {}\n", toml_float(s.burn_in));
  if (!s.observe_times.empty())
    out += fmt::format("observe_times = {}\n", array(s.observe_times, 0, s.observe_times.size()));
  out += fmt::format("\n[histograms]\nbins = {}\nstick_duration_max = {}\nslip_duration_max = {}\n",
                     toml_u64(s.histograms.bins), toml_float(s.histograms.stick_duration_max),
                     toml_float(s.histograms.slip_duration_max));
  if (s.statistics.survival || !(s.survival == survival_spec{}))
    out += fmt::format("\n[survival]\nbins = {}\nstick_duration_max = {}\nslip_duration_max = {}\n",
                       toml_u64(s.survival.bins), toml_float(s.survival.stick_duration_max),
                       toml_float(s.survival.slip_duration_max));
  return out;
}

}  // namespace stickslip::io
