// The estimate table (estimates.hpp): its rows, the names and texts it gives
// the writers, and that each row's estimate exists exactly where the row
// says it applies. That the outputs carry the same rows is
// tests/python/test_estimate_table.py.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "stickslip/estimates.hpp"

namespace stickslip {
namespace {

TEST(EstimateTable, RowsHaveUniqueNamesAndResultsNcNamesHoldTheQuantity) {
  std::set<std::string> names;
  for (const auto& row : estimate_kinds()) {
    EXPECT_TRUE(names.insert(row.name).second) << row.name;
    EXPECT_NE(std::string(row.variable).find("{q}"), std::string::npos) << row.name;
    EXPECT_EQ(&estimate_kind(row.name), &row);
    EXPECT_EQ(row.group, &statistics_selection::derivatives) << row.name;
  }
  EXPECT_THROW((void)estimate_kind("no such estimate"), std::out_of_range);
}

// results.nc's long_name fits xarray's one-line plot label (30 characters,
// with " [units]"), for every quantity and index name the writers give it.
TEST(EstimateTable, LongNamesFitAPlotLabel) {
  for (const auto& row : estimate_kinds())
    for (const auto& q : quantities()) {
      if (!row.has(q)) continue;
      for (const char* index : {"", "r1", "lambda", "q_ij"})
        for (int side : {-1, 0, 1})
          EXPECT_LE(estimate_long_name(row, q, index, side).size(), 30u)
              << estimate_long_name(row, q, index, side);
    }
}

// The names results.nc has always given the estimates, written out by hand.
TEST(EstimateTable, KeepsTheNamesOfResultsNc) {
  const auto& R = quantity_table[quantity_row("stick_fraction")];
  EXPECT_EQ(estimate_variable(estimate_kind("dmean_dlambda"), R.name, ""), "stick_fraction_dmean_dlambda");
  EXPECT_EQ(estimate_variable(estimate_kind("control_variate"), R.name, ""), "stick_fraction_cv");
  EXPECT_EQ(std::string(estimate_kind("control_variate").value_suffix), "_mean");
  EXPECT_EQ(estimate_variable(estimate_kind("dmean_drates"), R.name, "r2"), "stick_fraction_dmean_dr2");
  EXPECT_EQ(estimate_variable(estimate_kind("crn_slopes"), R.name, "mu"), "stick_fraction_dmean_dmu_crn");
  EXPECT_EQ(estimate_variable(estimate_kind("crn_slopes"), R.summary_name, "mu"), "R_dmean_dmu_crn");
  EXPECT_EQ(estimate_units(estimate_kind("dmean_dlambda"), R, ""), "s");
  EXPECT_EQ(estimate_units(estimate_kind("crn_slopes"), R, "mu"), "1");
  EXPECT_EQ(estimate_long_name(estimate_kind("dmean_drates"), R, "r1", -1), "slope low R r1");
  EXPECT_EQ(estimate_description(estimate_kind("control_variate"), R, "", 1).substr(0, 45),
            "mean + 1.96 x the residual standard error; co");
}

// Filled by hand: 10 realizations of R against made-up switch counts.
point_result poisson_point(double lambda) {
  point_result p;
  p.parameters.switch_rate = lambda;
  auto& s = p.stats;
  for (int i = 0; i < 10; ++i) {
    const double r = 0.1 * i, k = (i % 3) - 1.0;
    s.stick_fraction.add(r);
    s.stick_fraction_score.add(r, k);
    s.stick_fraction_causal_score.add(0.01 * i, 0.5 * k);
  }
  return p;
}

TEST(EstimateTable, AnEstimateExistsWhereItsRowApplies) {
  const sweep_spec spec;
  const auto p = poisson_point(2.0);
  const estimate_source src{spec, p, {}};
  const auto& R = quantity_table[quantity_row("stick_fraction")];
  ASSERT_TRUE(has_poisson_switching(p.parameters));
  for (const auto& row : estimate_kinds()) {
    if (!row.has(R)) continue;
    for (const auto i : estimate_indices(row, spec))
      EXPECT_EQ(row.at(src, R, i).has_value(), row.applies(src) &&
                                                   row.index != estimate_index::generator_entry)
          << row.name;
  }
  // The value is the estimator's, to the bit.
  const auto d = estimate_kind("dmean_dlambda").at(src, R, 0);
  const auto e = score_derivative(p.stats.stick_fraction_score, p.stats.stick_fraction, 2.0);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->value.value, e.value);
  EXPECT_EQ(d->value.std_error, e.std_error);
  const auto cv = estimate_kind("control_variate").at(src, R, 0);
  ASSERT_TRUE(cv);
  EXPECT_EQ(cv->variance_reduction,
            control_variate_mean(p.stats.stick_fraction_score, p.stats.stick_fraction)
                .variance_reduction);
}

TEST(EstimateTable, MeanEstimateIsTheIntervalOfEveryMean) {
  mean_variance m;
  for (double x : {1.0, 2.0, 4.0, 8.0}) m.add(x);
  const auto e = mean_estimate(m);
  EXPECT_EQ(e.value, m.mean());
  EXPECT_EQ(e.ci95_half_width(), m.ci95_half_width());
}

}  // namespace
}  // namespace stickslip
