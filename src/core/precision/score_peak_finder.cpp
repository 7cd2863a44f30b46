#include "stickslip/precision/score_peak_finder.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include "stickslip/error.hpp"
#include "stickslip/precision/batch_means.hpp"
#include "stickslip/precision/common_peak_finder.hpp"

namespace stickslip::precision {

namespace {

// The root of the fitted derivative p(t) = a + b t + q t^2 in [t_lo, t_hi]
// where p falls through zero (p'(r) < 0: a maximum of the mean, not a
// minimum), the one nearest to the window's centre t = 0; NaN if there is
// none. The two roots in the form without cancellation (h/q and a/h), which
// also covers q = 0 (h/q is then infinite and a/h = -a/b).
double falling_root(const polynomial_fit& p, double t_lo, double t_hi) {
  const double a = p.coef[0], b = p.coef[1], q = p.coef[2];
  const double disc = b * b - 4 * a * q;
  double best = std::numeric_limits<double>::quiet_NaN();
  if (!(disc >= 0)) return best;
  const double h = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  for (const double t : {h / q, a / h}) {
    if (!std::isfinite(t) || t < t_lo || t > t_hi || !(p.derivative(t) < 0)) continue;
    if (std::isnan(best) || std::abs(t) < std::abs(best)) best = t;
  }
  return best;
}

// The delta-method standard error of a root r of the fitted p: from
// p(r; coef) = 0, dr/dcoef_j = -r^j / p'(r), with the coefficients'
// (batch-means) covariance.
double root_std_error(const polynomial_fit& p, double r) {
  const std::size_t k = p.coef.size();
  std::vector<double> g(k);
  double rj = 1.0;
  for (std::size_t j = 0; j < k; ++j, rj *= r) g[j] = rj / p.derivative(r);
  double var = 0.0;
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = 0; j < k; ++j) var += g[i] * p.covariance[i][j] * g[j];
  return std::sqrt(std::max(var, 0.0));
}

}  // namespace

