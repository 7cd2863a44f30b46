#include "stickslip/precision/score_peak_finder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

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

// One group's estimates at the 3 points (left, centre, right) of a window
// of half-width `half`, in t = (x - mid)/half: the derivative D(t) ~ a + b t
// + q t^2 and the checks of the bias terms.
struct group_estimate {
  double d_centre, d_values;  // D(0): the score at the centre; from the values
  double b, q;                // from the scores at the 3 points
  double b_values;            // b from the values' second difference
};
group_estimate estimate_of(const std::vector<double>& v, const std::vector<double>& d,
                           double half) {
  group_estimate e;
  e.d_centre = d[1];
  e.b = 0.5 * (d[2] - d[0]);
  e.q = 0.5 * (d[0] + d[2] - 2.0 * d[1]);
  // The values' central difference is D(0) + R''' h^2/6 + R^(5) h^4/120;
  // the scores' second difference gives R''' h^2/6 = q/3 (+ R^(5) h^4/72),
  // so the corrected difference is D(0) to O(h^4). With common random
  // numbers its variance falls as h grows (mu = 5: 1/5.4 of the score's at
  // the centre for h = 0.1, 1/14 for h = 0.4; mu = 0.5: about the score's at
  // h = 0.17, 1/3.3 at h = 0.4), and it is nearly uncorrelated with the
  // score.
  e.d_values = (v[2] - v[0]) / (2.0 * half) - e.q / 3.0;
  // R'' h^2 = V(+) + V(-) - 2 V(0) (+ R'''' h^4/12), against b = R'' h
  // (+ R'''' h^3/6) from the scores.
  e.b_values = (v[2] + v[0] - 2.0 * v[1]) / half;
  return e;
}

// mean and standard error of f over the groups.
template <class F>
std::pair<double, double> group_mean(const std::vector<group_estimate>& es, F f) {
  double m = 0.0, m2 = 0.0;
  const auto g = static_cast<double>(es.size());
  for (const auto& e : es) m += f(e) / g;
  for (const auto& e : es) m2 += (f(e) - m) * (f(e) - m);
  return {m, std::sqrt(m2 / (g * (g - 1.0)))};
}

}  // namespace

