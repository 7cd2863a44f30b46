// The peak finder on derivative data (docs/precision.md): the evaluator
// returns, per group and point, the group's mean of the statistic and an
// unbiased estimate of its derivative in x (for R(lambda), the causal
// likelihood-ratio estimator), and the maximizer is the root of the mean
// derivative D. Each stage evaluates 3 points c - w, c, c + w in G
// independent groups, common random numbers across the points within a
// group; D(t) = a + b t + q t^2 near the root, with b and q from the
// derivatives at the 3 points and a = D(c) the best mix of the derivative
// at the centre and the values' central difference corrected by q (its
// error O(w^4)). The root's sampling error is a's over |R''|: with the
// derivative alone it does not grow as the window shrinks (unlike a
// maximizer fitted to values); the values' part does, as their variance
// grows at small w. Where the values do not pay (their variance above half
// the derivative's), the ends get 1/8 of the centre's realizations and a is
// the derivative alone.
// Coefficient covariances are batch means over the groups, as in
// find_peak_common. No I/O.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "stickslip/precision/peak_finder.hpp"

namespace stickslip::precision {

// Per group: at each point xs[i], the group's mean of the statistic and its
// unbiased estimate of d mean/dx (the evaluator applies `baseline` as the
// coefficient of its mean-zero control; any fixed value keeps the estimate
// unbiased, the mean at the peak minimizes its variance).
struct score_group {
  std::vector<double> value, derivative;
};

// Groups are independent of each other and of other stages (the CLI derives
// each group's seed from (seed, stage, group)).
using score_group_evaluator = std::function<std::vector<score_group>(
    const std::vector<double>& xs, std::uint64_t realizations, std::size_t groups,
    std::uint64_t stage, double baseline)>;

struct score_peak_options {
  peak_options base;            // range, target, scan, budget, stages (not window_points)
  std::size_t groups = 20;      // independent groups per stage (>= 5)
  std::size_t min_groups_to_stop = 40;  // groups in the final fit, at least (as find_peak_common)
  // The next stage aims at a bias term of bias_share x the target (by the
  // window) and a sampling part of sampling_share x the target (by n), as in
  // find_peak_common.
  double bias_share = 0.2, sampling_share = 0.8;
};

// The result is the last stage's (a frozen window's stages pool their
// groups). Throws like find_peak (the scan's maximum at an end of the range,
// invalid options).
[[nodiscard]] peak_result find_peak_score(const score_group_evaluator& eval,
                                          const score_peak_options& o);

}  // namespace stickslip::precision
