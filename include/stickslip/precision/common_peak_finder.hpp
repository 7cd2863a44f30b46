// The peak finder with common random numbers (docs/precision.md): each stage
// evaluates the window's points in G independent groups; within a group
// every point uses the same random numbers (sweep_spec::
// common_random_numbers), so the group's curve is smooth and its shape, the
// part the maximizer depends on, has a small variance. The local
// polynomials are fitted to the mean curve of the stage; their coefficients'
// covariance comes from the spread of the groups' fits (batch means: the
// groups are independent replicates of the stage), so the correlation of the
// points is accounted for, and the sampling half-width uses Student's t with
// G - 1 degrees of freedom. The local-model bias term is find_peak's:
// max(|x_4 - x_c|, |x_q - x_c| / 2). No I/O.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "stickslip/precision/peak_finder.hpp"

namespace stickslip::precision {

// means[g][i]: the mean of group g at xs[i], each group of `realizations`
// realizations with common random numbers across the points and independent
// of the other groups and of other stages.
using group_evaluator = std::function<std::vector<std::vector<double>>(
    const std::vector<double>& xs, std::uint64_t realizations, std::size_t groups,
    std::uint64_t stage)>;

struct common_peak_options {
  peak_options base;         // range, target, scan, budget, stages (not window_points)
  std::size_t groups = 20;   // independent groups per stage (>= 5)
  std::size_t min_groups_to_stop = 40;  // groups in the final fit, at least
  // Points per window (>= 5). With common random numbers the errors of
  // neighbouring points are strongly correlated, so the shape information
  // is in the spread of the points: 5 give nearly the precision of 9 at
  // 5/9 of the cost (measured: docs/precision.md).
  std::size_t window_points = 5;
  // The next stage aims at a bias term of bias_share x the target (by the
  // window) and a sampling part of sampling_share x the target (by n). With
  // bias ~ w^2 and sampling ~ 1/sqrt(w n), the cost is least at a bias of
  // 1/5 of the half-width; 0.8 for the sampling part: docs/precision.md
  // (coverage and cost of 0.75, 0.8, 0.85).
  double bias_share = 0.2, sampling_share = 0.8;
};

// The stages do not pool: each stage's estimate stands on its own data (the
// level of a group's curve varies between stages; its shape is what counts),
// and the result is the last stage's. Throws like find_peak.
[[nodiscard]] peak_result find_peak_common(const group_evaluator& eval,
                                           const common_peak_options& o);

// The two-sided 95 % quantile of Student's t with `dof` degrees of freedom
// (Cornish-Fisher expansion; within 0.3 % for dof >= 4, 1e-4 for dof >= 19).
[[nodiscard]] double student_t95(std::size_t dof) noexcept;

}  // namespace stickslip::precision
