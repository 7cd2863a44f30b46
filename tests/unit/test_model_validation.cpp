// Bad input for the model family: every rejection names the parameter, the
// value and the allowed range, with exit code 2 (invalid_input).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/model/belt_chain.hpp"
#include "stickslip/model/oscillator_model.hpp"

namespace stickslip {
namespace {

// Runs validate() and returns the message; fails unless it throws with exit code 2.
template <class T>
std::string rejection(const T& value) {
  try {
    validate(value);
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::invalid_input);
    return e.what();
  }
  ADD_FAILURE() << "accepted";
  return {};
}

void expect_mentions(const std::string& message, std::initializer_list<const char*> parts) {
  for (const char* p : parts) EXPECT_NE(message.find(p), std::string::npos) << message << " lacks " << p;
}

TEST(ModelValidation, DefaultsAndThePaperModelAreValid) {
  EXPECT_NO_THROW(validate(oscillator_model{}));
  EXPECT_NO_THROW(validate(model_of(model_parameters{})));
  oscillator_model m;
  m.belt = markov_belt{{-1.0, 0.0, 2.5}, {-3, 1, 2, 0.5, -0.5, 0, 1, 1, -2}};
  m.damping = 0.7;
  m.static_friction = 6.0;
  EXPECT_NO_THROW(validate(m));
}

TEST(ModelValidation, KineticAboveStaticFriction) {
  oscillator_model m;
  m.static_friction = 2.0;
  m.kinetic_friction = 3.0;
  expect_mentions(rejection(m), {"mu_s", "2", ">= mu_k = 3"});
}

TEST(ModelValidation, NegativeOrNonFiniteDamping) {
  oscillator_model m;
  m.damping = -0.5;
  expect_mentions(rejection(m), {"c (damping)", "-0.5", ">= 0"});
  m.damping = std::numeric_limits<double>::infinity();
  expect_mentions(rejection(m), {"c (damping)", "inf", ">= 0"});
}

TEST(ModelValidation, NonPositiveKineticFriction) {
  oscillator_model m;
  m.kinetic_friction = 0.0;
  expect_mentions(rejection(m), {"mu_k", "0", "> 0"});
}

// A belt so slow against the band that a slip would be shorter than the
// resolution of t (fuzz_model_family's dropped slip and missed damped return,
// both at omega_0 a_s / |v| ~ 1e52). The bound sits at 1e12; resting levels
// (v = 0) are not moving levels and stay allowed.
TEST(ModelValidation, ABeltTooSlowForTheResolutionOfTime) {
  oscillator_model m;  // m = k = 1: omega_0 = 1, a_s = mu_s g
  m.static_friction = m.kinetic_friction = 5.0;
  const double band_speed = m.natural_frequency() * m.static_band_half_width();
  m.belt = markov_belt{{0.0, -band_speed * 1.0001e-12}, {-1, 1, 1, -1}};
  EXPECT_NO_THROW(validate(m));
  m.belt.levels[1] = -band_speed * 0.9999e-12;
  expect_mentions(rejection(m), {"belt level v2", "omega_0 a_s / 1e12", "resolution of t"});
  model_parameters paper;  // V: the paper's belt +V, -V
  paper.belt_speed = 1e-12;
  expect_mentions(rejection(model_of(paper)), {"belt level v1", "V for the paper's belt"});
}

// Over-damped relaxation faster than the resolution of t (fuzz_model_family:
// c = 9.7e15, m = 0.078, t_a = 0.52, a return 1.5e-16 s after the start).
TEST(ModelValidation, DampingFasterThanTheResolutionOfTime) {
  oscillator_model m;
  m.window = 0.5;
  m.damping = 2.0 * m.mass * 1e12 / m.window;  // gamma t_a = 1e12 exactly
  EXPECT_NO_THROW(validate(m));
  m.damping *= 1.0001;
  expect_mentions(rejection(m), {"c (damping)", "gamma t_a = c t_a / (2 m) <= 1e12",
                                 "resolution of t"});
}

TEST(ModelValidation, FewerThanTwoLevels) {
  expect_mentions(rejection(markov_belt{{1.0}, {0.0}}), {"belt levels", "1", "at least 2"});
}

TEST(ModelValidation, EqualLevels) {
  const auto message = rejection(markov_belt{{1.0, 0.5, 1.0}, {-2, 1, 1, 1, -2, 1, 1, 1, -2}});
  expect_mentions(message, {"belt level v3", "1", "distinct", "v1"});
}

TEST(ModelValidation, NegativeAndNonFiniteRates) {
  expect_mentions(rejection(two_level_belt(1, -1, -1.0, 1.0)), {"q1,2", "-1", ">= 0"});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_mentions(rejection(markov_belt{{1, -1}, {-1, 1, nan, 1}}), {"q2,1", "nan", "finite"});
}

TEST(ModelValidation, ALevelThatIsNeverLeft) {
  expect_mentions(rejection(two_level_belt(1, -1, 1.0, 0.0)),
                  {"leaving belt level v2", "0", "> 0"});
}

TEST(ModelValidation, GeneratorRowThatDoesNotSumToZero) {
  expect_mentions(rejection(markov_belt{{1, -1}, {-1, 1, 2, -1}}),
                  {"generator row 2 sum", "1", "0 (q2,2 = -sum"});
}

TEST(ModelValidation, ReplayedLevelThatDoesNotExist) {
  const std::vector<level_switch> ok{{0.5, 1}, {1.0, 0}};
  EXPECT_NO_THROW(validate_level_switches(ok, 2, 0));
  const std::vector<level_switch> bad{{0.5, 1}, {1.0, 2}};
  try {
    validate_level_switches(bad, 2, 0);
    ADD_FAILURE() << "accepted";
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::invalid_input);
    expect_mentions(e.what(), {"switch #2 level", "2", "0..1"});
  }
}