peak_result find_peak_score(const score_group_evaluator& eval, const score_peak_options& so) {
  const peak_options& o = so.base;
  validate(o);
  if (so.groups < 5) throw invalid_parameter("groups", static_cast<double>(so.groups), ">= 5");
  const std::size_t groups = so.groups;
  const double target = o.target_halfwidth;
  std::uint64_t total = 0;
  double baseline = 0.0;  // the scan runs with 0 (any fixed value is unbiased)
  std::vector<std::vector<double>> values, derivatives;  // per group, per point
  auto run = [&](const std::vector<double>& xs, std::uint64_t per_group, std::size_t count,
                 std::uint64_t stage) {
    for (auto& g : eval(xs, per_group, count, stage, baseline)) {
      values.push_back(std::move(g.value));
      derivatives.push_back(std::move(g.derivative));
    }
    total += per_group * count * xs.size();
  };
  const auto per_group_of = [&](std::uint64_t n) {
    return std::max<std::uint64_t>(2, (n + groups - 1) / groups);
  };
  // The centre design: the centre with `per_group` realizations and the two
  // ends with 1/8 of them, in two calls of the same stage (a group's seed
  // depends on the stage and the group only, so its ends share their random
  // numbers with its centre's first realizations). Rows (left, centre, right).
  const auto run_centre = [&](const std::vector<double>& xs, std::uint64_t per_group,
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

  // 1. The scan over the range, as find_peak_common's.
  const auto scan_x = spaced_points(o.lo, o.hi, o.scan_points, o.log_scan);
  run(scan_x, per_group_of(o.initial_realizations), groups, 0);
  const auto scan = mean_curve(values);
  const auto best = interior_scan_maximum(scan_x, scan, o);
  double c = scan_x[best];
  double w = std::max(c - scan_x[best - 1], scan_x[best + 1] - c);
  // The scan's window spans two scan intervals and may be wider than the
  // curve's own scale, where the 3-point model's next-order error exceeds
  // what its bias terms show while the noise is large (a synthetic skewed
  // quartic stopped there 0.35 from its maximizer). A window is trusted to
  // freeze or stop only once it has shrunk below this one.
  const double scan_w = w;
  // The control's coefficient from now on: the scan's highest mean is near
  // the peak's value, which minimizes the score's variance there; it stays
  // fixed, so every stage's estimate stays unbiased.
  baseline = scan[best];
  std::uint64_t n = o.initial_realizations;

  // 2. Stages: 3 points c - w, c, c + w, every group with common random
  // numbers across them. D(t) = a + b t + q t^2: b and q from the scores at
  // the 3 points (strongly correlated, so their differences are precise), a
  // = D at the centre as the best combination of two estimates, the score
  // there and the values' corrected central difference (estimate_of), with
  // the weight that minimizes the variance of the mix over the stage's
  // groups. The estimate is the falling root of the mean polynomial; its
  // interval is batch means over the groups, as find_peak_common's. While
  // the window moves and shrinks each stage runs `groups` new groups; once
  // the root is central and the bias term small the window is frozen and
  // later stages add groups at the same points.
  peak_result r;
  bool frozen = false;
  std::vector<double> xs;
  std::uint64_t per_group = 0, per_end = 0;
  std::size_t add = groups;
  // Which design a new window gets. The values' estimate of D at the centre
  // needs all 3 points at n realizations (3n per group), the score alone
  // only the centre (1.25n with the ends at n/8 for b and q). With the two
  // estimates uncorrelated the values break even at a variance ratio of
  // 0.71 (information (1/V_s + 1/V_v)/3 against 1/(1.25 V_s) per
  // realization); the rule asks for 0.5, leaning to the centre design, whose
  // interval has no weight to estimate. The first window measures both;
  // later ones follow the last window's measurement (mu = 5: 0.12 at h =
  // 0.2; mu = 0.5: ~0.8 at h = 0.17).
  bool values_design = true;
  double alpha_prior = 0.5;  // the score's weight in a values design's D(0)
  for (std::size_t stage = 1; stage <= o.max_stages; ++stage) {
    const double wlo = std::max(o.lo, c - w), whi = std::min(o.hi, c + w);
    if (!frozen) {
      xs = spaced_points(wlo, whi, 3, false);
      per_group = per_group_of(n);
      per_end = values_design ? per_group : std::max<std::uint64_t>(2, (per_group + 7) / 8);
      add = groups;
      values.clear();
      derivatives.clear();
    }
    const std::uint64_t cost = (per_group + 2 * per_end) * add;
    if (total + cost > o.max_total_realizations) break;
    if (values_design)
      run(xs, per_group, add, stage);
    else
      run_centre(xs, per_group, per_end, add, stage);
    r.stages = stage;
    peak_stage progress{stage, wlo, whi, xs.size(), cost, total};
    const auto report = [&] {
      if (o.on_stage) o.on_stage(progress);
    };
    const double t_quantile = student_t95(derivatives.size() - 1);
    const double mid = xs[1], half = 0.5 * (xs[2] - xs[0]);  // t = (x - mid)/half
    std::vector<group_estimate> es;
    for (std::size_t g = 0; g < derivatives.size(); ++g)
      es.push_back(estimate_of(values[g], derivatives[g], half));
    // The weight of the score in a: Var(mix) is least at
    // (V_v - C) / (V_s + V_v - 2 C), from the groups' spread.
    const auto [ms, ss] = group_mean(es, [](const group_estimate& e) { return e.d_centre; });
    const auto [mv, sv] = group_mean(es, [](const group_estimate& e) { return e.d_values; });
    double cov = 0.0;
    for (const auto& e : es) cov += (e.d_centre - ms) * (e.d_values - mv);
    cov /= static_cast<double>(es.size()) * static_cast<double>(es.size() - 1);
    const double denom = ss * ss + sv * sv - 2.0 * cov;
    // The weight comes from the previous look's groups: weights fitted to
    // the same groups would favour the mixes whose noise is small by chance
    // (the stand-in for mu = 5 covered 93.3 % with weights fitted to the
    // same groups, 94.2 % with the previous look's). In a frozen
    // window those groups are still in the pool, so this only dilutes that
    // selection; the synthetic coverage is what checks it.
    const double alpha = values_design ? alpha_prior : 1.0;
    if (values_design && denom > 0.0) alpha_prior = std::clamp((sv * sv - cov) / denom, 0.0, 1.0);
    // Per realization: the score's variance at the centre, the values'.
    const double groups_n = static_cast<double>(es.size());
    const double var_score = ss * ss * groups_n * static_cast<double>(per_group);
    const double var_values = sv * sv * groups_n * static_cast<double>(per_end);
    std::vector<std::vector<double>> coefs;
    for (const auto& e : es)
      coefs.push_back({alpha * e.d_centre + (1.0 - alpha) * e.d_values, e.b, e.q});
    const auto dquad = average_of_groups(coefs, mid, half);
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
    // The bias term, the sum of three noise-corrected parts (each less two
    // of its standard errors, so that they fade as the window shrinks or
    // the noise falls; what they bound is of higher order):
    // (1) the size of the quadratic's correction to the Newton step from
    //     the centre, |x_q - (mid - a/b)| ~ |q| t*^2/|b| half-windows: the
    //     next order of the local model is below it near the root;
    // (2) the values' estimate of a against the score's (their difference
    //     is the O(h^4) error of the values' one), times its weight;
    // (3) the two estimates of b against each other: their difference is
    //     R'''' h^3/12, half the scores' error R'''' h^3/6, which moves the
    //     root by t* db/b.
    const double b = dquad.coef[1];
    const double tnewton = -dquad.coef[0] / b;
    const auto [dv, dv_se] =
        group_mean(es, [](const group_estimate& e) { return e.d_values - e.d_centre; });
    const auto [db, db_se] =
        group_mean(es, [](const group_estimate& e) { return e.b_values - e.b; });
    const double values_bias = (1.0 - alpha) * std::max(0.0, std::abs(dv) - 2.0 * dv_se);
    const double slope_bias = 2.0 * std::abs(tq) * std::max(0.0, std::abs(db) - 2.0 * db_se);
    r.argmax = xq;
    r.sampling_halfwidth = t_quantile * half * root_std_error(dquad, tq);
    r.model_bias = half * (std::abs(tq - tnewton) + (values_bias + slope_bias) / std::abs(b));
    const double hw = r.sampling_halfwidth + r.model_bias;
    r.argmax_lo = xq - hw;
    r.argmax_hi = xq + hw;
    // 3. The maximum: the quadratic through the 3 values at x_q (x_q treated
    // as fixed: the mean is flat there), against the second-order Taylor
    // expansion from the centre with a and b. Both are second-order
    // estimates of the same value; their difference bounds the local
    // model's error.
    const auto vquad = fit_groups(xs, values, 2, mid, half);
    const double u = xq - mid;
    const double taylor = vquad.value(0) + dquad.coef[0] * u + b / half * u * u / 2;
    r.max = vquad.value(tq);
    const double max_hw = t_quantile * vquad.value_std_error(tq) + std::abs(r.max - taylor);
    record_stage_estimate(r, progress, max_hw, wlo, whi, xs.size());
    report();
    // 4. Stop with the root in the central 60 % of the window and enough
    // groups for a stable error estimate (find_peak_common's reason).
    const bool centred = std::abs(tq) <= 0.6, trusted = w < scan_w;
    if (hw <= target && centred && trusted && derivatives.size() >= so.min_groups_to_stop) {
      r.target_met = true;
      break;
    }
    // 5. The sampling part falls like 1/sqrt(groups or n); the frozen
    // window adds what it needs (find_peak_common's rule).
    const double ratio = r.sampling_halfwidth / (so.sampling_share * target);
    // A frozen window stays frozen while its root is central and its bias
    // term leaves room for the sampling part (half the target): moving
    // would throw its groups away for a small gain (mu = 5: a window whose
    // bias term rose from 0.0029 to 0.0031 moved and lost 40 % of the work).
    const double freeze_limit = (frozen ? 0.5 : 1.5 * so.bias_share) * target;
    if (centred && trusted && r.model_bias <= freeze_limit) {
      frozen = true;
      add = groups_to_add(derivatives.size(), ratio, so.min_groups_to_stop);
      continue;
    }
    values_design = var_values < 0.5 * var_score;
    // Moving on: re-centre on the root and shrink the window so that the
    // bias term would be bias_share of the target (each of its parts falls
    // at least like w^2), at most 0.4x per stage and at least 0.5x for the
    // scan's window; but keep the root's 95 % interval inside the window
    // and w at least half the target. n *= ratio^2 (at most 8x per stage,
    // as find_peak_common).
    frozen = false;
    double shrink =
        r.model_bias > 0 ? std::clamp(std::sqrt(so.bias_share * target / r.model_bias), 0.4, 1.0)
                         : 1.0;
    if (!trusted) shrink = std::min(shrink, 0.5);
    w = std::min(w, std::max({w * shrink, r.sampling_halfwidth, 0.5 * target}));
    c = std::clamp(xq, o.lo, o.hi);
    n = grown_realizations(n, static_cast<double>(n) * ratio * ratio);
  }
  r.realizations = total;
  return r;
}

}  // namespace stickslip::precision
