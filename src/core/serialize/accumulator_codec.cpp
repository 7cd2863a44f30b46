// The codecs of the accumulators a point's statistics are made of
// (accumulators/*.hpp, uncertainty/sobol.hpp), and of the lists they share.
#include "serialize/codecs.hpp"

#include <bit>
#include <cmath>
#include <fmt/format.h>

#include "stickslip/error.hpp"

namespace stickslip::serial {

// A list of doubles: its length, then each value.
void put_values(writer& w, const std::vector<double>& v) {
  w.u64(v.size());
  for (double x : v) w.f64(x);
}
std::vector<double> get_values(reader& r, std::string_view what) {
  std::vector<double> v(r.count(what, 8));
  for (double& x : v) x = r.f64(what);
  return v;
}

std::uint64_t sparse_index(std::uint64_t i, std::uint64_t size, std::uint64_t k,
                           std::uint64_t& last, std::string_view what, std::string_view noun) {
  if (i >= size || (k > 0 && i <= last))
    throw corrupt(fmt::format("{}: {} {} out of order or range", what, noun, i));
  last = i;
  return i;
}

void put_mean_m2(writer& w, const mean_variance& m) {
  w.f64(m.count() ? m.mean() : 0.0);
  w.f64(m.sum_sq_dev());
}
void put(writer& w, const mean_variance& m) {
  w.u64(m.count());
  put_mean_m2(w, m);
}
mean_variance get_mean_variance(reader& r) {
  const auto n = r.u64("accumulator count");
  const double mean = r.f64("accumulator mean");
  const double m2 = r.f64("accumulator M2");
  // put() writes an empty accumulator as (0, +0.0, +0.0): anything else with a
  // zero count would be read as an accumulator that writes other bytes.
  if (n == 0 && (std::bit_cast<std::uint64_t>(mean) != 0 || std::bit_cast<std::uint64_t>(m2) != 0))
    throw corrupt(fmt::format("empty accumulator with mean {} and M2 {}", mean, m2));
  if (m2 < 0) throw corrupt(fmt::format("accumulator M2 {} is negative", m2));
  return mean_variance::from_raw(n, mean, m2);
}

void put(writer& w, const histogram& h) {
  w.f64(h.lo());
  w.f64(h.hi());
  w.u64(h.bins());
  for (auto c : h.counts()) w.u64(c);
  w.u64(h.underflow());
  w.u64(h.overflow());
}
histogram get_histogram(reader& r) {
  const double lo = r.f64("histogram lower edge");
  const double hi = r.f64("histogram upper edge");
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi))
    throw corrupt(fmt::format("histogram range [{}, {}] is not a finite interval", lo, hi));
  const auto bins = r.count("histogram bins", 8);
  if (bins < 1) throw corrupt("histogram with zero bins");
  std::vector<std::uint64_t> counts(bins);
  for (auto& c : counts) c = r.u64("histogram count");
  const auto under = r.u64("histogram underflow");
  const auto over = r.u64("histogram overflow");
  histogram h(lo, hi, bins);
  h.set_raw(std::move(counts), under, over);
  return h;
}

// The pick-freeze moments (uncertainty/sobol.hpp): inputs, rows, the means
// of the row vector z and its co-moments (upper triangle). Empty: zeros.
void put(writer& w, const sobol_moments& m) {
  w.u64(m.inputs());
  w.u64(m.rows());
  put_values(w, m.means());
  put_values(w, m.comoments());
}
sobol_moments get_sobol_moments(reader& r) {
  const auto inputs = r.u64("sensitivity inputs");
  const auto rows = r.u64("sensitivity rows");
  std::vector<double> means = get_values(r, "sensitivity means");
  std::vector<double> comoments = get_values(r, "sensitivity co-moments");
  if (inputs == 0 && rows == 0 && means.empty() && comoments.empty()) return {};
  if (inputs > 1000) throw corrupt(fmt::format("{} sensitivity inputs", inputs));
  try {  // from_state checks the sizes against the inputs
    return sobol_moments::from_state(static_cast<std::size_t>(inputs), rows, std::move(means),
                                     std::move(comoments));
  } catch (const error& e) {
    throw corrupt(e.what());
  }
}

// Survival counts (accumulators/survival_counts.hpp): whether selected;
// then the upper end, the bins, the overflow of ended and of censored
// episodes, and sparsely (a block fills few of the bins) the number of bins
// with a count, then (bin, ended, censored) for each, in bin order.
void put(writer& w, const survival_counts& c) {
  w.u8(c.selected() ? 1 : 0);
  if (!c.selected()) return;
  w.f64(c.upper());
  w.u64(c.bins());
  w.u64(c.ended().overflow());
  w.u64(c.censored().overflow());
  std::uint64_t filled = 0;
  auto counted = [&](std::size_t j) { return c.ended().count(j) != 0 || c.censored().count(j) != 0; };
  for (std::size_t j = 0; j < c.bins(); ++j) filled += counted(j) ? 1 : 0;
  w.u64(filled);
  for (std::size_t j = 0; j < c.bins(); ++j)
    if (counted(j)) {
      w.u64(j);
      w.u64(c.ended().count(j));
      w.u64(c.censored().count(j));
    }
}
survival_counts get_survival_counts(reader& r, std::string_view name) {
  const std::string what = fmt::format("{} survival counts", name);
  if (!r.boolean(what)) return {};
  const double upper = r.f64(what);
  if (!(upper > 0) || !std::isfinite(upper))
    throw corrupt(fmt::format("{}: upper end {} is not finite and > 0", what, upper));
  const auto bins = r.u64(what);
  if (bins < 1 || bins > max_histogram_bins)
    throw corrupt(fmt::format("{}: {} bins", what, bins));
  const auto ended_over = r.u64(what), censored_over = r.u64(what);
  std::vector<std::uint64_t> ended(bins, 0), censored(bins, 0);
  const auto filled = r.count(what, 24);
  std::uint64_t last = 0;
  for (std::size_t k = 0; k < filled; ++k) {
    const auto j = sparse_index(r.u64(what), bins, k, last, what, "bin");
    ended[j] = r.u64(what);
    censored[j] = r.u64(what);
    if (ended[j] == 0 && censored[j] == 0)  // put() lists only the bins with a count
      throw corrupt(fmt::format("{}: bin {} listed without a count", what, j));
  }
  histogram e(0.0, upper, bins), c(0.0, upper, bins);
  e.set_raw(std::move(ended), 0, ended_over);
  c.set_raw(std::move(censored), 0, censored_over);
  survival_counts out(upper, bins);
  out.set_raw(std::move(e), std::move(c));
  return out;
}

}  // namespace stickslip::serial
