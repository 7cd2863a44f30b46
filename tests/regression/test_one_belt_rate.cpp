// Regression (found by fuzz_family_toml): a belt given one rate
// (TOML `belt_rates = [1.0]`, `--belt-rates 1`) made validate(model_parameters)
// read belt_rates[1], past the end of the vector, through
// max_stick_duration() -> generator(), before validate_family counted the
// rates: a heap-buffer-overflow under AddressSanitizer (the release build
// went on to print the right error). Run under scripts/sanitizers.sh this
// test fails without the fix; everywhere it pins the message.
#include <gtest/gtest.h>

#include <string>

#include "stickslip/error.hpp"
#include "stickslip/parameters.hpp"

using namespace stickslip;

TEST(OneBeltRate, IsRefusedWithoutReadingPastTheRates) {
  for (const auto& levels : {std::vector<double>{-1.0, 0.5}, std::vector<double>{0.0, -1.0, 1.0}}) {
    model_parameters p;
    p.belt_levels = levels;
    p.belt_rates = {1.0};
    try {
      validate(p);
      FAIL() << "validate accepted one belt rate for " << levels.size() << " levels";
    } catch (const error& e) {
      EXPECT_EQ(e.code(), exit_code::invalid_input);
      EXPECT_NE(std::string(e.what()).find("belt-rates (count)"), std::string::npos) << e.what();
    }
  }
}

TEST(OneBeltRate, GeneratorStaysInsideTheRates) {
  model_parameters p;
  p.belt_levels = {-1.0, 0.5};
  p.belt_rates = {3.0};
  const auto q = p.generator();
  ASSERT_EQ(q.size(), 4u);
  EXPECT_EQ(q[1], 3.0);
  EXPECT_EQ(q[2], 3.0);
}

// The same input with a law or a grid axis on r2 (`r2 = "uniform(...)"`,
// `belt_rates = [6.0]`): set_parameter wrote belt_rates[1] past the end of
// a one-entry vector (heap-buffer-overflow WRITE under AddressSanitizer).
TEST(OneBeltRate, SettingTheSecondRateIsRefused) {
  model_parameters p;
  p.belt_levels = {6.0, -1.0};
  p.belt_rates = {6.0};
  try {
    set_parameter(p, "r2", 0.3);
    FAIL() << "set_parameter wrote r2 into one rate";
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::invalid_input);
    EXPECT_NE(std::string(e.what()).find("belt-rates (count)"), std::string::npos) << e.what();
  }
  EXPECT_EQ(p.belt_rates.size(), 1u);
}