TEST(ModelValidation, ReplayedSwitchThatKeepsTheLevel) {
  const std::vector<level_switch> from_start{{0.5, 0}};
  const std::vector<level_switch> repeated{{0.5, 2}, {0.7, 1}, {0.9, 1}};
  for (const auto& [switches, start, which] :
       {std::tuple{from_start, std::size_t{0}, "switch #1 level"},
        std::tuple{repeated, std::size_t{0}, "switch #3 level"}}) {
    try {
      validate_level_switches(switches, 3, start);
      ADD_FAILURE() << "accepted";
    } catch (const error& e) {
      EXPECT_EQ(e.code(), exit_code::invalid_input);
      expect_mentions(e.what(), {which, "other than the current one"});
    }
  }
  const std::vector<level_switch> fine{{0.5, 2}, {0.7, 1}};
  EXPECT_NO_THROW(validate_level_switches(fine, 3, 0));
}

TEST(ModelValidation, InitialStateOnAnExistingLevel) {
  const markov_belt belt = two_level_belt(1.0, -1.0, 1.0, 1.0);
  EXPECT_NO_THROW(validate(model_initial_state{0.5, -0.2, 1}, belt));
  try {
    validate(model_initial_state{0.5, -0.2, 2}, belt);
    ADD_FAILURE() << "accepted";
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::invalid_input);
    expect_mentions(e.what(), {"belt-start", "2", "0..1"});
  }
  try {
    validate(model_initial_state{std::numeric_limits<double>::quiet_NaN(), 0.0, 0}, belt);
    ADD_FAILURE() << "accepted";
  } catch (const error& e) {
    expect_mentions(e.what(), {"x0", "nan", "finite"});
  }
}

TEST(ModelValidation, PaperModelIsTheFamilysSpecialCase) {
  model_parameters p;
  p.friction_coefficient = 0.3;
  p.belt_speed = 1.5;
  p.switch_rate = 2.0;
  const oscillator_model m = model_of(p);
  EXPECT_EQ(m.static_friction, 0.3);
  EXPECT_EQ(m.kinetic_friction, 0.3);
  EXPECT_EQ(m.damping, 0.0);
  EXPECT_EQ(m.belt, (markov_belt{{1.5, -1.5}, {-2, 2, 2, -2}}));
  EXPECT_EQ(m.static_band_half_width(), p.band_half_width());
}

}  // namespace
}  // namespace stickslip
