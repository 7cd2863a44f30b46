#include "stickslip/precision/peak_finder.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "stickslip/accumulators/mean_variance.hpp"
#include "stickslip/error.hpp"

namespace stickslip::precision {

void validate(const peak_options& o) {
  if (!std::isfinite(o.lo) || !std::isfinite(o.hi) || !(o.lo < o.hi))
    throw invalid_parameter("range upper end", o.hi, fmt::format("> the lower end {}", o.lo));
  if (o.log_scan && !(o.lo > 0))
    throw invalid_parameter("range lower end", o.lo, "> 0 for a geometric scan");
  if (!(o.target_halfwidth > 0) || !std::isfinite(o.target_halfwidth))
    throw invalid_parameter("target half-width", o.target_halfwidth, "> 0");
  if (o.scan_points < 5) throw invalid_parameter("scan points", double(o.scan_points), ">= 5");
  if (o.window_points < 5)
    throw invalid_parameter("window points", double(o.window_points), ">= 5");
  if (o.initial_realizations < 2)
    throw invalid_parameter("initial realizations", double(o.initial_realizations), ">= 2");
}

std::vector<double> spaced_points(double lo, double hi, std::size_t n, bool geometric) {
  std::vector<double> xs(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double f = static_cast<double>(i) / static_cast<double>(n - 1);
    xs[i] = geometric ? lo * std::pow(hi / lo, f) : lo + (hi - lo) * f;
  }
  xs.front() = lo;
  xs.back() = hi;
  return xs;
}

std::uint64_t stage_seed(std::uint64_t seed, std::uint64_t stage) noexcept {
  // splitmix64 of the pair: distinct stages give unrelated seeds.
  std::uint64_t z = seed ^ (0x9e3779b97f4a7c15ULL * (stage + 1));
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

namespace {

// The goodness-of-fit level below which the local cubic is rejected as a
// model of the curve in its window (the window then shrinks).
constexpr double min_fit_p_value = 0.01;

}  // namespace

peak_result find_peak(const evaluator& eval, const peak_options& o) {
  validate(o);
  std::vector<evaluation> pool;
  std::vector<std::uint64_t> pool_n;
  std::uint64_t total = 0;
  auto run = [&](const std::vector<double>& xs, std::uint64_t n, std::uint64_t stage) {
    auto ev = eval(xs, n, stage);
    total += n * xs.size();
    for (auto& e : ev) {
      pool.push_back(e);
      pool_n.push_back(n);
    }
    return ev;
  };

  // 1. The scan over the range.
  const auto scan = run(spaced_points(o.lo, o.hi, o.scan_points, o.log_scan), o.initial_realizations, 0);
  const auto best = static_cast<std::size_t>(
      std::max_element(scan.begin(), scan.end(),
                       [](const auto& a, const auto& b) { return a.mean < b.mean; }) -
      scan.begin());
  if (best == 0 || best + 1 == scan.size())
    throw error(exit_code::invalid_input,
                fmt::format("the largest mean of the first scan is at {} = the {} end of the "
                            "range [{}, {}]; the maximizer may lie outside: widen the range",
                            scan[best].x, best == 0 ? "lower" : "upper", o.lo, o.hi));
  const std::size_t i0 = best < 2 ? 0 : best - 2;
  const std::size_t i1 = std::min(scan.size() - 1, best + 2);
  double c = scan[best].x;
  double w = std::max(c - scan[i0].x, scan[i1].x - c);
  std::uint64_t n = o.initial_realizations;

  peak_result r;
  for (std::size_t stage = 1; stage <= o.max_stages; ++stage) {
    const double wlo = std::max(o.lo, c - w), whi = std::min(o.hi, c + w);
    if (total + n * o.window_points > o.max_total_realizations) break;
    run(spaced_points(wlo, whi, o.window_points, false), n, stage);
    r.stages = stage;
    peak_stage progress{stage, wlo, whi, o.window_points, n * o.window_points, total};
    const auto report = [&] {
      if (o.on_stage) o.on_stage(progress);
    };

    std::vector<evaluation> in;
    std::uint64_t n_in = 0;
    for (std::size_t i = 0; i < pool.size(); ++i)
      if (pool[i].x >= wlo && pool[i].x <= whi) {
        in.push_back(pool[i]);
        n_in += pool_n[i];
      }
    const double tlo = (wlo - c) / w, thi = (whi - c) / w;
    const auto quad = fit_polynomial(in, 2, c, w);
    const auto cubic = fit_polynomial(in, 3, c, w);
    const auto mq = maximize(quad, tlo, thi);
    const auto mc = maximize(cubic, tlo, thi);
    const auto quartic = fit_polynomial(in, 4, c, w);
    const auto m4 = maximize(quartic, tlo, thi);
    const double p_fit = chi2_upper_tail(cubic.chi2, cubic.dof);

    if (!mq.interior) {
      // Not concave here, or the peak lies beyond the window: move to the
      // highest fitted point and look wider.
      report();
      c = std::clamp(c + w * mq.t, o.lo, o.hi);
      w *= 1.5;
      continue;
    }
    const double xq = c + w * mq.t;
    if (!mc.interior) {  // the cubic has no interior maximum: look closer
      report();
      c = std::clamp(xq, o.lo, o.hi);
      w *= 0.7;
      continue;
    }
    // The estimate is the cubic's maximizer (bias O(w^3)) with the cubic's
    // delta-method error. Its bias is estimated by the distance to the
    // quartic's maximizer, floored at half the distance to the quadratic's
    // (the stop rule favours stages where the quartic difference is small by
    // chance; without the floor the synthetic coverage drops to ~94 %).
    const double xc = c + w * mc.t;
    r.argmax = xc;
    r.sampling_halfwidth = z95 * w * mc.t_std_error;
    r.model_bias =
        m4.interior ? std::max(std::abs(c + w * m4.t - xc), 0.5 * std::abs(xq - xc)) : w;
    const double hw = r.sampling_halfwidth + r.model_bias;
    r.argmax_lo = xc - hw;
    r.argmax_hi = xc + hw;
    r.max = cubic.value(mc.t);
    const double max_hw = z95 * cubic.value_std_error(mc.t) + std::abs(quad.value(mq.t) - r.max);
    r.max_lo = r.max - max_hw;
    r.max_hi = r.max + max_hw;
    r.window_lo = wlo;
    r.window_hi = whi;
    r.points_in_fit = in.size();
    progress.estimate = true;
    progress.argmax = r.argmax;
    progress.sampling_halfwidth = r.sampling_halfwidth;
    progress.model_bias = r.model_bias;
    report();
    const bool centred = std::abs(mc.t) <= 0.6;
    const bool model_ok = p_fit >= min_fit_p_value;
    if (hw <= o.target_halfwidth && centred && model_ok) {
      r.target_met = true;
      break;
    }
    // Next stage: shrink the window while the local model's bias (or misfit)
    // dominates, and add realizations for the sampling part.
    if (!model_ok || r.model_bias > 0.5 * hw) w *= 0.7;
    c = std::clamp(xc, o.lo, o.hi);
    const double ratio = r.sampling_halfwidth / (0.6 * o.target_halfwidth);
    if (ratio > 1.0) {
      const double want = static_cast<double>(n_in) * (ratio * ratio - 1.0) /
                          static_cast<double>(o.window_points);
      n = static_cast<std::uint64_t>(std::clamp(want, static_cast<double>(n), 8.0 * static_cast<double>(n)));
    }
  }
  r.realizations = total;
  return r;
}

}  // namespace stickslip::precision
