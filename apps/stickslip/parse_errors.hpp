// Command-line syntax errors (unknown subcommand or flag, a flag given twice,
// a missing value) in the house form "stickslip: error: ...", with the
// nearest subcommand or flag as a suggestion, and exit code 2 (invalid
// input) like every other bad input. --help and --version keep CLI11's
// output and exit 0.
#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace stickslip::app {

// Edit distance (insertions, deletions, substitutions, adjacent swaps).
[[nodiscard]] std::size_t edit_distance(const std::string& a, const std::string& b);

// The candidate nearest to `word` if it is near enough to be a likely typo
// (distance <= max(2, |word| / 3)), else "".
[[nodiscard]] std::string nearest(const std::string& word, const std::vector<std::string>& candidates);

// Prints the error for `e` (raised while parsing `args`, argv without the
// program name) and returns the process exit code.
[[nodiscard]] int report_parse_error(CLI::App& app, const CLI::ParseError& e,
                                     const std::vector<std::string>& args);

}  // namespace stickslip::app
