// Command-line syntax errors (unknown subcommand or flag, a flag given twice,
// a missing value) in the house form "stickslip: error: ...", with the
// nearest subcommand or flag as a suggestion (nearest_name.hpp), and exit code 2 (invalid
// input) like every other bad input. --help and --version keep CLI11's
// output and exit 0.
#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace stickslip::app {

// Prints the error for `e` (raised while parsing `args`, argv without the
// program name) and returns the process exit code.
[[nodiscard]] int report_parse_error(CLI::App& app, const CLI::ParseError& e,
                                     const std::vector<std::string>& args);

}  // namespace stickslip::app
