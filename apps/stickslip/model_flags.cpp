#include "model_flags.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "stickslip/error.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/presets.hpp"
#include "stickslip/io/config.hpp"

namespace stickslip::app {

void add_model_flags(CLI::App& cmd, model_flags& f, flag_values kind,
                     const model_parameters& defaults) {
  std::string presets;
  for (const auto& p : parameter_presets())
    presets += fmt::format("; {}: {}", p.name, p.description);
  f.preset_option =
      cmd.add_option("--preset", f.preset,
                     "a named parameter set, applied before the parameter flags" + presets)
          ->type_name("NAME")
          ->group("Model parameters (the paper's symbols)");
  for (std::size_t i = 0; i < f.params.size(); ++i) {
    const std::string symbol = recorded_parameter_names[i];
    const auto& info = info_for(symbol);
    auto& flag = f.params[i];
    flag.symbol = symbol;
    const std::string what =
        kind == flag_values::grid
            ? fmt::format("{} [{}]: a value, a list 'a,b,c', 'lin:a:b:n' or 'log:a:b:n', or a "
                          "law such as 'gamma(mean=M,cv=C)' (default {})",
                          info.description, info.units, parameter_value(defaults, symbol))
            : fmt::format("{} [{}] (default {})", info.description, info.units,
                          parameter_value(defaults, symbol));
    const bool family = i >= std::size(parameter_names);
    flag.option = cmd.add_option(fmt::format("{},--{}", flag_name(symbol), info.long_name), flag.text, what)
                      ->type_name(kind == flag_values::grid ? "GRID" : "X")
                      ->group(family ? "Model family (docs/models.md)"
                                     : "Model parameters (the paper's symbols)");
  }
  f.belt_levels_option =
      cmd.add_option("--belt-levels", f.belt_levels,
                     "belt velocity levels v1,v2,... [m/s]: n >= 2 distinct values, any sign, 0 "
                     "allowed (default +V,-V); more than two need --belt-generator")
          ->type_name("LIST")
          ->group("Model family (docs/models.md)");
  f.belt_rates_option =
      cmd.add_option("--belt-rates", f.belt_rates,
                     "two-level belt: the rates r1,r2 [1/s] of leaving the first and the second "
                     "level (default lambda,lambda)")
          ->type_name("R1,R2")
          ->group("Model family (docs/models.md)");
  f.belt_generator_option =
      cmd.add_option("--belt-generator", f.belt_generator,
                     "the belt's generator Q [1/s] for any number of levels: rows separated by "
                     "';', rates by ',' (q_ij >= 0 off the diagonal, each row summing to 0), "
                     "e.g. '-2,1,1;1,-1,0;0.5,0.5,-1'")
          ->type_name("Q")
          ->group("Model family (docs/models.md)");
  f.seed_option = cmd.add_option("--seed", f.seed_text,
                                 "seed of the random streams, 0 .. 2^64-1 (default 1)")
                      ->type_name("S");
  f.max_events_option =
      cmd.add_option("--max-events", f.max_events_text,
                     fmt::format("bound on events per realization; hitting it is an error "
                                 "(default {})",
                                 default_max_events))
          ->type_name("N");
}

std::vector<const model_flags::flag*> given_model_flags(const CLI::App& cmd,
                                                        const model_flags& f) {
  std::vector<const model_flags::flag*> given;
  for (const CLI::Option* opt : cmd.parse_order())
    for (const auto& flag : f.params)
      if (flag.option == opt &&
          std::find(given.begin(), given.end(), &flag) == given.end())
        given.push_back(&flag);
  order_assignments(given, [](const model_flags::flag* g) -> std::string_view { return g->symbol; });
  return given;
}

std::string flag_name(const std::string& symbol) { return flag_of(symbol); }

std::string flag_label(const std::string& symbol) {
  return fmt::format("{} ({})", flag_name(symbol), info_for(symbol).description);
}

model_parameters apply_belt_flags(const model_flags& f, model_parameters base) {
  if (f.belt_levels_option && f.belt_levels_option->count() > 0)
    base.belt_levels = io::parse_belt_levels(f.belt_levels);
  if (f.belt_rates_option && f.belt_rates_option->count() > 0)
    base.belt_rates = io::parse_value_list("--belt-rates", f.belt_rates);
  if (f.belt_generator_option && f.belt_generator_option->count() > 0)
    base.belt_generator = io::parse_belt_generator(f.belt_generator);
  return base;
}

model_parameters apply_preset(const model_flags& f, model_parameters base) {
  if (!f.preset_option || f.preset_option->count() == 0) return base;
  const auto& preset = find_preset("--preset", f.preset).parameters;
  base.mass = preset.mass;
  base.stiffness = preset.stiffness;
  base.gravity = preset.gravity;
  base.belt_speed = preset.belt_speed;
  base.window = preset.window;
  return base;
}

bool holds_law(const model_flags::flag& flag) noexcept { return looks_like_law(flag.text); }

std::vector<uncertain_parameter> given_laws(const CLI::App& cmd, const model_flags& f) {
  std::vector<uncertain_parameter> laws;
  for (const auto* flag : given_model_flags(cmd, f))
    if (holds_law(*flag))
      laws.push_back({flag->symbol, parse_law(flag->text, flag_name(flag->symbol))});
  io::sort_laws(laws);
  return laws;
}

void refuse_laws(const CLI::App& cmd, const model_flags& f, const std::string& command,
                 const std::string& instead) {
  for (const auto* flag : given_model_flags(cmd, f))
    if (holds_law(*flag))
      throw invalid_value(flag_label(flag->symbol), flag->text,
                          fmt::format("a number: `stickslip {}` does not take laws; {}", command,
                                      instead));
}

// The note of only_in_the_stream_key for the given flags, and for the
// symbols a --config file set besides them (`also_set`).
void note_unused_model_flags(const CLI::App& cmd, const model_flags& f,
                             const std::vector<std::string>& also_set = {}) {
  std::vector<given_parameter> values;
  for (const auto* g : given_model_flags(cmd, f)) values.push_back({g->symbol, g->text});
  for (const auto& symbol : also_set) values.push_back({symbol, "", true});
  if (const auto note = only_in_the_stream_key(values); !note.empty())
    fmt::print(stderr, "stickslip: warning: {}\n", note);
}

// The refinements of the given flags' symbols (mu_s, mu_k of --mu) that a
// --config file's axis or law sets, and no flag. (A file's value of mu_s or
// mu_k is cleared by a --mu number, which then sets the friction: flags come
// after the file.)
std::vector<std::string> refinements_set_in(const CLI::App& cmd, const model_flags& f,
                                            const sweep_spec& spec) {
  std::vector<std::string> out;
  const auto flags = given_model_flags(cmd, f);
  for (const auto* g : flags)
    for (const auto& r : refinements_of(g->symbol)) {
      const auto named = [&](const auto& x) { return x.symbol == r; };
      if (std::any_of(flags.begin(), flags.end(), [&](const auto* h) { return h->symbol == r; }))
        continue;  // a flag gives it
      const bool on_axis = std::any_of(spec.axes.begin(), spec.axes.end(),
                                       [&](const axis& a) { return a.name == r; });
      if (on_axis || std::any_of(spec.uncertain.begin(), spec.uncertain.end(), named))
        out.push_back(r);
    }
  return out;
}

model_parameters apply_scalar_flags(const CLI::App& cmd, const model_flags& f,
                                    model_parameters base) {
  base = apply_belt_flags(f, std::move(base));
  std::vector<parameter_assignment> values;
  for (const auto* flag : given_model_flags(cmd, f))
    if (!holds_law(*flag))
      values.push_back({flag->symbol, io::parse_number(flag_label(flag->symbol), flag->text)});
  base = assign(std::move(base), std::move(values));
  note_unused_model_flags(cmd, f);  // after every value passed its checks
  return base;
}

void apply_model_flags(const CLI::App& cmd, const model_flags& f, sweep_spec& spec,
                       bool grids_allowed) {
  spec.base = apply_belt_flags(f, apply_preset(f, std::move(spec.base)));
  std::vector<axis> added;
  for (const auto* flag : given_model_flags(cmd, f)) {
    const auto& sym = flag->symbol;
    if (holds_law(*flag)) {
      io::set_law(spec, sym, parse_law(flag->text, flag_name(sym)));
      continue;
    }
    io::drop_law(spec, sym);
    auto in_spec = std::find_if(spec.axes.begin(), spec.axes.end(),
                                [&](const axis& a) { return a.name == sym; });
    if (io::is_single_value(flag->text)) {
      assign_value(spec.base, sym, io::parse_number(flag_label(sym), flag->text));
      if (in_spec != spec.axes.end()) spec.axes.erase(in_spec);
      continue;
    }
    if (!grids_allowed)
      throw invalid_value(flag_label(sym), flag->text,
                          fmt::format("a value or a law such as 'uniform(2,7)': `stickslip {}` "
                                      "has no grid axes (`stickslip sweep` takes grids)",
                                      cmd.get_name()));
    auto values = io::parse_grid(flag_name(sym), flag->text, io::grid_domain_of(sym));
    if (in_spec != spec.axes.end())
      in_spec->values = std::move(values);
    else
      added.push_back({sym, std::move(values)});
  }
  io::order_added_axes(added);
  spec.axes.insert(spec.axes.end(), added.begin(), added.end());
  // after every value passed its checks
  note_unused_model_flags(cmd, f, refinements_set_in(cmd, f, spec));
}

std::uint64_t resolve_seed(const model_flags& f, std::uint64_t fallback) {
  if (!f.seed_option || f.seed_option->count() == 0) return fallback;
  return io::parse_unsigned("--seed", f.seed_text);
}

std::int64_t resolve_max_events(const model_flags& f, std::int64_t fallback) {
  if (!f.max_events_option || f.max_events_option->count() == 0) return fallback;
  return static_cast<std::int64_t>(io::parse_unsigned(
      "--max-events", f.max_events_text, 1,
      static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())));
}

}  // namespace stickslip::app
