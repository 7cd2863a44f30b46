// The presets name exactly the parameter sets the paper study runs
// (printed: k = 4; concluded, what the figures used: k = 40).
#include <gtest/gtest.h>

#include "stickslip/error.hpp"
#include "stickslip/study/design.hpp"
#include "stickslip/presets.hpp"

namespace stickslip {
namespace {

TEST(Presets, AreTheStudysParameterSets) {
  EXPECT_EQ(find_preset("--preset", "paper-printed").parameters, study::printed_parameters().base);
  EXPECT_EQ(find_preset("--preset", "paper-figures").parameters,
            study::concluded_parameters().base);
  EXPECT_EQ(find_preset("--preset", "paper-figures").parameters.stiffness, 40.0);
  EXPECT_EQ(find_preset("--preset", "paper-printed").parameters, model_parameters{});
}

TEST(Presets, UnknownNameListsTheKnownOnes) {
  try {
    (void)find_preset("--preset", "paper");
    FAIL() << "accepted an unknown preset";
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::invalid_input);
    EXPECT_NE(std::string(e.what()).find("paper-printed or paper-figures"), std::string::npos);
  }
}

}  // namespace
}  // namespace stickslip
