// Regression: `--lambda 1,1` was accepted. The two grid points
// have the same parameters, hence the same point_key and the same random
// streams: they are copies, not independent replicates, and their coordinate
// cannot be selected from. validate() must refuse a value given twice on one
// axis, naming the axis, the value and both entries.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "stickslip/error.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

std::string validation_error(const sweep_spec& s) {
  try {
    validate(s);
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::invalid_input);
    return e.what();
  }
  ADD_FAILURE() << "validate accepted the spec";
  return {};
}

TEST(DuplicateGridValues, AreRefusedWithAxisValueAndEntries) {
  sweep_spec s;
  s.axes = {{"lambda", {0.5, 1.0, 1.0}}, {"mu", {5.0}}};
  EXPECT_THAT(validation_error(s),
              AllOf(HasSubstr("lambda"), HasSubstr("#2 and #3"), HasSubstr("random stream")));
  s.axes = {{"lambda", {1.0}}, {"mu", {7.0, 0.5, 7.0}}};
  EXPECT_THAT(validation_error(s), AllOf(HasSubstr("mu"), HasSubstr("#1 and #3")));
}

TEST(DuplicateGridValues, TheSameValueOnTwoAxesIsFine) {
  sweep_spec s;
  s.axes = {{"lambda", {1.0, 2.0}}, {"V", {1.0, 2.0}}};
  EXPECT_NO_THROW(validate(s));
}

}  // namespace
}  // namespace stickslip
