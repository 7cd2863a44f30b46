// Model-parameter flags shared by `simulate`, `sweep` and `peak`: one flag per
// parameter, named after the paper's symbol, with a descriptive alias
// (--lambda / --switch-rate, ...), plus --seed and --max-events. Values are
// kept as text and turned into numbers by the command: a scalar in
// `simulate`, a grid specification in `sweep` (see io::parse_grid). Any of
// them may instead hold a law ('gamma(mean=5,cv=0.2)', parameter_law.hpp),
// told apart by looks_like_law: an uncertain parameter.
#pragma once
#include <CLI/CLI.hpp>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "stickslip/parameters.hpp"
#include "stickslip/sweep.hpp"
#include "stickslip/uncertainty/parameter_law.hpp"

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

// Whether a flag holds a law rather than a value or a grid.
[[nodiscard]] bool holds_law(const model_flags::flag& flag) noexcept;

// The given flags that hold laws, parsed (parse_law: exit 2 naming the flag,
// the law and the problem), in io::sort_laws' canonical order.
[[nodiscard]] std::vector<uncertain_parameter> given_laws(const CLI::App& cmd,
                                                          const model_flags& f);

// Throws invalid_input naming the first flag that holds a law: `command`
// cannot use one, and `instead` says what to do.
void refuse_laws(const CLI::App& cmd, const model_flags& f, const std::string& command,
                 const std::string& instead);

// Applies --preset, the belt flags and every given parameter flag to `spec`,
// each flag's text read as one of three things:
// - a law (looks_like_law): the parameter is uncertain (io::set_law, which
//   replaces an axis, value or law the spec had for it);
// - one number: the fixed value (dropping the spec's axis or law of it);
// - a grid (a list, lin:, log:): an axis, replacing the spec's axis of that
//   parameter in place or appended after its axes (lambda, then mu, then the
//   others in the order given). Without `grids_allowed` (a command that runs
//   one point, such as `sensitivity`) a grid is refused, exit 2.
// Bad text exits 2 naming the flag. Nothing is validated beyond the flag.
// Like apply_scalar_flags, prints only_in_the_stream_key's note (--mu beside
// --mu-s and --mu-k) on stderr as "stickslip: warning: ..."; here a
// refinement the spec already held (a --config file's value, grid axis or
// law of mu_s or mu_k) counts as given beside a --mu flag.
void apply_model_flags(const CLI::App& cmd, const model_flags& f, sweep_spec& spec,
                       bool grids_allowed);

// `base` with every given flag applied as one number (and the belt flags),
// not validated. Flags that hold laws are left out (given_laws reads them).
// Prints only_in_the_stream_key's note (--mu beside --mu-s and --mu-k).
[[nodiscard]] model_parameters apply_scalar_flags(const CLI::App& cmd, const model_flags& f,
                                                  model_parameters base);

// --seed and --max-events if given, otherwise the fallbacks.
[[nodiscard]] std::uint64_t resolve_seed(const model_flags& f, std::uint64_t fallback);
[[nodiscard]] std::int64_t resolve_max_events(const model_flags& f, std::int64_t fallback);

}  // namespace stickslip::app
