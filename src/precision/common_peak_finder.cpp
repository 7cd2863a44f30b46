#include "stickslip/precision/common_peak_finder.hpp"

#include <algorithm>
#include <cmath>

#include "stickslip/accumulators/mean_variance.hpp"
#include "stickslip/error.hpp"
#include "stickslip/precision/batch_means.hpp"

namespace stickslip::precision {

double student_t95(std::size_t dof) noexcept {
  // Cornish-Fisher: t = z + g1/nu + g2/nu^2 + g3/nu^3 (Abramowitz & Stegun 26.7.5).
  const double z = z95, nu = static_cast<double>(dof);
  const double z3 = z * z * z, z5 = z3 * z * z, z7 = z5 * z * z;
  const double g1 = (z3 + z) / 4, g2 = (5 * z5 + 16 * z3 + 3 * z) / 96;
  const double g3 = (3 * z7 + 19 * z5 + 17 * z3 - 15 * z) / 384;
  return z + g1 / nu + g2 / (nu * nu) + g3 / (nu * nu * nu);
}

peak_result find_peak_common(const group_evaluator& eval, const common_peak_options& co) {
  const peak_options& o = co.base;
  validate(o);
  if (co.groups < 5) throw invalid_parameter("groups", static_cast<double>(co.groups), ">= 5");
  if (co.window_points < 5)
    throw invalid_parameter("window points", static_cast<double>(co.window_points), ">= 5");
  const std::size_t groups = co.groups;
  std::uint64_t total = 0;
  auto run = [&](const std::vector<double>& xs, std::uint64_t per_group, std::size_t count,
                 std::uint64_t stage) {
    auto m = eval(xs, per_group, count, stage);
    total += per_group * count * xs.size();
    return m;
  };
  const auto per_group_of = [&](std::uint64_t n) {
    return std::max<std::uint64_t>(2, (n + groups - 1) / groups);
  };

  // 1. The scan over the range (one common-random-number curve).
  const auto scan_x = spaced_points(o.lo, o.hi, o.scan_points, o.log_scan);
  const auto scan =
      mean_curve(run(scan_x, per_group_of(o.initial_realizations), groups, 0));
  const auto best = interior_scan_maximum(scan_x, scan, o);
  double c = scan_x[best];
  double w = std::max(c - scan_x[best - 1], scan_x[best + 1] - c) * 1.5;
  std::uint64_t n = o.initial_realizations;

  // 2. Stages. While the window moves and shrinks, each stage runs `groups`
  // new groups of n / groups realizations at new points. Once the bias term
  // is small enough and the maximizer central, the window is frozen: later
  // stages add groups of the same size at the same points, and the fits use
  // every group of the frozen window (so no work is thrown away, and the
  // sampling part shrinks in small steps up to the target).
  peak_result r;
  bool frozen = false;
  std::vector<double> xs;
  std::vector<std::vector<double>> means;
  std::uint64_t per_group = 0;
  std::size_t add = groups;
  for (std::size_t stage = 1; stage <= o.max_stages; ++stage) {
    const double wlo = std::max(o.lo, c - w), whi = std::min(o.hi, c + w);
    if (!frozen) {
      xs = spaced_points(wlo, whi, co.window_points, false);
      per_group = per_group_of(n);
      add = groups;
      means.clear();
    }
    if (total + per_group * add * xs.size() > o.max_total_realizations) break;
    auto fresh = run(xs, per_group, add, stage);
    means.insert(means.end(), std::make_move_iterator(fresh.begin()),
                 std::make_move_iterator(fresh.end()));
    r.stages = stage;
    peak_stage progress{stage, wlo, whi, xs.size(), per_group * add * xs.size(), total};
    const auto report = [&] {
      if (o.on_stage) o.on_stage(progress);
    };
    const double t_quantile = student_t95(means.size() - 1);
    const double tlo = (wlo - c) / w, thi = (whi - c) / w;
    const auto quad = fit_groups(xs, means, 2, c, w);
    const auto cubic = fit_groups(xs, means, 3, c, w);
    const auto quartic = fit_groups(xs, means, 4, c, w);
    const auto mq = maximize(quad, tlo, thi);
    const auto mc = maximize(cubic, tlo, thi);
    const auto m4 = maximize(quartic, tlo, thi);
    if (!mq.interior) {  // not concave here, or the peak beyond the window
      report();
      c = std::clamp(c + w * mq.t, o.lo, o.hi);
      w *= 1.5;
      frozen = false;
      continue;
    }
    const double xq = c + w * mq.t;
    if (!mc.interior) {
      report();
      c = std::clamp(xq, o.lo, o.hi);
      w *= 0.7;
      frozen = false;
      continue;
    }
    const double xc = c + w * mc.t;
    r.argmax = xc;
    r.sampling_halfwidth = t_quantile * w * mc.t_std_error;
    r.model_bias =
        m4.interior ? std::max(std::abs(c + w * m4.t - xc), 0.5 * std::abs(xq - xc)) : w;
    const double hw = r.sampling_halfwidth + r.model_bias;
    r.argmax_lo = xc - hw;
    r.argmax_hi = xc + hw;
    r.max = cubic.value(mc.t);
    const double max_hw =
        t_quantile * cubic.value_std_error(mc.t) + std::abs(quad.value(mq.t) - r.max);
    record_stage_estimate(r, progress, max_hw, wlo, whi, xs.size());
    report();
    const bool centred = std::abs(mc.t) <= 0.6;
    // Stop only with enough groups for a stable error estimate: with 20 the
    // estimated standard error has a relative sd of ~16 %, and a stop rule
    // that looks at it repeatedly favours estimates that are small by chance
    // (synthetic coverage 94.6 % with 20, see docs/precision.md).
    if (hw <= o.target_halfwidth && centred && means.size() >= co.min_groups_to_stop) {
      r.target_met = true;
      break;
    }
    const double ratio = r.sampling_halfwidth / (co.sampling_share * o.target_halfwidth);
    if (centred && r.model_bias <= 1.5 * co.bias_share * o.target_halfwidth) {
      // Frozen (or freezing now): add the groups the sampling part needs,
      // at least half and at most 3x the groups so far. Few looks at the
      // data keep the stop rule from favouring an error estimate that is
      // small by chance (optional stopping).
      frozen = true;
      add = groups_to_add(means.size(), ratio, co.min_groups_to_stop);
      continue;
    }
    // Moving on. The bias term falls like w^2 (the quadratic-vs-cubic
    // floor) or faster, while with common random numbers the sampling part
    // grows only like w^-1/2 (the variance of a difference of one curve at
    // two points grows about linearly with their distance): shrink the
    // window so that the bias would be bias_share of the target, at most
    // 0.4x per stage; then choose n so that the sampling part would be
    // sampling_share of it.
    frozen = false;
    const double shrink =
        std::clamp(std::sqrt(co.bias_share * o.target_halfwidth / r.model_bias), 0.4, 1.0);
    w *= shrink;
    c = std::clamp(xc, o.lo, o.hi);
    n = grown_realizations(n, static_cast<double>(n) * ratio * ratio / shrink);
  }
  r.realizations = total;
  return r;
}

}  // namespace stickslip::precision
