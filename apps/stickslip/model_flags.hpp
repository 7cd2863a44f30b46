// Model-parameter flags shared by `simulate` and `sweep`: one flag per
// parameter, named after the paper's symbol, with a descriptive alias
// (--lambda / --switch-rate, ...), plus --seed and --max-events. Values are
// kept as text and turned into numbers by the command: a scalar in
// `simulate`, a grid specification in `sweep` (see io::parse_grid).
#pragma once
#include <CLI/CLI.hpp>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "stickslip/parameters.hpp"

namespace stickslip::app {

struct model_flags {
  struct flag {
    std::string symbol;  // m k g mu V lambda ta c mu_s mu_k
    std::string text;    // as given on the command line
    CLI::Option* option = nullptr;
  };
  std::array<flag, std::size(recorded_parameter_names)> params;
  std::string belt_levels, belt_rates;  // lists "v1,v2,..." and "r1,r2"
  std::string belt_generator;           // rows "q11,q12;q21,q22"
  CLI::Option* belt_levels_option = nullptr;
  CLI::Option* belt_generator_option = nullptr;
  CLI::Option* belt_rates_option = nullptr;
  std::string seed_text, max_events_text, preset;
  CLI::Option* seed_option = nullptr;
  CLI::Option* preset_option = nullptr;
  CLI::Option* max_events_option = nullptr;
};

enum class flag_values { scalar, grid };

// Registers --preset NAME (presets.hpp), --m/--mass, --k/--stiffness, --g/--gravity, --mu/--friction-coefficient,
// --V/--belt-speed, --lambda/--switch-rate, --ta/--window, the family's
// --c/--damping, --mu-s/--static-friction, --mu-k/--kinetic-friction,
// --belt-levels, --belt-rates, and --seed, --max-events.
// `defaults` is shown in --help.
void add_model_flags(CLI::App& cmd, model_flags& f, flag_values kind,
                     const model_parameters& defaults);

// The model flags given on the command line, in the order they were given,
// except that --mu comes first: it sets mu_s and mu_k both, and --mu-s or
// --mu-k then refine it whatever their order.
[[nodiscard]] std::vector<const model_flags::flag*> given_model_flags(const CLI::App& cmd,
                                                                      const model_flags& f);

// The flag of a symbol: "--mu-s" for mu_s.
[[nodiscard]] std::string flag_name(const std::string& symbol);
// Flag name with its meaning, for messages: "--mu (friction coefficient)".
[[nodiscard]] std::string flag_label(const std::string& symbol);

// `base` with the --preset values if one was given (the parameters the
// preset names replace those of `base`), otherwise `base` unchanged.
[[nodiscard]] model_parameters apply_preset(const model_flags& f, model_parameters base);

// `base` with --belt-levels and --belt-rates applied if given.
[[nodiscard]] model_parameters apply_belt_flags(const model_flags& f, model_parameters base);

// `base` with every given flag applied as one number (and the belt flags),
// not validated.
[[nodiscard]] model_parameters apply_scalar_flags(const CLI::App& cmd, const model_flags& f,
                                                  model_parameters base);

// --seed and --max-events if given, otherwise the fallbacks.
[[nodiscard]] std::uint64_t resolve_seed(const model_flags& f, std::uint64_t fallback);
[[nodiscard]] std::int64_t resolve_max_events(const model_flags& f, std::int64_t fallback);

}  // namespace stickslip::app
