// The parameter table (parameters.hpp, scalar_parameters): access by symbol
// and alias, domains, the stream key's order, the one assignment order
// (mu before mu_s and mu_k) that TOML shares with the CLI and Python, and
// the refusal of a value outside a row's domain.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/parameters.hpp"
#include "stickslip/random_stream.hpp"

namespace stickslip {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

std::string refusal_of(const model_parameters& p) {
  try {
    validate(p);
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::invalid_input) << e.what();
    return e.what();
  }
  return "";
}

TEST(ParameterTable, EveryRowIsReadAndWrittenBySymbolAndAlias) {
  for (const auto& row : scalar_parameters) {
    model_parameters p;
    set_parameter(p, row.symbol, 0.75);
    EXPECT_EQ(p.*row.field, 0.75) << row.symbol;
    EXPECT_EQ(parameter_value(p, row.symbol), 0.75) << row.symbol;
    set_parameter(p, row.long_name, 0.5);
    EXPECT_EQ(parameter_value(p, row.long_name), 0.5) << row.long_name;
    EXPECT_EQ(canonical_symbol(row.long_name), row.symbol);
    EXPECT_TRUE(is_parameter_symbol(row.symbol));
    EXPECT_EQ(&info_for(row.long_name), &row);
    EXPECT_EQ(domain_of(row.symbol), row.domain);
  }
  EXPECT_EQ(flag_of("mu_s"), "--mu-s");
  EXPECT_EQ(flag_of("v2"), "v2");
  EXPECT_EQ(domain_of("v3"), parameter_domain::any);
  EXPECT_EQ(domain_of("r1"), parameter_domain::positive);
}

TEST(ParameterTable, NamesAndStreamKeyPositionsComeFromTheRows) {
  EXPECT_THAT(std::vector<std::string>(recorded_parameter_names.begin(),
                                       recorded_parameter_names.end()),
              ::testing::ElementsAre("m", "k", "g", "mu", "V", "lambda", "ta", "c", "mu_s", "mu_k"));
  std::vector<unsigned> positions;
  for (const auto& row : scalar_parameters) positions.push_back(row.key_position);
  for (std::size_t i = 0; i < paper_parameter_count; ++i) EXPECT_EQ(positions[i], i);
  std::sort(positions.begin(), positions.end());
  for (std::size_t i = 0; i < positions.size(); ++i) EXPECT_EQ(positions[i], i);
}

TEST(ParameterTable, UnsetFrictionResolvesToMuAndMuClearsIt) {
  model_parameters p;
  set_parameter(p, "mu_s", 7.0);
  set_parameter(p, "mu", 3.0);
  EXPECT_EQ(p.static_friction, 0.0);
  EXPECT_EQ(parameter_value(p, "mu_s"), 3.0);
  EXPECT_EQ(parameter_value(p, "mu_k"), 3.0);
}

TEST(ParameterTable, AssignAppliesMuBeforeMuSAndMuKWhateverTheWrittenOrder) {
  const model_parameters p = assign({}, {{"mu_s", 6.0}, {"mu_k", 4.0}, {"mu", 5.0}, {"c", 0.3}});
  EXPECT_EQ(p.mu_s(), 6.0);
  EXPECT_EQ(p.mu_k(), 4.0);
  EXPECT_EQ(p.friction_coefficient, 5.0);
  EXPECT_EQ(p.damping, 0.3);
  // A later value of the same parameter wins.
  EXPECT_EQ(assign({}, {{"k", 2.0}, {"stiffness", 3.0}}).stiffness, 3.0);
}

TEST(ParameterTable, TomlGivesTheModelOfTheSameAssignments) {
  const auto s = io::parse_sweep_toml("[model]\nmu_s = 6\nmu_k = 4.0\nmu = 5\nc = 0.3\nk = 9\n",
                                      "order.toml");
  const model_parameters expected =
      assign({}, {{"mu_s", 6.0}, {"mu_k", 4.0}, {"mu", 5.0}, {"c", 0.3}, {"k", 9.0}});
  EXPECT_EQ(s.base, expected);
  EXPECT_EQ(point_key(s.base), point_key(expected));
  // The resolved configuration prints the rows as given and reads back.
  EXPECT_EQ(io::parse_sweep_toml(io::to_toml(s), "again.toml").base, expected);
}

