// Configuration: TOML files, grid specifications, switch-time lists. This is
// the edge where text becomes values: every error names the key, the text and
// the problem (stickslip::error with exit_code::invalid_input).
// The TOML schema is documented in docs/config.md.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "stickslip/sweep.hpp"

namespace stickslip::io {

// One finite decimal number and nothing else (surrounding blanks ignored).
// Rejects empty text, trailing garbage ("1.5x"), "nan" and "inf".
[[nodiscard]] double parse_number(std::string_view key, std::string_view text);
// One whole number in [min, max] and nothing else ("-1" is rejected for min 0,
// never wrapped around).
[[nodiscard]] std::uint64_t parse_unsigned(std::string_view key, std::string_view text,
                                           std::uint64_t min = 0,
                                           std::uint64_t max = UINT64_MAX);

// Grid specification of one model parameter:
//   "0.1,0.5,3.8"  a list, in the order given
//   "lin:a:b:n"    n values evenly spaced from a to b, both included (n = 1 gives a)
//   "log:a:b:n"    n values geometrically spaced from a to b (a, b > 0)
// Every value must be finite and lie in the domain: > 0 for most model
// parameters, >= 0 for the damping c, any number for a belt level vI
// (grid_domain_of); a log range needs a, b > 0 in any domain.
// `key` names the parameter in error messages (e.g. "--lambda", "grid.mu").
enum class grid_domain : unsigned char { positive, non_negative, any };
[[nodiscard]] grid_domain grid_domain_of(std::string_view symbol);
// The order of the axes that flags or Python keywords add (docs/cli.md):
// lambda first, then mu, then the others as given (stable).
void order_added_axes(std::vector<axis>& axes);
// The belt as --belt-levels "v1,v2,..." (at least 2) and --belt-generator
// "q11,q12;q21,q22" (square) give it; Python passes its lists as this text,
// so that both refuse alike. Exit 2 naming the flag (and the row).
[[nodiscard]] std::vector<double> parse_belt_levels(std::string_view text);
[[nodiscard]] std::vector<double> parse_belt_generator(std::string_view text);
[[nodiscard]] std::vector<double> parse_grid(std::string_view key, std::string_view text,
                                             grid_domain d = grid_domain::positive);

// True when `text` is a single plain number (not a list, not lin:/log:), i.e.
// a fixed value rather than a grid axis.
[[nodiscard]] bool is_single_value(std::string_view text) noexcept;

// "fast" or "reference" (the engine never changes results, only speed).
[[nodiscard]] sweep_engine parse_engine(std::string_view key, std::string_view text);
// "STAT:HALFWIDTH" (e.g. "R:0.002") into s.target_statistic and
// s.target_halfwidth; throws naming `key` when malformed or unknown.
void parse_target_ci(std::string_view key, std::string_view text, sweep_spec& s);

// Uncertain parameters (uncertainty/parameter_law.hpp) in a spec, as every
// front end (flags, TOML keys, Python keywords) sets them:
//   set_law     makes `symbol` (canonical) a law: it replaces that symbol's
//               law or grid axis, and the base value of a scalar goes back to
//               its default (model_parameters{}), so that to_toml, which writes
//               the law in its place, reads back to the same spec. Laws are
//               kept in one canonical order (m k g mu V lambda ta c mu_s mu_k,
//               then v1..vN, then r1 r2), so that a realization's draws (word i
//               of its substream for law i) do not depend on the order the
//               flags or keys were given in.
//   drop_law    removes `symbol`'s law, if any (a value or a grid replaces it).
//   find_law    the law of `symbol`, or nullptr.
void set_law(sweep_spec& s, const std::string& symbol, parameter_law law);
void drop_law(sweep_spec& s, std::string_view symbol);
[[nodiscard]] const parameter_law* find_law(const sweep_spec& s, std::string_view symbol) noexcept;
// The laws in set_law's canonical order.
void sort_laws(std::vector<uncertain_parameter>& laws);

// Reads a sweep spec from TOML text (see docs/config.md for the keys). Keys
// not given keep the defaults of sweep_spec. Does not call validate(): flags
// may still override values; the caller validates the final spec.
// `origin` names the file in error messages (file:line:col).
[[nodiscard]] sweep_spec parse_sweep_toml(std::string_view toml_text, std::string_view origin);
// The same, from a file (io_failure if it cannot be read).
[[nodiscard]] sweep_spec read_sweep_toml_file(const std::string& path);

// The full resolved spec as TOML: what goes into every output's attributes.
// Round trip: parse_sweep_toml(to_toml(s), ...) == s for any spec whose laws
// were set by set_law (an uncertain parameter's [model] key holds its law in
// canonical text, to_string(law); its base value is the default).
[[nodiscard]] std::string to_toml(const sweep_spec& s);

// A replayed belt: switch times, and the level each switch goes to.
struct switch_schedule {
  std::vector<double> times;
  std::vector<std::size_t> levels;  // level index (0-based), or empty: alternate two levels
};
// One switch per line, "t" (two levels: go to the other one) or "t level"
// (level number 1..level_count), not mixed; blank lines and '#' comments are
// ignored. Times validated as below; a level outside 1..level_count is an
// error naming origin:line, the value and the range.
[[nodiscard]] switch_schedule parse_switch_schedule(std::string_view text, std::string_view origin,
                                                    std::size_t level_count);
[[nodiscard]] switch_schedule read_switch_schedule_file(const std::string& path,
                                                        std::size_t level_count);

// "+1", "-1", "stationary" (or the older "random") on two levels; a level
// number 1..n or "stationary" on n levels: initial_condition_law::belt_start.
[[nodiscard]] int parse_belt_start(std::string_view key, std::string_view text,
                                   std::size_t level_count);
// The inverse, for outputs: "stationary", "+1", "-1", "3".
[[nodiscard]] std::string belt_start_text(int belt_start);
// "1,-1,0": finite numbers (belt levels, rates); errors name the entry.
[[nodiscard]] std::vector<double> parse_value_list(std::string_view key, std::string_view text);

// One switch time per line; blank lines and '#' comments are ignored.
// Validated: finite, >= 0, strictly increasing; errors name origin:line.
[[nodiscard]] std::vector<double> parse_switch_times(std::string_view text, std::string_view origin);
[[nodiscard]] std::vector<double> read_switch_times_file(const std::string& path);
// Comma-separated switch times ("1.5,2,7.25"), validated the same way;
// errors name `key` and the entry number.
[[nodiscard]] std::vector<double> parse_switch_time_list(std::string_view key,
                                                         std::string_view text);

}  // namespace stickslip::io
