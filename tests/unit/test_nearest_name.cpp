// nearest_name (nearest_name.hpp), the one "did you mean" rule of the
// command line's parser, `plot` and the Python keywords: a likely typo is
// named, a word near nothing is not, and a short word must be close (a
// review found `--y X` taken for R and W_f for D_1 under the old rule).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "stickslip/nearest_name.hpp"

using stickslip::edit_distance;
using stickslip::nearest_name;

TEST(NearestName, EditDistanceCountsSwapsAsOneEdit) {
  EXPECT_EQ(edit_distance("", ""), 0u);
  EXPECT_EQ(edit_distance("abc", ""), 3u);
  EXPECT_EQ(edit_distance("trajectroy", "trajectory"), 1u);  // adjacent swap
  EXPECT_EQ(edit_distance("lamda", "lambda"), 1u);
  EXPECT_EQ(edit_distance("W_f", "D_1"), 2u);
}

TEST(NearestName, NamesLikelyTyposOnly) {
  const std::vector<std::string> flags = {"--lambda", "--realizations", "--trajectory", "--mu"};
  EXPECT_EQ(nearest_name("--lamda", flags), "--lambda");
  EXPECT_EQ(nearest_name("--realisations", flags), "--realizations");
  EXPECT_EQ(nearest_name("--trajectroy", flags), "--trajectory");
  EXPECT_EQ(nearest_name("--zzzzzz", flags), "");
  const std::vector<std::string> words = {"sweep", "simulate", "lam", "R", "D_1", "D"};
  EXPECT_EQ(nearest_name("swep", words), "sweep");
  EXPECT_EQ(nearest_name("lamda", words), "lam");  // 2 edits in 5 letters
  EXPECT_EQ(nearest_name("RR", words), "R");       // 1 edit in 2 letters
  EXPECT_EQ(nearest_name("DD", words), "D");
  // short words: at most |word| / 2 edits
  EXPECT_EQ(nearest_name("X", words), "");    // 1 edit would replace all of it
  EXPECT_EQ(nearest_name("W_f", words), "");  // 2 edits in 3 letters
  EXPECT_EQ(nearest_name("", words), "");
}