// mu's refinements and the rules of an axis or law without effect come from
// the table (the rows whose unset value resolves to mu), written once for
// grid axes and uncertain laws alike.
TEST(ParameterTable, MusRefinementsAndTheOverridesOfTheBaseComeFromTheRows) {
  EXPECT_THAT(refinements_of("mu"), ::testing::ElementsAre("mu_s", "mu_k"));
  EXPECT_THAT(refinements_of("friction-coefficient"), ::testing::ElementsAre("mu_s", "mu_k"));
  for (const char* other : {"mu_s", "mu_k", "lambda", "k", "v1"})
    EXPECT_TRUE(refinements_of(other).empty()) << other;
  model_parameters base;
  for (const auto& row : scalar_parameters) EXPECT_EQ(overridden_by_base(base, row.symbol), "");
  set_parameter(base, "mu_k", 4.0);
  EXPECT_EQ(overridden_by_base(base, "mu"),
            "mu sets mu_s and mu_k both, and one of them is given");
  EXPECT_EQ(overridden_by_base(base, "mu_s"), "");
  base.belt_levels = {1.0, -0.5};
  EXPECT_EQ(overridden_by_base(base, "V"), "the belt levels are given");
  base.belt_rates = {1.0, 2.0};
  EXPECT_EQ(overridden_by_base(base, "lambda"), "the belt rates are given");
  EXPECT_EQ(overridden_by_base(base, "switch-rate"), "the belt rates are given");
}

// mu beside mu_s and mu_k sets neither, yet enters the stream key: a note
// (a new user's report: `--mu 5 --mu-s 6 --mu-k 5` was taken without a
// word), whatever the order and the names; none beside one of them or
// alone. (A given 0, which would leave a refinement unset, is refused:
// AnExplicitZeroFrictionIsRefusedNotTakenForMu.)
TEST(ParameterTable, MuBesideBothItsRefinementsIsNotedNotIgnored) {
  const std::string note = only_in_the_stream_key({{"mu_s", "6"}, {"mu_k", "4"}, {"mu", "5"}});
  EXPECT_EQ(note,
            "--mu 5 sets neither mu_s nor mu_k: --mu-s and --mu-k give them. Unless the model "
            "is the paper's (mu_s = mu_k, c = 0, the belt +-V), --mu still enters the random "
            "streams' key and changes the draws, not the model: keep it to replay a run made "
            "with it, drop it otherwise");
  EXPECT_THAT(only_in_the_stream_key({{"friction-coefficient", "2"},
                                      {"static-friction", "lin:6:8:3"},
                                      {"kinetic-friction", "uniform(2,5)"}}),
              HasSubstr("--mu 2 sets neither"));
  // a refinement a --config file set is named as such; an empty text (an
  // empty Python list) is not a file
  EXPECT_THAT(only_in_the_stream_key({{"mu", "5"}, {"mu_s", "", true}, {"mu_k", "", true}}),
              HasSubstr("--mu 5 sets neither mu_s nor mu_k: the --config file gives them."));
  EXPECT_THAT(only_in_the_stream_key({{"mu", "5"}, {"mu_k", "4"}, {"mu_s", "", true}}),
              HasSubstr("nor mu_k: --mu-k and the --config file give them."));
  EXPECT_THAT(only_in_the_stream_key({{"mu", "5"}, {"mu_k", "4"}, {"mu_s", ""}}),
              HasSubstr("nor mu_k: --mu-s and --mu-k give them."));
  // a grid or a law over mu beside a refinement is refused elsewhere
  // (overridden_by_base): no note before that refusal
  EXPECT_EQ(only_in_the_stream_key({{"mu", "0.5,2"}, {"mu_s", "6"}, {"mu_k", "4"}}), "");
  EXPECT_EQ(only_in_the_stream_key({{"mu", "uniform(2,5)"}, {"mu_s", "6"}, {"mu_k", "4"}}), "");
  EXPECT_EQ(only_in_the_stream_key({{"mu", "5"}, {"mu_s", "6"}}), "");
  EXPECT_EQ(only_in_the_stream_key({{"mu", "5"}, {"mu_k", "4"}, {"k", "40"}}), "");
  EXPECT_EQ(only_in_the_stream_key({{"mu_s", "6"}, {"mu_k", "4"}}), "");
  EXPECT_EQ(only_in_the_stream_key({}), "");
  // the claim behind the note: mu beside both changes the key, not the model
  model_parameters with_mu, without;
  with_mu = assign(with_mu, {{"mu", 3.0}, {"mu_s", 6.0}, {"mu_k", 4.0}});
  without = assign(without, {{"mu_s", 6.0}, {"mu_k", 4.0}});
  EXPECT_EQ(parameter_value(with_mu, "mu_s"), parameter_value(without, "mu_s"));
  EXPECT_EQ(parameter_value(with_mu, "mu_k"), parameter_value(without, "mu_k"));
  EXPECT_NE(point_key(with_mu), point_key(without));
  // ... unless the model is the paper's (mu_s = mu_k, c = 0, +-V): its key is
  // its seven values with mu_k for mu, and mu changes nothing at all
  model_parameters paper_with_mu, paper_without;
  paper_with_mu = assign(paper_with_mu, {{"mu", 3.0}, {"mu_s", 6.0}, {"mu_k", 6.0}});
  paper_without = assign(paper_without, {{"mu_s", 6.0}, {"mu_k", 6.0}});
  EXPECT_EQ(point_key(paper_with_mu), point_key(paper_without));
}

