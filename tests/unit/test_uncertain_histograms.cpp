// The histograms of a point with laws hold the mixture: their ranges come
// from histogram_parameters (each law at the quantile that widens them), not
// from the median model, whose stick-band and stick-duration ranges cut off
// ~12 % of the stick-onset positions and ~1 % of the stick durations of
// mu ~ gamma(mean=5, cv=0.2) (found by a new user's check of records.csv).
#include <gtest/gtest.h>

#include "stickslip/sweep.hpp"
#include "stickslip/uncertainty/parameter_law.hpp"

namespace stickslip {
namespace {

TEST(UncertainHistograms, RangesHoldTheMixture) {
  sweep_spec s;
  s.base.stiffness = 40.0;
  s.base.switch_rate = 1.0;
  s.uncertain = {{"mu", parse_law("gamma(mean=5,cv=0.2)", "--mu")}};
  s.realizations = 2000;
  s.seed = 9;
  const auto rs = run_sweep(s, 2);
  const auto& st = rs.points.front().stats;
  const double onsets = static_cast<double>(st.stick_onset_position_hist.total());
  ASSERT_GT(onsets, 10000.0);
  const double outside = static_cast<double>(st.stick_onset_position_hist.underflow() +
                                             st.stick_onset_position_hist.overflow());
  EXPECT_LT(outside / onsets, 0.002) << outside << " of " << onsets << " onsets outside";
  EXPECT_LT(static_cast<double>(st.stick_duration_hist.overflow()),
            0.002 * static_cast<double>(st.stick_duration_hist.total()));
  // The range is wider than the median model's, and only as wide as the
  // law's 0.999 quantile makes it.
  const auto median = point_parameters(s, 0), widest = histogram_parameters(s, 0);
  EXPECT_GT(widest.friction_coefficient, median.friction_coefficient);
  EXPECT_NEAR(widest.friction_coefficient, quantile(s.uncertain[0].law, 0.999), 1e-12);
}

}  // namespace
}  // namespace stickslip
