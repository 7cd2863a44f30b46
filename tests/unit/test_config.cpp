// io/config: grid specifications, TOML sweep configuration (round trip and
// every class of error), switch-time lists. Errors must name the key, the
// offending text and the problem, and carry exit_code::invalid_input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>

#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"

namespace stickslip::io {
namespace {

using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

// The message of the stickslip::error that `f` throws ("" if none).
template <class F>
std::string error_of(F&& f, exit_code expected = exit_code::invalid_input) {
  try {
    f();
  } catch (const error& e) {
    EXPECT_EQ(e.code(), expected) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no stickslip::error thrown";
  return {};
}

// ---- grid specifications ----

TEST(ParseGrid, ListKeepsOrderAndExactValues) {
  EXPECT_THAT(parse_grid("lambda", "0.1,0.5,3.8"), ElementsAre(0.1, 0.5, 3.8));
  EXPECT_THAT(parse_grid("lambda", " 3.8 , 0.1 "), ElementsAre(3.8, 0.1));
  EXPECT_THAT(parse_grid("mu", "5"), ElementsAre(5.0));
  EXPECT_THAT(parse_grid("mu", "+2,1e-3"), ElementsAre(2.0, 1e-3));
}

TEST(ParseGrid, LinearRangeIncludesBothEnds) {
  const auto v = parse_grid("mu", "lin:0.5:7:8");
  ASSERT_EQ(v.size(), 8u);
  EXPECT_EQ(v.front(), 0.5);
  EXPECT_EQ(v.back(), 7.0);
  for (std::size_t i = 0; i < v.size(); ++i) EXPECT_NEAR(v[i], 0.5 + 6.5 * i / 7.0, 1e-15);
  EXPECT_THAT(parse_grid("mu", "lin:1:3:3"), ElementsAre(1.0, 2.0, 3.0));
  EXPECT_THAT(parse_grid("mu", "lin:3:1:3"), ElementsAre(3.0, 2.0, 1.0));
}

TEST(ParseGrid, LogRangeIsGeometricWithExactEnds) {
  const auto v = parse_grid("lambda", "log:0.1:30:40");
  ASSERT_EQ(v.size(), 40u);
  EXPECT_EQ(v.front(), 0.1);
  EXPECT_EQ(v.back(), 30.0);
  const double ratio = std::pow(300.0, 1.0 / 39);
  for (std::size_t i = 1; i < v.size(); ++i) EXPECT_NEAR(v[i] / v[i - 1], ratio, 1e-12);
  EXPECT_THAT(parse_grid("lambda", "log:1:100:3"), ElementsAre(1.0, ::testing::DoubleEq(10.0), 100.0));
}

TEST(ParseGrid, SinglePointRangeGivesA) {
  EXPECT_THAT(parse_grid("lambda", "lin:2:9:1"), ElementsAre(2.0));
  EXPECT_THAT(parse_grid("lambda", "log:0.3:30:1"), ElementsAre(0.3));
}

struct bad_grid {
  const char* text;
  const char* problem;  // a phrase the message must contain
};

class ParseGridError : public ::testing::TestWithParam<bad_grid> {};

TEST_P(ParseGridError, NamesKeyTextAndProblem) {
  const auto& c = GetParam();
  const auto msg = error_of([&] { (void)parse_grid("--lambda", c.text); });
  EXPECT_THAT(msg, AllOf(HasSubstr("--lambda"), HasSubstr(std::string("'") + c.text + "'"),
                         HasSubstr(c.problem)));
}

INSTANTIATE_TEST_SUITE_P(
    AllClasses, ParseGridError,
    ::testing::Values(bad_grid{"", "empty list"}, bad_grid{"  ", "empty list"},
                      bad_grid{"0.1,,2", "empty entry"}, bad_grid{"1,", "empty entry"},
                      bad_grid{"nan", "not finite"}, bad_grid{"1,inf", "not finite"},
                      bad_grid{"lin:1:nan:3", "not finite"}, bad_grid{"log:0.1:30:0", "n = 0"},
                      bad_grid{"lin:1:2:-4", "n >= 1"}, bad_grid{"lin:1:2:2.5", "whole number"},
                      bad_grid{"lin:1:2", "4 fields"}, bad_grid{"abc", "not a number"},
                      bad_grid{"1.5x", "trailing characters 'x'"},
                      bad_grid{"0.1,0.5;3", "trailing characters"},
                      bad_grid{"-0.1,1", "entry #1 = -0.1"}, bad_grid{"1,0", "values > 0"},
                      bad_grid{"log:0:1:3", "a = 0"}, bad_grid{"log:1:-2:3", "b = -2"},
                      bad_grid{"geo:1:2:3", "lin:a:b:n"}, bad_grid{"1e999", "out of the range"},
                      bad_grid{"lin:1:2:99999999", "n <= 1000000"}));

TEST(ParseNumber, StrictWholeText) {
  EXPECT_EQ(parse_number("--x0", " -0.25 "), -0.25);
  EXPECT_EQ(parse_number("--x0", "0.1"), 0.1);
  EXPECT_THAT(error_of([] { (void)parse_number("--x0", "1e"); }), HasSubstr("--x0"));
  EXPECT_THAT(error_of([] { (void)parse_number("--x0", "-inf"); }), HasSubstr("not finite"));
  EXPECT_THAT(error_of([] { (void)parse_number("--x0", ""); }), HasSubstr("empty"));
}

TEST(ParseUnsigned, RejectsNegativeInsteadOfWrapping) {
  EXPECT_EQ(parse_unsigned("--seed", "18446744073709551615"), UINT64_MAX);
  EXPECT_THAT(error_of([] { (void)parse_unsigned("--seed", "-1"); }),
              AllOf(HasSubstr("--seed"), HasSubstr("'-1'")));
  EXPECT_THAT(error_of([] { (void)parse_unsigned("--seed", "18446744073709551616"); }),
              HasSubstr("--seed"));
  EXPECT_THAT(error_of([] { (void)parse_unsigned("--realizations", "0", 1); }),
              HasSubstr("from 1"));
  EXPECT_THAT(error_of([] { (void)parse_unsigned("--threads", "2x"); }), HasSubstr("'2x'"));
}

TEST(IsSingleValue, DistinguishesFixedValuesFromGrids) {
  EXPECT_TRUE(is_single_value("5"));
  EXPECT_TRUE(is_single_value(" 0.5 "));
  EXPECT_FALSE(is_single_value("1,2"));
  EXPECT_FALSE(is_single_value("lin:1:2:1"));
  EXPECT_FALSE(is_single_value(""));
}

// ---- TOML ----

constexpr const char* paper_toml = R"(
[model]
m = 1
k = 4.0
ta = 50.0

[initial]
x0 = [-1.0, 1.0]
xdot0 = [-0.5, 2]
belt_start = "-1"

[grid]
mu = [0.5, 1.0, 7.0]
lambda = "log:0.1:30:40"

[sweep]
realizations = 2000
seed = 42
block_size = 25
keep_records = true
max_events = 1000000

[histograms]
bins = 40
stick_duration_max = 3.5
)";

TEST(ParseSweepToml, ReadsEveryTable) {
  const auto s = parse_sweep_toml(paper_toml, "paper.toml");
  EXPECT_EQ(s.base.mass, 1.0);
  EXPECT_EQ(s.base.stiffness, 4.0);
  EXPECT_EQ(s.base.gravity, 9.81);  // default kept
  EXPECT_EQ(s.initial.velocity_min, -0.5);
  EXPECT_EQ(s.initial.velocity_max, 2.0);
  EXPECT_EQ(s.initial.belt_start, -1);
  ASSERT_EQ(s.axes.size(), 2u);
  EXPECT_EQ(s.axes[0].name, "lambda");  // default order: lambda, mu, others
  EXPECT_EQ(s.axes[0].values, parse_grid("lambda", "log:0.1:30:40"));
  EXPECT_EQ(s.axes[1].name, "mu");
  EXPECT_THAT(s.axes[1].values, ElementsAre(0.5, 1.0, 7.0));
  EXPECT_EQ(s.realizations, 2000u);
  EXPECT_EQ(s.seed, 42u);
  EXPECT_EQ(s.block_size, 25u);
  EXPECT_TRUE(s.keep_records);
  EXPECT_EQ(s.max_events, 1000000);
  EXPECT_EQ(s.histograms.bins, 40u);
  EXPECT_EQ(s.histograms.stick_duration_max, 3.5);
  EXPECT_EQ(s.histograms.slip_duration_max, 0.0);
  EXPECT_NO_THROW(validate(s));
}

TEST(ParseSweepToml, EmptyTextGivesDefaults) {
  EXPECT_EQ(parse_sweep_toml("", "empty.toml"), sweep_spec{});
}

TEST(ParseSweepToml, ExplicitAxisOrderIsKept) {
  const auto s = parse_sweep_toml("[grid]\norder = [\"k\", \"lambda\"]\nlambda = [1, 2]\nk = [3]\n",
                                  "o.toml");
  ASSERT_EQ(s.axes.size(), 2u);
  EXPECT_EQ(s.axes[0].name, "k");
  EXPECT_EQ(s.axes[1].name, "lambda");
}

sweep_spec awkward_spec() {
  sweep_spec s;
  s.base.mass = 0.1 + 0.2;  // not exactly representable in few digits
  s.base.gravity = 9.80665;
  s.base.window = 1e-300;
  s.base.friction_coefficient = 1.0 / 3.0;
  s.initial = {-2.5, 1e-17, 0.0, 0.0, 1};
  s.axes = {{"k", {std::nextafter(4.0, 5.0), 1e300}},
            {"lambda", parse_grid("lambda", "log:0.1:30:7")},
            {"V", {2.0}}};
  s.realizations = 123457;
  s.seed = UINT64_MAX;  // above TOML's signed 64-bit integers
  s.block_size = 7;
  s.histograms = {17, 0.1, 2.0 / 3.0};
  s.max_events = 12345678901;
  s.keep_records = true;
  return s;
}

TEST(ToToml, RoundTripsExactly) {
  for (const auto& s : {sweep_spec{}, awkward_spec(), parse_sweep_toml(paper_toml, "p.toml")}) {
    const auto text = to_toml(s);
    EXPECT_EQ(parse_sweep_toml(text, "roundtrip.toml"), s) << text;
    EXPECT_EQ(to_toml(parse_sweep_toml(text, "roundtrip.toml")), text);
  }
}

TEST(ToToml, RoundTripsTheEngine) {
  sweep_spec s;
  s.engine = sweep_engine::reference;
  const auto text = to_toml(s);
  EXPECT_THAT(text, HasSubstr("engine = \"reference\""));
  EXPECT_EQ(parse_sweep_toml(text, "engine.toml"), s);
  EXPECT_THROW((void)parse_sweep_toml("[sweep]\nengine = \"turbo\"\n", "e.toml"), stickslip::error);
  EXPECT_THROW((void)parse_sweep_toml("[sweep]\nengine = 1\n", "e.toml"), stickslip::error);
}

// The precision keys (common_random_numbers, target_ci): written only when set (configurations without them read
// and print as before), and read back exactly.
TEST(ToToml, RoundTripsCommonRandomNumbersAndTheTargetCi) {
  sweep_spec s;
  EXPECT_THAT(to_toml(s), Not(HasSubstr("common_random_numbers")));
  EXPECT_THAT(to_toml(s), Not(HasSubstr("target_ci")));
  s.common_random_numbers = true;
  s.target_statistic = std::string(1, 'R');
  s.target_halfwidth = 0.0025;
  s.min_realizations = 300;
  s.realizations = 100000;
  const auto text = to_toml(s);
  EXPECT_THAT(text, HasSubstr("common_random_numbers = true"));
  EXPECT_THAT(text, HasSubstr("target_ci = \"R:0.0025\""));
  EXPECT_EQ(parse_sweep_toml(text, "crn.toml"), s);
  EXPECT_THROW((void)parse_sweep_toml("[sweep]\ntarget_ci = \"D:0.1\"\n", "t.toml"), stickslip::error);
  EXPECT_THROW((void)parse_sweep_toml("[sweep]\ntarget_ci = 0.1\n", "t.toml"), stickslip::error);
  EXPECT_THROW((void)parse_sweep_toml("[sweep]\ncommon_random_numbers = 1\n", "t.toml"),
               stickslip::error);
}

// Laws for uncertain parameters: a [model] key holds a law's text; to_toml writes the
// canonical text back, so the resolved config in results.nc reads back to the
// same spec (resume identifies finished outputs by it).
sweep_spec uncertain_spec() {
  sweep_spec s = awkward_spec();
  set_law(s, "mu_k", parse_law("uniform(0.5, 2)", "test"));
  set_law(s, "k", parse_law("lognormal(cv=0.25,mean=40)", "test"));
  set_law(s, "mu_s", parse_law("beta(mean=3,sd=0.1,min=2.5,max=4)", "test"));
  set_law(s, "v1", parse_law("truncnormal(mean=1,sd=0.3,min=0.2,max=3)", "test"));
  set_law(s, "c", parse_law("gamma(mean=0.1,cv=1.7)", "test"));
  return s;
}

TEST(ToToml, RoundTripsLawsExactly) {
  const sweep_spec s = uncertain_spec();
  const auto text = to_toml(s);
  EXPECT_THAT(text, HasSubstr("k = \"lognormal(mean=40,cv=0.25)\""));
  EXPECT_THAT(text, HasSubstr("mu_k = \"uniform(min=0.5,max=2)\""));
  EXPECT_THAT(text, HasSubstr("v1 = \"truncnormal(mean=1,sd=0.3,min=0.2,max=3)\""));
  EXPECT_EQ(parse_sweep_toml(text, "laws.toml"), s) << text;
  EXPECT_EQ(to_toml(parse_sweep_toml(text, "laws.toml")), text);
}

// A sensitivity study is a sweep_spec too, and its resolved config in
// sensitivity.nc identifies it on resume: its statistic, and its half-width
// without a target statistic (the study's stop rule), read back exactly; so
// do a half-width or a min_realizations that no stop rule uses.
TEST(ToToml, RoundTripsSensitivityStudies) {
  sweep_spec fixed_rows;
  set_law(fixed_rows, "mu", parse_law("uniform(2,7)", "test"));
  set_law(fixed_rows, "lambda", parse_law("loguniform(0.5,10)", "test"));
  fixed_rows.base.stiffness = 40;
  fixed_rows.sensitivity_statistic = "R";
  fixed_rows.realizations = 4096;
  fixed_rows.block_size = 64;
  sweep_spec to_target = fixed_rows;
  to_target.target_halfwidth = 0.02 / 3;
  to_target.min_realizations = 777;
  to_target.realizations = 1'000'000;
  sweep_spec only_min;
  only_min.min_realizations = 5;
  sweep_spec only_halfwidth;
  only_halfwidth.target_halfwidth = 1e-300;
  for (const auto& s : {fixed_rows, to_target, only_min, only_halfwidth, uncertain_spec()}) {
    const auto text = to_toml(s);
    EXPECT_EQ(parse_sweep_toml(text, "sensitivity.toml"), s) << text;
    EXPECT_EQ(to_toml(parse_sweep_toml(text, "sensitivity.toml")), text);
  }
  EXPECT_THAT(to_toml(fixed_rows), AllOf(HasSubstr("sensitivity_statistic = \"R\""),
                                         Not(HasSubstr("target_halfwidth")),
                                         Not(HasSubstr("min_realizations"))));
  EXPECT_THAT(to_toml(to_target), AllOf(HasSubstr("target_halfwidth = 0.006666666666666667"),
                                        HasSubstr("min_realizations = 777")));
  // Without these keys a configuration reads and prints as before.
  EXPECT_THAT(to_toml(sweep_spec{}), AllOf(Not(HasSubstr("sensitivity_statistic")),
                                           Not(HasSubstr("target_halfwidth")),
                                           Not(HasSubstr("min_realizations"))));
  EXPECT_THAT(error_of([] { (void)parse_sweep_toml("[sweep]\ntarget_halfwidth = 0\n", "h.toml"); }),
              AllOf(HasSubstr("sweep.target_halfwidth at h.toml:2:"), HasSubstr("> 0")));
  EXPECT_THAT(error_of([] {
                (void)parse_sweep_toml("[sweep]\ntarget_ci = \"R:0.1\"\ntarget_halfwidth = 0.2\n",
                                       "h.toml");
              }),
              AllOf(HasSubstr("sweep.target_halfwidth"), HasSubstr("target_ci")));
  EXPECT_THAT(error_of([] { (void)parse_sweep_toml("[sweep]\nsensitivity_statistic = 1\n", "h.toml"); }),
              AllOf(HasSubstr("sweep.sensitivity_statistic"), HasSubstr("naming a statistic")));
}

// Specs that validate() refuses still print back as they were read (what
// fuzz_family_toml found): a generator whose size does not match the levels,
// a negative mu_s or mu_k.
TEST(ToToml, RoundTripsSpecsThatValidateRefuses) {
  for (const char* text : {"[model]\nbelt_levels = [1, 0, -1]\nbelt_generator = [[-1, 1], [2, -2]]\n",
                           "[model]\nbelt_generator = [[-1, 0.5, 0.5], [1, -1, 0], [0, 2, -2]]\n",
                           "[model]\nmu_s = -1\nmu_k = -0.5\n"}) {
    const sweep_spec s = parse_sweep_toml(text, "odd.toml");
    const auto printed = to_toml(s);
    EXPECT_EQ(parse_sweep_toml(printed, "roundtrip.toml"), s) << printed;
  }
}

TEST(SetLaw, KeepsOneCanonicalOrderAndReplacesAxesValuesAndLaws) {
  sweep_spec s;
  s.axes = {{"lambda", {1.0, 3.8}}, {"mu", {2.0, 5.0}}};
  s.base.stiffness = 40;
  set_law(s, "k", parse_law("gamma(mean=40,cv=0.1)", "--k"));
  set_law(s, "mu", parse_law("uniform(2,7)", "--mu"));
  set_law(s, "k", parse_law("gamma(mean=30,cv=0.1)", "--k"));
  ASSERT_EQ(s.uncertain.size(), 2u);
  EXPECT_EQ(s.uncertain[0].symbol, "k");  // m k g mu ...: k before mu whatever the call order
  EXPECT_EQ(s.uncertain[1].symbol, "mu");
  EXPECT_EQ(to_string(s.uncertain[0].law), "gamma(mean=30,cv=0.1)");
  ASSERT_EQ(s.axes.size(), 1u);  // the law replaced the mu axis
  EXPECT_EQ(s.axes[0].name, "lambda");
  EXPECT_EQ(s.base.stiffness, model_parameters{}.stiffness);  // the base value is the default
  drop_law(s, "mu");
  EXPECT_EQ(find_law(s, "mu"), nullptr);
  EXPECT_NE(find_law(s, "k"), nullptr);
}

TEST(ParseSweepToml, ModelKeysTakeLaws) {
  const auto s = parse_sweep_toml(
      "[model]\nk = 40\nmu = \"gamma(mean=5, cv=0.2)\"\n[grid]\nlambda = [1, 3.8]\n", "l.toml");
  ASSERT_EQ(s.uncertain.size(), 1u);
  EXPECT_EQ(s.uncertain[0].symbol, "mu");
  EXPECT_EQ(to_string(s.uncertain[0].law), "gamma(mean=5,cv=0.2)");
  EXPECT_EQ(s.base.stiffness, 40.0);
  EXPECT_EQ(s.axes.size(), 1u);
  // Errors name the key, its position, the law and the problem.
  EXPECT_THAT(error_of([] { (void)parse_sweep_toml("[model]\nmu = \"gama(mean=5,cv=1)\"\n", "b.toml"); }),
              AllOf(HasSubstr("model.mu at b.toml:2:6"), HasSubstr("unknown law 'gama'")));
  EXPECT_THAT(error_of([] { (void)parse_sweep_toml("[model]\nk = \"gamma(mean=5)\"\n", "b.toml"); }),
              AllOf(HasSubstr("model.k"), HasSubstr("cv is missing")));
  EXPECT_THAT(error_of([] { (void)parse_sweep_toml("[model]\nk = \"fast\"\n", "b.toml"); }),
              AllOf(HasSubstr("model.k"), HasSubstr("a number, or a law")));
  EXPECT_THAT(error_of([] { (void)parse_sweep_toml("[model]\nv1 = 2\n", "b.toml"); }),
              AllOf(HasSubstr("model.v1"), HasSubstr("a law string")));
  // A law and an axis for one parameter: refused, whichever table comes first.
  for (const char* text : {"[grid]\nmu = [1, 2]\n[model]\nmu = \"uniform(1,2)\"\n",
                           "[model]\nmu = \"uniform(1,2)\"\n[grid]\nmu = [1, 2]\n"})
    EXPECT_THAT(error_of([&] { (void)parse_sweep_toml(text, "b.toml"); }),
                AllOf(HasSubstr("mu"), HasSubstr("a law or a [grid] axis, not both")));
}

TEST(ToToml, IsReadableAndComplete) {
  const auto text = to_toml(parse_sweep_toml(paper_toml, "p.toml"));
  for (const char* key : {"[model]", "[initial]", "[grid]", "[sweep]", "[histograms]",
                          "order = [\"lambda\", \"mu\"]", "belt_start = \"-1\"", "seed = 42",
                          "m = 1.0", "g = 9.81"})
    EXPECT_THAT(text, HasSubstr(key));
  // The swept parameters' [model] values are said to be replaced by the
  // grid's (a new user read them as the sweep's values); the fixed are not.
  EXPECT_THAT(text, HasSubstr("\nmu = 5.0  # swept: [grid] gives its values\n"));
  EXPECT_THAT(text, HasSubstr("\nlambda = 1.0  # swept: [grid] gives its values\n"));
  EXPECT_THAT(text, HasSubstr("\nm = 1.0\n"));
  EXPECT_THAT(text, HasSubstr("\ng = 9.81\n"));
}

struct bad_toml {
  const char* text;
  std::vector<const char*> expected;  // phrases the message must contain
};

class ParseSweepTomlError : public ::testing::TestWithParam<bad_toml> {};

TEST_P(ParseSweepTomlError, NamesKeyAndPosition) {
  const auto& c = GetParam();
  const auto msg = error_of([&] { (void)parse_sweep_toml(c.text, "bad.toml"); });
  for (const char* phrase : c.expected) EXPECT_THAT(msg, HasSubstr(phrase));
}

INSTANTIATE_TEST_SUITE_P(
    AllClasses, ParseSweepTomlError,
    ::testing::Values(
        // syntax errors report file:line:col
        bad_toml{"[model]\nm = \n", {"bad.toml:2:", "syntax error"}},
        bad_toml{"[model\n", {"bad.toml:1:", "syntax error"}},
        bad_toml{"[model]\nm = 1\nm = 2\n", {"bad.toml:3:", "syntax error"}},
        // unknown tables and keys
        bad_toml{"[modle]\nm = 1\n", {"'modle'", "bad.toml:1:", "[model]"}},
        bad_toml{"[model]\nmass = 1\n", {"'model.mass'", "bad.toml:2:1", "m, k, g, mu"}},
        bad_toml{"[grid]\nalpha = [1]\n", {"'grid.alpha'", "bad.toml:2:1"}},
        bad_toml{"[sweep]\nthreads = 4\n", {"'sweep.threads'"}},
        bad_toml{"[initial]\nv0 = [0, 1]\n", {"'initial.v0'"}},
        bad_toml{"[histograms]\nbinz = 4\n", {"'histograms.binz'"}},
        bad_toml{"seed = 4\n", {"'seed'", "tables are"}},
        // wrong types
        bad_toml{"[model]\nmu = \"five\"\n", {"model.mu", "bad.toml:2:6", "a number", "a string"}},
        bad_toml{"model = 3\n", {"model", "a table"}},
        bad_toml{"[sweep]\nrealizations = 2.5\n", {"sweep.realizations", "a float"}},
        // the true range, with file:line, in every limit message
        bad_toml{"[sweep]\nrealizations = 100.5\n",
                 {"sweep.realizations at bad.toml:2:", "1 to 2^40 = 1099511627776"}},
        bad_toml{"[sweep]\nrealizations = 0\n",
                 {"sweep.realizations at bad.toml:2:", "1 to 2^40 = 1099511627776"}},
        bad_toml{"[sweep]\nrealizations = 1099511627777\n",
                 {"sweep.realizations at bad.toml:2:", "1 to 2^40"}},
        bad_toml{"[sweep]\nblock_size = 0\n", {"sweep.block_size at bad.toml:2:", "2^24"}},
        bad_toml{"[sweep]\nmax_events = -3\n", {"sweep.max_events at bad.toml:2:", "2^53"}},
        bad_toml{"[histograms]\nbins = 0\n", {"histograms.bins at bad.toml:2:", "1 to 100000"}},
        bad_toml{"[histograms]\nbins = 100001\n", {"histograms.bins", "1 to 100000"}},
        bad_toml{"[initial]\nx0 = [1.0, -1.0]\n",
                 {"initial.x0 at bad.toml:2:", "lo = 1 > hi = -1"}},
        bad_toml{"[initial]\nxdot0 = [0.25, 0.125]\n",
                 {"initial.xdot0 at bad.toml:2:", "lo = 0.25 > hi = 0.125"}},
        bad_toml{"[sweep]\nrealizations = -5\n", {"sweep.realizations", "-5"}},
        bad_toml{"[sweep]\nseed = \"12a\"\n", {"sweep.seed", "an integer"}},
        bad_toml{"[sweep]\nkeep_records = 1\n", {"sweep.keep_records", "a boolean"}},
        bad_toml{"[initial]\nx0 = [1]\n", {"initial.x0", "two numbers"}},
        bad_toml{"[initial]\nx0 = 1.0\n", {"initial.x0", "two numbers"}},
        bad_toml{"[initial]\nbelt_start = \"sideways\"\n", {"initial.belt_start", "\"stationary\""}},
        bad_toml{"[grid]\nlambda = 0.5\n", {"grid.lambda", "grid spec string", "a float"}},
        bad_toml{"[grid]\nmu = [1, \"x\"]\n", {"grid.mu[1]", "a number"}},
        bad_toml{"[model]\nm = nan\n", {"model.m", "finite"}},
        // bad grids inside the file
        bad_toml{"[grid]\nlambda = []\n", {"grid.lambda", "empty"}},
        bad_toml{"[grid]\nlambda = [0.5, -1]\n", {"grid.lambda[1]", "> 0"}},
        bad_toml{"[grid]\nlambda = \"log:0.1:30:0\"\n", {"grid.lambda", "bad.toml:2:", "n >= 1"}},
        bad_toml{"[grid]\nlambda = \"1,nan\"\n", {"grid.lambda", "not finite"}},
        bad_toml{"[grid]\norder = [\"mu\"]\nlambda = [1]\n", {"grid.order", "not a key"}},
        bad_toml{"[grid]\norder = [\"lambda\", \"lambda\"]\nlambda = [1]\n", {"repeated"}},
        bad_toml{"[grid]\norder = []\nlambda = [1]\n", {"grid.order", "every swept"}}));

// A missing input file is bad input (exit 2), not an I/O failure.
TEST(ReadSweepTomlFile, MissingFileIsInvalidInputThatDoesNotExist) {
  const auto msg = error_of([] { (void)read_sweep_toml_file("/nonexistent/x.toml"); },
                            exit_code::invalid_input);
  EXPECT_THAT(msg, AllOf(HasSubstr("/nonexistent/x.toml"), HasSubstr("does not exist")));
}

// ---- switch times ----

TEST(ParseSwitchTimes, SkipsCommentsAndBlankLines) {
  const auto t = parse_switch_times("# measured belt signal\n0.5\n\n  1.25  # second\n7\r\n",
                                    "belt.txt");
  EXPECT_THAT(t, ElementsAre(0.5, 1.25, 7.0));
  EXPECT_TRUE(parse_switch_times("# nothing\n\n", "empty.txt").empty());
  EXPECT_THAT(parse_switch_times("0\n3", "zero.txt"), ElementsAre(0.0, 3.0));
}

// Replay files of a Markov belt: "t level" lines, level numbers 1..n.
TEST(ParseSwitchSchedule, LinesWithLevelsGiveZeroBasedLevels) {
  const auto s = parse_switch_schedule("0.5 3\n# comment\n1.25 1\n2 2\n", "m.txt", 3);
  EXPECT_EQ(s.times, (std::vector<double>{0.5, 1.25, 2}));
  EXPECT_EQ(s.levels, (std::vector<std::size_t>{2, 0, 1}));
  const auto two = parse_switch_schedule("0.5\n1\n", "t.txt", 2);
  EXPECT_TRUE(two.levels.empty());
}

TEST(ParseSwitchSchedule, RefusesMixedLinesMissingLevelsAndUnknownLevels) {
  EXPECT_THAT(error_of([] { (void)parse_switch_schedule("0.5 2\n1\n", "m.txt", 3); }),
              AllOf(HasSubstr("m.txt"), HasSubstr("1 of 2 lines with a level")));
  EXPECT_THAT(error_of([] { (void)parse_switch_schedule("0.5\n1\n", "m.txt", 3); }),
              AllOf(HasSubstr("m.txt"), HasSubstr("3 levels")));
  EXPECT_THAT(error_of([] { (void)parse_switch_schedule("0.5 4\n", "m.txt", 3); }),
              AllOf(HasSubstr("belt level at m.txt:1"), HasSubstr("'4'"), HasSubstr("1 to 3")));
  EXPECT_THAT(error_of([] { (void)parse_switch_schedule("0.5 0\n", "m.txt", 3); }),
              HasSubstr("1 to 3"));
}

TEST(ParseSwitchTimes, ErrorsNameTheLine) {
  EXPECT_THAT(error_of([] { (void)parse_switch_times("1\n# c\n0.5\n", "b.txt"); }),
              AllOf(HasSubstr("b.txt:3"), HasSubstr("0.5"), HasSubstr("sorted")));
  EXPECT_THAT(error_of([] { (void)parse_switch_times("1\n1\n", "b.txt"); }),
              HasSubstr("b.txt:2"));
  EXPECT_THAT(error_of([] { (void)parse_switch_times("\n-1\n", "b.txt"); }),
              AllOf(HasSubstr("b.txt:2"), HasSubstr("-1"), HasSubstr(">= 0")));
  // "t level" lines: a level the belt does not have (two levels here).
  EXPECT_THAT(error_of([] { (void)parse_switch_times("1\n2 3\n", "b.txt"); }),
              AllOf(HasSubstr("belt level at b.txt:2"), HasSubstr("'3'"), HasSubstr("1 to 2")));
  EXPECT_THAT(error_of([] { (void)parse_switch_times("1\n2 2 x\n", "b.txt"); }),
              HasSubstr("b.txt:2"));
  EXPECT_THAT(error_of([] { (void)parse_switch_times("nan\n", "b.txt"); }),
              AllOf(HasSubstr("b.txt:1"), HasSubstr("not finite")));
  EXPECT_THAT(error_of([] { (void)parse_switch_times("1,2\n", "b.txt"); }),
              HasSubstr("b.txt:1"));
}

TEST(ParseSwitchTimeList, CommaSeparated) {
  EXPECT_THAT(parse_switch_time_list("--switch-times", "0.5, 2,7.25"), ElementsAre(0.5, 2.0, 7.25));
  EXPECT_TRUE(parse_switch_time_list("--switch-times", "").empty());
  EXPECT_THAT(error_of([] { (void)parse_switch_time_list("--switch-times", "3,1"); }),
              AllOf(HasSubstr("--switch-times entry #2"), HasSubstr("sorted")));
  EXPECT_THAT(error_of([] { (void)parse_switch_time_list("--switch-times", "-2"); }),
              AllOf(HasSubstr("entry #1"), HasSubstr("-2")));
  EXPECT_THAT(error_of([] { (void)parse_switch_time_list("--switch-times", "1,,2"); }),
              HasSubstr("entry #2"));
}

TEST(ReadSwitchTimesFile, ReadsAFileAndNamesIt) {
  const std::string path = ::testing::TempDir() + "switch_times_test.txt";
  {
    std::ofstream f(path);
    f << "# t\n0.25\n4\n";
  }
  EXPECT_THAT(read_switch_times_file(path), ElementsAre(0.25, 4.0));
  {
    std::ofstream f(path);
    f << "4\n0.25\n";
  }
  EXPECT_THAT(error_of([&] { (void)read_switch_times_file(path); }), HasSubstr(path + ":2"));
  std::remove(path.c_str());
  EXPECT_THAT(error_of([&] { (void)read_switch_times_file(path); }, exit_code::invalid_input),
              AllOf(HasSubstr(path), HasSubstr("does not exist")));
}

}  // namespace
}  // namespace stickslip::io
