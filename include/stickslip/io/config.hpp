// Configuration: TOML files and grid specifications. Validation happens here,
// at the edge; errors name the key, the value and what is allowed.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "stickslip/sweep.hpp"

namespace stickslip::io {

// "0.1,0.5,3.8" (a list), "lin:a:b:n" (n values, a and b included),
// "log:a:b:n" (n values geometrically spaced, a, b > 0). `key` names the
// parameter in error messages.
[[nodiscard]] std::vector<double> parse_grid(std::string_view key, std::string_view text);

// Reads a sweep spec from TOML text (see docs/config.md for the keys).
// `origin` names the file in error messages.
[[nodiscard]] sweep_spec parse_sweep_toml(std::string_view toml_text, std::string_view origin);

// The full resolved spec as TOML (what goes into every output's attributes).
[[nodiscard]] std::string to_toml(const sweep_spec& s);

// One switch time per line; blank lines and lines starting with '#' are
// ignored. Validated: finite, >= 0, strictly increasing.
[[nodiscard]] std::vector<double> parse_switch_times(std::string_view text, std::string_view origin);
[[nodiscard]] std::vector<double> read_switch_times_file(const std::string& path);

}  // namespace stickslip::io
