// The sweep of the paper's figures (k = 40) that the precision tests run.
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "stickslip/sweep.hpp"

namespace stickslip::testing_support {

// k = 40, friction mu, lambda over `lambdas`; n realizations per point.
inline sweep_spec figure_spec(double mu, std::vector<double> lambdas, std::uint64_t n, bool crn,
                              std::uint64_t seed) {
  sweep_spec s;
  s.base.stiffness = 40.0;
  s.base.friction_coefficient = mu;
  s.axes = {{"lambda", std::move(lambdas)}};
  s.realizations = n;
  s.seed = seed;
  s.common_random_numbers = crn;
  return s;
}

}  // namespace stickslip::testing_support
