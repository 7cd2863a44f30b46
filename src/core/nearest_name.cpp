#include "stickslip/nearest_name.hpp"

#include <algorithm>

namespace stickslip {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  // Optimal string alignment distance, O(|a| |b|).
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

std::string nearest_name(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  // At most max(2, |word| / 3) edits, and for a word of 3 letters or fewer
  // at most |word| / 2: a short word is not "near" another by replacing
  // most of it (a review found `--y X` taken for R and W_f for D_1).
  const std::size_t n = word.size();
  std::size_t best_distance = (n <= 3 ? n / 2 : std::max<std::size_t>(2, n / 3)) + 1;
  for (const auto& c : candidates)
    if (const auto dist = edit_distance(word, c); dist < best_distance) {
      best = c;
      best_distance = dist;
    }
  return best;
}

std::string did_you_mean(const std::string& guess) {
  return guess.empty() ? "" : "; did you mean " + guess + "?";
}

}  // namespace stickslip