peak_result find_peak_score(const score_group_evaluator& eval, const score_peak_options& so) {
  const peak_options& o = so.base;
  validate(o);
  if (so.groups < 5) throw invalid_parameter("groups", static_cast<double>(so.groups), ">= 5");
  if (!(so.end_share > 0.0 && so.end_share <= 1.0))
    throw invalid_parameter("end share", so.end_share, "in (0, 1]");
  const std::size_t groups = so.groups;
  const double target = o.target_halfwidth;
  std::uint64_t total = 0;
  double baseline = 0.0;  // the scan runs with 0 (any fixed value is unbiased)
  std::vector<std::vector<double>> values, derivatives;  // per group, per point
  const auto per_group_of = [&](std::uint64_t n) {
    return std::max<std::uint64_t>(2, (n + groups - 1) / groups);
  };

  // 1. The scan over the range, as find_peak_common's. The first window
  // reaches the best point's neighbours: the maximizer lies between them
  // unless the scan's noise is comparable to the curve's differences (then
  // the first stages walk, below).
  const auto scan_x = spaced_points(o.lo, o.hi, o.scan_points, o.log_scan);
  for (auto& g : eval(scan_x, per_group_of(o.initial_realizations), groups, 0, baseline))
    values.push_back(std::move(g.value));
  total += per_group_of(o.initial_realizations) * groups * scan_x.size();
  const auto scan = mean_curve(values);
  const auto best = interior_scan_maximum(scan_x, scan, o);
  double c = scan_x[best];
  double w = std::max(c - scan_x[best - 1], scan_x[best + 1] - c);
  // The scan's window spans two scan intervals and may be wider than the
  // curve's own scale, where the 3-point model's next-order error exceeds
  // its bias term (a noisy q hides it: a synthetic skewed quartic stopped
  // there 0.35 from its maximizer, 4 - 8 half-widths). A window is trusted
  // to freeze or stop only once it has shrunk below this one.
  const double scan_w = w;
  // The control's coefficient from now on: the scan's highest mean is near
  // the peak's value, which minimizes the derivative estimator's variance
  // there; it stays fixed, so every stage's estimate stays unbiased.
  baseline = scan[best];
  std::uint64_t n = o.initial_realizations;

  // One stage's groups at the 3 points: the centre with `per_group`
  // realizations, the two ends with end_share of them, in two calls of the
  // same stage (each group's seed depends on the stage and the group only,
  // so a group's ends share their random numbers with its centre's first
  // realizations). Rows are (left, centre, right).
  const auto run_stage = [&](const std::vector<double>& xs, std::uint64_t per_group,
                             std::uint64_t per_end, std::size_t count, std::uint64_t stage) {
    auto centre = eval({xs[1]}, per_group, count, stage, baseline);
    auto ends = eval({xs[0], xs[2]}, per_end, count, stage, baseline);
    for (std::size_t g = 0; g < count; ++g) {
      values.push_back({ends[g].value[0], centre[g].value[0], ends[g].value[1]});
      derivatives.push_back(
          {ends[g].derivative[0], centre[g].derivative[0], ends[g].derivative[1]});
    }
    total += (per_group + 2 * per_end) * count;
  };

  // 2. Stages: 3 points c - w, c, c + w. Near the root the estimate is the
  // Newton step c - D(c)/D'(c), corrected by the quadratic through the 3
  // derivative values: its sampling error is the centre's derivative error
  // over |R''|, so the centre gets the realizations; the ends only give the
  // slope and the curvature, whose errors enter multiplied by t* and t*^2
  // (small once the root is central), and get end_share of them. While the
  // window moves and shrinks each stage runs `groups` new groups; once the
  // root is central and the bias term small the window is frozen and later
  // stages add groups at the same points, as in find_peak_common.
  peak_result r;
  bool frozen = false;
  std::vector<double> xs;
  std::uint64_t per_group = 0, per_end = 0;
  std::size_t add = groups;
  for (std::size_t stage = 1; stage <= o.max_stages; ++stage) {
    const double wlo = std::max(o.lo, c - w), whi = std::min(o.hi, c + w);
    if (!frozen) {
      xs = spaced_points(wlo, whi, 3, false);
      per_group = per_group_of(n);
      per_end = std::max<std::uint64_t>(
          2, static_cast<std::uint64_t>(std::ceil(so.end_share * static_cast<double>(per_group))));
      add = groups;
      values.clear();
      derivatives.clear();
    }
    const std::uint64_t cost = (per_group + 2 * per_end) * add;
    if (total + cost > o.max_total_realizations) break;
    run_stage(xs, per_group, per_end, add, stage);
    r.stages = stage;
    peak_stage progress{stage, wlo, whi, xs.size(), cost, total};
    const auto report = [&] {
      if (o.on_stage) o.on_stage(progress);
    };
    const double t_quantile = student_t95(derivatives.size() - 1);
    const double mid = xs[1], half = 0.5 * (xs[2] - xs[0]);  // t = (x - mid)/half
    const auto dquad = fit_groups(xs, derivatives, 2, mid, half);  // exact through the 3 points
    const double tq = falling_root(dquad, -1.0, 1.0);
    if (!(dquad.coef[1] < 0) || std::isnan(tq)) {
      // The derivative does not fall through zero in the window: the peak
      // lies beyond it, or the window is too narrow for the noise. Move to
      // the end the mean derivative points to (uphill) and widen.
      report();
      c = dquad.coef[0] > 0 ? whi : wlo;
      w *= 1.5;
      frozen = false;
      continue;
    }
    const double xq = mid + half * tq;
    // The bias term, in two parts. (1) The size of the quadratic's
    // correction to the Newton step from the centre, |x_q - (mid - D/D')|
    // ~ |q| t*^2/|b| (t in half-windows). (2) Half the bias of the line
    // through the 3 points, ~ |q|/(3 |b|) half-windows, with q less two of
    // its standard errors: the 3-point model leaves out the next order, the
    // interpolation error R'''' t* (t*^2 - 1) w^3/6 over |R''|, which is
    // below (2) while the window is small against the curve's own scale, and
    // (2) keeps a wide window from stopping on a curvature the noise hides;
    // the noise is taken out so that (2) fades as the window shrinks (with
    // the ends' few realizations q is noisy; a noisy floor would cost
    // realizations, docs/precision.md). The synthetic problems check both.
    const double b = dquad.coef[1], q = dquad.coef[2];
    const double tnewton = -dquad.coef[0] / b;
    const double q_signal = std::max(0.0, std::abs(q) - 2.0 * std::sqrt(dquad.covariance[2][2]));
    r.argmax = xq;
    r.sampling_halfwidth = t_quantile * half * root_std_error(dquad, tq);
    r.model_bias = half * std::max(std::abs(tq - tnewton), q_signal * 2.0 / (3.0 * std::abs(b)));
    const double hw = r.sampling_halfwidth + r.model_bias;
    r.argmax_lo = xq - hw;
    r.argmax_hi = xq + hw;
    // 3. The maximum: the quadratic through the 3 values at x_q (x_q treated
    // as fixed: the mean is flat there), against the second-order Taylor
    // expansion from the centre with the derivative fit's D and D'. Both are
    // second-order estimates of the same value; their difference bounds the
    // local model's error.
    const auto vquad = fit_groups(xs, values, 2, mid, half);
    const double u = xq - mid;
    const double taylor = vquad.value(0) + dquad.coef[0] * u + dquad.coef[1] / half * u * u / 2;
    r.max = vquad.value(tq);
    const double max_hw = t_quantile * vquad.value_std_error(tq) + std::abs(r.max - taylor);
    r.max_lo = r.max - max_hw;
    r.max_hi = r.max + max_hw;
    r.window_lo = wlo;
    r.window_hi = whi;
    r.points_in_fit = xs.size();
    progress.estimate = true;
    progress.argmax = r.argmax;
    progress.sampling_halfwidth = r.sampling_halfwidth;
    progress.model_bias = r.model_bias;
    report();
    // 4. Stop with the root in the central 60 % of the window (the errors of
    // the ends enter with t* and t*^2, and the interpolation error grows
    // towards them) and enough groups for a stable error estimate
    // (find_peak_common's reason).
    const bool centred = std::abs(tq) <= 0.6, trusted = w < scan_w;
    if (hw <= target && centred && trusted && derivatives.size() >= so.min_groups_to_stop) {
      r.target_met = true;
      break;
    }
    // 5. The sampling part falls like 1/sqrt(groups or n); the frozen
    // window adds what it needs (find_peak_common's rule).
    const double ratio = r.sampling_halfwidth / (so.sampling_share * target);
    if (centred && trusted && r.model_bias <= 1.5 * so.bias_share * target) {
      frozen = true;
      add = groups_to_add(derivatives.size(), ratio, so.min_groups_to_stop);
      continue;
    }
    // Moving on: re-centre on the root and shrink the window so that the
    // bias term (~ w^2 at a given t*) would be bias_share of the target, at
    // most 0.4x per stage; but keep the root's 95 % interval inside the
    // window (w at least the sampling half-width) and w at least half the
    // target (a narrower window buys nothing). The root's standard error is
    // the derivative's at the root over |R''|, which to first order does not
    // depend on w: n alone sets the sampling part, n *= ratio^2 (at most 8x
    // per stage, as find_peak_common).
    frozen = false;
    double shrink =
        r.model_bias > 0 ? std::clamp(std::sqrt(so.bias_share * target / r.model_bias), 0.4, 1.0)
                         : 1.0;
    if (!trusted) shrink = std::min(shrink, 0.5);
    w = std::min(w, std::max({w * shrink, r.sampling_halfwidth, 0.5 * target}));
    c = std::clamp(xq, o.lo, o.hi);
    const double want = static_cast<double>(n) * ratio * ratio;
    n = std::isfinite(want) ? static_cast<std::uint64_t>(std::clamp(
                                  want, static_cast<double>(n), 8.0 * static_cast<double>(n)))
                            : 8 * n;
  }
  r.realizations = total;
  return r;
}

}  // namespace stickslip::precision