// mu_s or mu_k written as 0 (a flag, a TOML key, a keyword: assign,
// assign_value) was taken for "unset", i.e. mu, without a word; it is
// refused by name. A C++ field left 0 still means unset.
TEST(ParameterTable, AnExplicitZeroFrictionIsRefusedNotTakenForMu) {
  const auto refusal = [](auto&& f) -> std::string {
    try {
      f();
    } catch (const error& e) {
      EXPECT_EQ(e.code(), exit_code::invalid_input) << e.what();
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(refusal([] { (void)assign({}, {{"mu", 3.0}, {"mu_k", 0.0}}); }),
            "invalid mu_k (kinetic friction): 0 (allowed: a finite number > 0; leave mu_k out "
            "for mu_k = mu)");
  EXPECT_THAT(refusal([] { (void)assign({}, {{"static-friction", 0.0}}); }),
              HasSubstr("invalid mu_s (static friction): 0"));
  EXPECT_THAT(refusal([] { (void)io::parse_sweep_toml("[model]\nmu_k = 0.0\n", "t.toml"); }),
              HasSubstr("invalid mu_k (kinetic friction): 0"));
  EXPECT_EQ(refusal([] { (void)assign({}, {{"c", 0.0}, {"mu", 0.0}, {"mu_k", 0.5}}); }), "");
  model_parameters unset;  // C++: 0 is unset, resolving to mu
  EXPECT_EQ(parameter_value(unset, "mu_k"), unset.friction_coefficient);
}

// A TOML [grid] without `order` sweeps in default_axis_order (lambda, mu
// first); the command line puts lambda and mu first and keeps the rest as
// given; both from the one list.
TEST(ParameterTable, GridAxesFollowTheOneDefaultOrder) {
  const auto s = io::parse_sweep_toml(
      "[grid]\nk = [4, 40]\nc = [0, 0.1]\nmu = [1, 2]\nlambda = [1, 2]\nv1 = [1, 2]\n",
      "grid.toml");
  std::vector<std::string> names;
  for (const auto& ax : s.axes) names.push_back(ax.name);
  EXPECT_THAT(names, ::testing::ElementsAre("lambda", "mu", "c", "k", "v1"));
  EXPECT_EQ(axis_rank("lambda"), 0u);
  EXPECT_EQ(axis_rank("mu"), 1u);
  EXPECT_EQ(axis_rank("v3"), std::size(scalar_parameters));
  std::vector<axis> cli{{"k", {4.0}}, {"mu", {1.0}}, {"c", {0.0}}, {"lambda", {1.0}}};
  io::order_added_axes(cli);
  names.clear();
  for (const auto& ax : cli) names.push_back(ax.name);
  EXPECT_THAT(names, ::testing::ElementsAre("lambda", "mu", "k", "c"));
}

TEST(ParameterTable, TheStreamKeyOfThePaperModelIsItsSevenValues) {
  model_parameters a, b;
  set_parameter(b, "mu_s", a.friction_coefficient);
  set_parameter(b, "mu_k", a.friction_coefficient);
  EXPECT_EQ(point_key(a), point_key(b));
  set_parameter(b, "mu_k", 4.0);
  EXPECT_NE(point_key(a), point_key(b));
}

TEST(ParameterTable, AValueOutsideItsRowsDomainIsRefusedByNameValueAndRange) {
  for (const auto& row : scalar_parameters) {
    model_parameters p;
    p.*row.field = row.domain == parameter_domain::any ? INFINITY : -1.0;
    const std::string words = [&] {
      std::string w = row.long_name;
      std::replace(w.begin(), w.end(), '-', ' ');
      return w;
    }();
    EXPECT_THAT(refusal_of(p), AllOf(HasSubstr(std::string(row.symbol) + " (" + words + ")"),
                                     HasSubstr("allowed")))
        << row.symbol;
  }
  model_parameters p = assign({}, {{"mu_s", 3.0}, {"mu_k", 4.0}});
  EXPECT_THAT(refusal_of(p), AllOf(HasSubstr("mu_k (kinetic friction)"), HasSubstr("<= mu_s = 3")));
}

// TOML's [model] keys are the symbols: a long alias is an unknown key (the
// CLI takes it as a flag, TOML never did), also for mu, which is read
// before the others.
TEST(ParameterTable, TomlRefusesALongAliasAsAModelKey) {
  for (const char* text : {"[model]\nfriction-coefficient = 3\n", "[model]\nstiffness = 9\n"}) {
    try {
      (void)io::parse_sweep_toml(text, "alias.toml");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const error& e) {
      EXPECT_NE(std::string(e.what()).find("model."), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(io::parse_sweep_toml("[model]\nmu = 3\n", "symbol.toml").base.friction_coefficient, 3.0);
}

}  // namespace
}  // namespace stickslip
