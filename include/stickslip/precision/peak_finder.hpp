// Locating the maximizer of a mean statistic over one parameter to a target
// 95 % half-width, with an interval that accounts for both the sampling error
// and the bias of the local model (docs/precision.md explains the method and
// its coverage test). The finder only sees an evaluator: the CLI's runs
// exact sweeps, the tests simulate noisy evaluations of known curves. No I/O.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "stickslip/precision/local_fit.hpp"

namespace stickslip::precision {

// Evaluates the mean at each x with `realizations` realizations per point.
// `stage` numbers the calls (0, 1, ...): evaluations of different stages must
// be statistically independent (the CLI derives the sweep seed from it).
using evaluator = std::function<std::vector<evaluation>(
    const std::vector<double>& xs, std::uint64_t realizations, std::uint64_t stage)>;

// What a finder reports after each refinement stage (progress of a long
// search): the stage's window and design, the estimate so far when the
// local fits have an interior maximum, and the realizations spent.
struct peak_stage {
  std::size_t stage = 0;
  double window_lo = 0.0, window_hi = 0.0;
  std::size_t points = 0;                 // points in the window
  std::uint64_t realizations_added = 0;   // by this stage
  std::uint64_t realizations = 0;         // so far, the scan included
  bool estimate = false;                  // false: the window moves on
  double argmax = 0.0, sampling_halfwidth = 0.0, model_bias = 0.0;
};

struct peak_options {
  double lo = 0.0, hi = 0.0;       // the search range (lo < hi)
  bool log_scan = false;           // space the first scan geometrically (lo > 0)
  double target_halfwidth = 0.01;  // in x, of the 95 % interval
  std::size_t scan_points = 17;    // the first scan over [lo, hi]
  std::size_t window_points = 9;   // new points per refinement stage
  std::uint64_t initial_realizations = 1000;  // per point, first scan and first stage
  std::uint64_t max_total_realizations = std::uint64_t{1} << 32;  // budget over all stages
  std::size_t max_stages = 40;
  std::function<void(const peak_stage&)> on_stage;  // optional progress report
};

// Throws stickslip::error naming the first invalid option.
void validate(const peak_options& o);

struct peak_result {
  double argmax = 0.0;
  double argmax_lo = 0.0, argmax_hi = 0.0;  // 95 %: sampling + local-model bias
  double sampling_halfwidth = 0.0;  // 1.96 x the delta-method standard error of x_c
  double model_bias = 0.0;  // max(|x_4 - x_c|, |x_q - x_c| / 2): quartic, cubic, quadratic maximizers
  double max = 0.0;
  double max_lo = 0.0, max_hi = 0.0;
  double window_lo = 0.0, window_hi = 0.0;  // the last local fit's window
  std::uint64_t realizations = 0;           // over all evaluations
  std::size_t stages = 0;                   // refinement stages run
  std::size_t points_in_fit = 0;
  bool target_met = false;
  [[nodiscard]] double halfwidth() const noexcept { return (argmax_hi - argmax_lo) / 2; }
};

// Throws stickslip::error when the maximum of the first scan sits at an end
// of the range (the maximizer may lie outside it).
[[nodiscard]] peak_result find_peak(const evaluator& eval, const peak_options& o);

// A sweep seed for a stage: a hash of (seed, stage), so that stages draw
// independent streams (never seed + stage).
[[nodiscard]] std::uint64_t stage_seed(std::uint64_t seed, std::uint64_t stage) noexcept;

// n >= 2 points from lo to hi, both ends exact: geometrically or evenly
// spaced (the scans and stage windows of both finders).
[[nodiscard]] std::vector<double> spaced_points(double lo, double hi, std::size_t n, bool geometric);

}  // namespace stickslip::precision
