// The nearest of some names to a mistyped one, for "did you mean" in
// messages: the command line's subcommands and flags, and `plot`'s
// statistics.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace stickslip {

// Edit distance (insertions, deletions, substitutions, adjacent swaps).
[[nodiscard]] std::size_t edit_distance(const std::string& a, const std::string& b);

// The candidate nearest to `word` if it is near enough to be a likely typo
// (distance <= max(2, |word| / 3), or <= |word| / 2 for a word of 3 letters
// or fewer), else "".
[[nodiscard]] std::string nearest_name(const std::string& word,
                                       const std::vector<std::string>& candidates);

// "; did you mean GUESS?" for a message's end, or "" without a guess.
[[nodiscard]] std::string did_you_mean(const std::string& guess);

}  // namespace stickslip
