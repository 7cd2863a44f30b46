// The peak finder on derivative data (docs/precision.md): the evaluator
// returns, per group and point, the group's mean of the statistic and an
// unbiased estimate of its derivative in x (for R(lambda), the causal
// likelihood-ratio estimator), and the maximizer is the root of the mean
// derivative. Each stage evaluates 3 points c - w, c, c + w in G independent
// groups; the quadratic through the three derivative values has a root whose
// bias is third order in w, so the window need not shrink much, and the
// sampling error of the root is that of the derivative at the root, which
// does not grow as the window shrinks (unlike a maximizer fitted to values).
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
  // Realizations at each end of the window per realization at its centre:
  // the ends only give the slope and curvature, whose errors enter the root
  // multiplied by t* and t*^2 (docs/precision.md).
  double end_share = 0.125;
};

// The result is the last stage's (a frozen window's stages pool their
// groups). Throws like find_peak (the scan's maximum at an end of the range,
// invalid options).
[[nodiscard]] peak_result find_peak_score(const score_group_evaluator& eval,
                                          const score_peak_options& o);

}  // namespace stickslip::precision
