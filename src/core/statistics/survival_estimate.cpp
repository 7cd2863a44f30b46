// Kaplan-Meier, Greenwood and the log(-log) interval from binned counts; the
// formulas and their derivation are in survival_estimate.hpp.
#include "stickslip/survival_estimate.hpp"

#include <cmath>
#include <limits>

namespace stickslip {

std::vector<double> survival_edges(double upper, std::size_t bins) {
  std::vector<double> e(bins + 1);
  for (std::size_t j = 0; j < bins; ++j)
    e[j] = upper * static_cast<double>(j) / static_cast<double>(bins);
  e[bins] = upper;
  return e;
}

namespace {

// The exponential Greenwood interval of S with Greenwood sum v.
void log_log_interval(double s, double v, double& low, double& high) {
  if (!(s > 0.0) || !(s < 1.0)) {  // S = 0, 1 (or NaN): the interval collapses
    low = high = s;
    return;
  }
  const double sigma = std::sqrt(v) / std::abs(std::log(s));
  low = std::pow(s, std::exp(survival_z95 * sigma));
  high = std::pow(s, std::exp(-survival_z95 * sigma));
}

}  // namespace

survival_curve kaplan_meier(const survival_counts& c) {
  const std::size_t bins = c.bins();
  survival_curve k;
  k.duration = survival_edges(c.upper(), bins);
  k.survival.resize(bins + 1);
  k.greenwood.resize(bins + 1);
  k.ci95_low.resize(bins + 1);
  k.ci95_high.resize(bins + 1);
  k.at_risk.resize(bins + 1);
  // n_j from the top: the overflow is at risk at every edge.
  std::uint64_t n = c.ended().overflow() + c.censored().overflow();
  k.at_risk[bins] = n;
  for (std::size_t j = bins; j-- > 0;) {
    n += c.ended().count(j) + c.censored().count(j);
    k.at_risk[j] = n;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double s = k.at_risk[0] > 0 ? 1.0 : nan, v = 0.0;
  for (std::size_t j = 0; j <= bins; ++j) {
    if (j > 0) {
      const auto d = c.ended().count(j - 1), at = k.at_risk[j - 1];
      if (at > 0 && d > 0) {
        const double nd = static_cast<double>(at), dd = static_cast<double>(d);
        s *= (nd - dd) / nd;
        // d = n: S = 0 and V infinite; the interval is [0, 0] then.
        v += at > d ? dd / (nd * (nd - dd)) : std::numeric_limits<double>::infinity();
      }
    }
    k.survival[j] = s;
    k.greenwood[j] = k.at_risk[0] > 0 ? v : nan;
    log_log_interval(s, v, k.ci95_low[j], k.ci95_high[j]);
  }
  k.restricted_mean = 0.0;
  for (std::size_t j = 0; j < bins; ++j)
    k.restricted_mean +=
        0.5 * (k.duration[j + 1] - k.duration[j]) * (k.survival[j] + k.survival[j + 1]);
  return k;
}

}  // namespace stickslip
