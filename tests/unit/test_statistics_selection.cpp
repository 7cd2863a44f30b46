// sweep --statistics LIST (statistics_groups.hpp): names and groups parse to
// one canonical selection, it round-trips through the serializer, it
// decides what the engines compute, and the paper model's statistics are the
// same bits under every selection that holds them.
#include <gtest/gtest.h>

#include "stickslip/error.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/statistics_groups.hpp"
#include "stickslip/statistics_schema.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip {
namespace {

statistics_selection parse(std::string_view list) {
  return parse_statistics_selection("--statistics", list);
}

TEST(StatisticsSelection, NamesAndGroupsAreCanonical) {
  EXPECT_EQ(parse("default"), statistics_selection{});
  EXPECT_EQ(parse("paper"), statistics_selection{});
  EXPECT_EQ(to_string(statistics_selection{}), "paper");
  EXPECT_EQ(to_string(parse("all")), "paper,family,derivatives,survival");
  // A row by its summary name, name or symbol; rows in table order, once,
  // and none that a selected group holds.
  EXPECT_EQ(to_string(parse("R")), "stick_fraction");
  EXPECT_EQ(to_string(parse("D, R, stick_fraction")), "stick_fraction,stick_duration");
  EXPECT_EQ(to_string(parse("paper,R,W_f")), "paper,friction_power");
  EXPECT_EQ(to_string(parse("family,P,X")), "family");
  EXPECT_EQ(to_string(parse("belt_level_fraction,survival")), "survival,belt_level_fraction");
  EXPECT_EQ(parse("survival , paper"), parse("paper,survival"));
  for (const char* bad : {"", "survial", "R,", "paper,,family", "papers"})
    EXPECT_THROW((void)parse(bad), error) << bad;
  try {
    (void)parse("survial");
  } catch (const error& e) {
    EXPECT_NE(std::string(e.what()).find("'survial' (allowed: a comma list of paper, family, "
                                         "derivatives, survival, default, all, or statistics by "
                                         "name (R, "),
              std::string::npos)
        << e.what();
  }
  // One string of a list is a comma list itself (TOML "paper,survival",
  // Python statistics="paper,survival").
  EXPECT_EQ(parse_statistics_selection("statistics", std::vector<std::string>{"paper, survival"}),
            parse("paper,survival"));
  // Python's statistics=None and TOML's []: the default.
  EXPECT_EQ(parse_statistics_selection("statistics", std::vector<std::string>{}),
            statistics_selection{});
}

TEST(StatisticsSelection, RoundTripsAndNonCanonicalRowsAreRefused) {
  sweep_spec s;
  s.axes = {{"lambda", {1.0}}};
  for (const char* list : {"paper", "R", "W_c,D", "family,derivatives", "survival,D_1"}) {
    s.statistics = parse(list);
    EXPECT_EQ(deserialize_sweep_spec(serialize(s)).statistics, s.statistics) << list;
  }
  // Rows out of order, repeated, held by a selected group, or unknown.
  for (auto rows : std::vector<std::vector<std::string>>{{"stick_duration", "stick_fraction"},
                                                         {"stick_fraction", "stick_fraction"},
                                                         {"R"},
                                                         {"nosuch"}}) {
    statistics_selection bad;
    bad.paper = false;
    bad.rows = rows;
    EXPECT_FALSE(canonical_rows(bad)) << rows.front();
  }
  statistics_selection held;  // paper holds R
  held.rows = {"stick_fraction"};
  EXPECT_FALSE(canonical_rows(held));
}

TEST(StatisticsSelection, DecidesWhatTheEnginesCompute) {
  struct row {
    const char* list;
    bool family, means_only;
  };
  for (const auto& r : {row{"paper", false, false}, row{"R", false, true},
                        row{"R,S_T/t_a,D_1", false, true}, row{"R,D", false, false},
                        row{"survival", false, false}, row{"W_f", true, false},
                        row{"X", true, false}, row{"family", true, false},
                        row{"derivatives", true, false}, row{"all", true, false}}) {
    sweep_spec s;
    s.statistics = parse(r.list);
    apply_statistics_selection(s);
    EXPECT_EQ(s.family_statistics, r.family) << r.list;
    EXPECT_EQ(s.means_only, r.means_only) << r.list;
  }
  // What the writers write.
  const auto sel = parse("R,W_f");
  EXPECT_TRUE(selects(sel, quantity_table[quantity_row("stick_fraction")]));
  EXPECT_TRUE(selects(sel, quantity_table[quantity_row("friction_power")]));
  EXPECT_FALSE(selects(sel, quantity_table[quantity_row("stick_duration")]));
  EXPECT_FALSE(selects(sel, level_table[0]));
  EXPECT_FALSE(selects_derivatives(sel));
  EXPECT_FALSE(selects_joint_histograms(sel));
  EXPECT_TRUE(selects_joint_histograms(parse("family")));
}

// A resume or merge with another selection names the selection, not the
// engine settings that follow from it; the derivatives need a mean.
TEST(StatisticsSelection, IsNamedFirstAndDerivativesNeedAMean) {
  sweep_spec a, b;
  a.axes = b.axes = {{"lambda", {1.0}}};
  a.statistics = parse("R");
  b.statistics = parse("all");
  apply_statistics_selection(a);
  apply_statistics_selection(b);
  EXPECT_EQ(first_difference(a, b), "statistics: stick_fraction vs paper,family,derivatives,survival");
  for (const char* list : {"derivatives", "derivatives,D", "derivatives,survival,W_f"}) {
    sweep_spec s;
    s.statistics = parse(list);
    apply_statistics_selection(s);
    EXPECT_THROW(validate(s), error) << list;
  }
  for (const char* list : {"R,derivatives", "paper,derivatives", "S_L/t_a,derivatives"}) {
    sweep_spec s;
    s.statistics = parse(list);
    apply_statistics_selection(s);
    EXPECT_NO_THROW(validate(s)) << list;
  }
}

// A target CI needs its statistic selected.
TEST(StatisticsSelection, ATargetStatisticMustBeSelected) {
  sweep_spec s;
  s.target_statistic = "friction_power";
  s.target_halfwidth = 0.1;
  s.min_realizations = 100;
  EXPECT_THROW(validate(s), error);
  s.statistics = parse("paper,W_f");
  apply_statistics_selection(s);
  EXPECT_NO_THROW(validate(s));
}

// The paper model's per-realization means (R, S_T/t_a, S_L/t_a, D_1) are the
// same bits whichever engine configuration a selection picks (means only,
// the paper's, the family's), on both engines; the pooled D and H the same
// with and without the family statistics.
TEST(StatisticsSelection, ThePapersStatisticsAreTheSameBitsUnderEverySelection) {
  sweep_spec base;
  base.axes = {{"lambda", {0.5, 3.8}}, {"mu", {2.0, 5.0}}};
  base.realizations = 300;
  base.block_size = 50;
  base.seed = 9;
  std::vector<result_set> runs;
  for (const char* list : {"R,S_T/t_a,S_L/t_a,D_1", "paper", "all"})
    for (auto engine : {sweep_engine::fast, sweep_engine::reference}) {
      sweep_spec s = base;
      s.statistics = parse(list);
      s.engine = engine;
      apply_statistics_selection(s);
      resolve_survival_grid(s);
      runs.push_back(run_sweep(s, 2));
    }
  const auto& ref = runs[2];  // paper, fast
  for (const auto& r : runs)
    for (std::size_t i = 0; i < ref.points.size(); ++i) {
      const auto& a = r.points[i].stats;
      const auto& b = ref.points[i].stats;
      for (auto m : {&point_statistics::stick_fraction, &point_statistics::sticks_per_time,
                     &point_statistics::slips_per_time, &point_statistics::first_stick_duration})
        EXPECT_EQ(a.*m, b.*m) << i;
      if (!r.spec.means_only) {
        EXPECT_EQ(a.stick_duration, b.stick_duration) << i;
        EXPECT_EQ(a.slip_duration, b.slip_duration) << i;
        EXPECT_EQ(a.stick_duration_hist, b.stick_duration_hist) << i;
      }
    }
}

}  // namespace
}  // namespace stickslip
