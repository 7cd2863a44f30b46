// Regression (found by fuzz_simulator): finite but enormous magnitudes made
// B^2 = (w y)^2 + x'^2 overflow in the slip step, and simulate() reported an
// episode starting at NaN with no error. Validation must refuse them, and any
// state it accepts must give finite episode times.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "stickslip/belt_switches.hpp"
#include "stickslip/error.hpp"
#include "stickslip/initial_conditions.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/observer.hpp"

using namespace stickslip;

namespace {
struct finite_times : observer_base {
  bool ok = true;
  void on_episode(const episode& e) { ok = ok && std::isfinite(e.start) && std::isfinite(e.end); }
};
}  // namespace

TEST(OverflowingMagnitudes, FuzzerInputIsRefused) {
  model_parameters p{9.81, 0.5, 1.0, 7.556e78, 6.924e274, 0.5, 1.0};
  try {
    validate(p);
    FAIL() << "validate accepted mu = 7.556e78, V = 6.924e274";
  } catch (const error& e) {
    EXPECT_EQ(e.code(), exit_code::invalid_input);
    EXPECT_NE(std::string(e.what()).find("between 1e-60 and 1e60"), std::string::npos) << e.what();
  }
  EXPECT_THROW(validate(initial_conditions{7.556e78, 6.924e274, -1}), error);
}

TEST(OverflowingMagnitudes, LargestAcceptedScalesGiveFiniteEpisodes) {
  // Push every scale to the edge of the accepted range.
  for (double V : {1e-59, 1.0, 1e59}) {
    model_parameters p{1.0, 1.0, 1.0, 1.0, V, 0.5, 1.0};
    try {
      validate(p);
    } catch (const error&) {
      continue;  // a derived scale left the range: refused, fine
    }
    const initial_conditions ic{1e59, -1e59, 1};
    ASSERT_NO_THROW(validate(ic));
    finite_times obs;
    const std::vector<double> times{0.25, 0.5};
    given_switches sw(times);
    try {
      (void)simulate(p, ic, sw, obs, 100000);
    } catch (const error& e) {
      EXPECT_EQ(e.code(), exit_code::work_bound);
    }
    EXPECT_TRUE(obs.ok) << "V = " << V;
  }
}
