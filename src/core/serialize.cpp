#include "stickslip/serialize.hpp"
#include "stickslip/fast_math.hpp"
#include "stickslip/version.hpp"

#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <optional>
#include <fmt/format.h>

#include "stickslip/error.hpp"
#include "stickslip/statistics_schema.hpp"

namespace stickslip {

error detail::corrupt(std::string_view what) {
  return error(exit_code::io_failure, fmt::format("corrupt serialized data: {}", what));
}

namespace {

constexpr std::string_view spec_tag = "SSPC", unit_tag = "SSWU", result_tag = "SSBR",
                           prefix_tag = "SSMP";

using detail::corrupt;
using writer = detail::byte_writer;
using reader = detail::byte_reader;

// ---- pieces ----
// The fields as given (not resolved), in the order of scalar_parameters
// (the paper's seven, then the family's c, mu_s, mu_k; 0 = mu), and the belt's
// levels, rates and generator, each with its length (the layout id covers
// both name lists).
void put_values(writer& w, const std::vector<double>& v) {
  w.u64(v.size());
  for (double x : v) w.f64(x);
}
std::vector<double> get_values(reader& r, std::string_view what) {
  std::vector<double> v(r.count(what, 8));
  for (double& x : v) x = r.f64(what);
  return v;
}
void put(writer& w, const model_parameters& p) {
  for (const auto& row : scalar_parameters) w.f64(p.*row.field);
  put_values(w, p.belt_levels);
  put_values(w, p.belt_rates);
  put_values(w, p.belt_generator);
}
model_parameters get_parameters(reader& r) {
  model_parameters p;
  for (const auto& row : scalar_parameters) p.*row.field = r.f64("model parameter");
  p.belt_levels = get_values(r, "belt levels");
  p.belt_rates = get_values(r, "belt rates");
  p.belt_generator = get_values(r, "belt generator");
  return p;
}

void put(writer& w, const event_counts& e) {
  w.u64(e.belt_switches);
  w.u64(e.stick_onsets);
  w.u64(e.stick_breaks);
  w.u64(e.slip_reversals);
  w.f64(e.switch_time_sum);
}
event_counts get_counts(reader& r) {
  event_counts e;
  e.belt_switches = r.u64("event counts");
  e.stick_onsets = r.u64("event counts");
  e.stick_breaks = r.u64("event counts");
  e.slip_reversals = r.u64("event counts");
  e.switch_time_sum = r.f64("switch time sum");
  return e;
}

void put(writer& w, const mean_variance& m) {
  w.u64(m.count());
  w.f64(m.count() ? m.mean() : 0.0);  // mean() is NaN when empty; the stored mean is 0
  w.f64(m.sum_sq_dev());
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

// score_moments and causal_score_moments (accumulators/score_moments.hpp):
// the count, then the five sums in their fixed order; 48 bytes.
constexpr std::size_t five_sums_bytes = 8 + 5 * 8;
template <class Moments>
void put(writer& w, const five_sums<Moments>& m) {
  w.u64(m.count());
  for (int i = 0; i < 5; ++i) w.f64(m.sum(i));
}
template <class Moments>
Moments get_five_sums(reader& r, std::string_view what) {
  const auto count = r.u64(what);
  double sums[5];
  for (double& x : sums) x = r.f64(what);
  return Moments::from_raw(count, sums);
}

// The accumulators in schema order (statistics_schema.cpp): every quantity's
// moments, every binned quantity's histogram, the realization count, every
// counter; then the convergence trace.
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
    const auto j = r.u64(what);
    if (j >= bins || (k > 0 && j <= last))
      throw corrupt(fmt::format("{}: bin {} out of order or range", what, j));
    last = j;
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

// Quantile sketches (accumulators/quantile_sketch.hpp): each store trimmed,
// as its range of bins (0: empty, nothing more), its first key, and its
// counts, densely (a count per bin of the range) or, when fewer than half
// the bins have a count (a block's few samples), sparsely (the number of
// bins with a count, then (offset, count) of each); counts and offsets as
// unsigned LEB128 varints (a merged point's counts are mostly one or two
// bytes), minimal, so the bytes are canonical, as is the form, a function
// of the counts. The zero bin sits between the negative and positive stores.
void put_varint(writer& w, std::uint32_t v) {
  while (v >= 0x80) {
    w.u8(static_cast<std::uint8_t>(v | 0x80));
    v >>= 7;
  }
  w.u8(static_cast<std::uint8_t>(v));
}
std::uint32_t get_varint(reader& r, std::string_view what) {
  std::uint64_t v = 0;
  for (int shift = 0; shift < 35; shift += 7) {
    const auto b = r.u8(what);
    v |= static_cast<std::uint64_t>(b & 0x7f) << shift;
    if (!(b & 0x80)) {
      if ((b == 0 && shift > 0) || v > 0xffffffffu)
        throw corrupt(fmt::format("{}: a varint that is not minimal or exceeds 32 bits", what));
      return static_cast<std::uint32_t>(v);
    }
  }
  throw corrupt(fmt::format("{}: a varint longer than 5 bytes", what));
}
void put(writer& w, const quantile_sketch::store& st) {
  w.u64(st.counts.size());
  if (st.counts.empty()) return;
  w.u32(st.first);
  const auto filled = static_cast<std::uint64_t>(
      std::count_if(st.counts.begin(), st.counts.end(), [](std::uint32_t c) { return c != 0; }));
  const bool sparse = 2 * filled < st.counts.size();
  w.u8(sparse ? 1 : 0);
  if (!sparse) {
    for (auto c : st.counts) put_varint(w, c);
    return;
  }
  w.u64(filled);
  for (std::size_t i = 0; i < st.counts.size(); ++i)
    if (st.counts[i] != 0) {
      put_varint(w, static_cast<std::uint32_t>(i));
      put_varint(w, st.counts[i]);
    }
}
quantile_sketch::store get_sketch_store(reader& r, std::string_view what,
                                        std::uint64_t& bin_budget) {
  quantile_sketch::store st;
  const auto range = r.u64(what);
  if (range == 0) return st;
  if (range > bin_budget)
    throw corrupt(fmt::format("{}: {} bins exceed what the record's size allows", what, range));
  bin_budget -= range;
  st.first = r.u32(what);
  if (st.first < quantile_sketch::min_key() || range > quantile_sketch::max_key() ||
      st.first > quantile_sketch::max_key() - (range - 1))
    throw corrupt(fmt::format("{}: {} bins from {} outside {} .. {}", what, range, st.first,
                              quantile_sketch::min_key(), quantile_sketch::max_key()));
  const bool sparse = r.boolean(what);
  std::uint64_t filled = 0;
  if (!sparse) {
    if (range > r.remaining())  // a varint is at least a byte
      throw corrupt(fmt::format("{}: {} bins exceed the bytes left", what, range));
    st.counts.resize(range);
    for (auto& c : st.counts) filled += (c = get_varint(r, what)) != 0;
  } else {
    filled = r.u64(what);
    if (filled == 0 || filled > r.remaining() / 2)
      throw corrupt(fmt::format("{}: {} bins with a count", what, filled));
    st.counts.assign(range, 0);
    std::uint64_t last = 0;
    for (std::uint64_t k = 0; k < filled; ++k) {
      const auto i = get_varint(r, what);
      if (i >= range || (k > 0 && i <= last))
        throw corrupt(fmt::format("{}: bin {} out of order or range", what, i));
      last = i;
      if ((st.counts[i] = get_varint(r, what)) == 0)
        throw corrupt(fmt::format("{}: bin {} listed without a count", what, i));
    }
  }
  if (st.counts.front() == 0 || st.counts.back() == 0)
    throw corrupt(fmt::format("{}: a store that is not trimmed", what));
  if (sparse != (2 * filled < range))
    throw corrupt(fmt::format("{}: {} bins of {} written in the other form", what, filled, range));
  return st;
}
void put(writer& w, const quantile_sketch& q) {
  put(w, q.negative());
  w.u64(q.zero());
  put(w, q.positive());
}
quantile_sketch get_quantile_sketch(reader& r, std::string_view what, std::uint64_t& bin_budget) {
  auto negative = get_sketch_store(r, what, bin_budget);
  const auto zero = r.u64(what);
  auto positive = get_sketch_store(r, what, bin_budget);
  quantile_sketch q;
  q.set_raw(std::move(negative), zero, std::move(positive));
  return q;
}

// The observe-time statistics (accumulators/time_statistics.hpp): the times
// (none: not selected), the level count, the realizations, then per time
// the sticking count, the four moments, the two sketches and the level
// counts. Every count must match the realizations.
void put(writer& w, const time_statistics& t) {
  put_values(w, t.times());
  if (!t.selected()) return;
  w.u64(t.levels());
  w.u64(t.realizations());
  for (std::size_t j = 0; j < t.times().size(); ++j) {
    const auto& a = t.at(j);
    w.u64(a.sticking);
    // Every moment counts every realization: its mean and M2 only.
    for (const auto* m : {&a.position, &a.velocity, &a.relative_velocity, &a.energy}) {
      w.f64(m->count() ? m->mean() : 0.0);
      w.f64(m->sum_sq_dev());
    }
    put(w, a.position_quantiles);
    put(w, a.velocity_quantiles);
    for (std::size_t l = 0; l < t.levels(); ++l) w.u64(t.level_count(j, l));
  }
}
time_statistics get_time_statistics(reader& r) {
  constexpr std::string_view what = "observe-time statistics";
  auto times = get_values(r, what);
  if (times.empty()) return {};
  if (times.size() > max_observe_times)
    throw corrupt(fmt::format("{}: {} times", what, times.size()));
  for (std::size_t j = 0; j < times.size(); ++j)
    if (!(times[j] >= 0.0) || std::signbit(times[j]) || !std::isfinite(times[j]) ||
        (j > 0 && !(times[j] > times[j - 1])))
      throw corrupt(fmt::format("{}: time {} out of order or range", what, times[j]));
  const auto levels = r.u64(what);
  if (levels < 1 || levels > 4096) throw corrupt(fmt::format("{}: {} belt levels", what, levels));
  // Every level count is 8 bytes of the record: nothing is allocated for
  // more than the bytes left can hold.
  if (times.size() * levels > r.remaining() / 8)
    throw corrupt(fmt::format("{}: {} times x {} levels exceed the bytes left", what,
                              times.size(), levels));
  // The sketches' bins: at most 16 per byte of the record (a sparse store of
  // real samples holds a few per byte), plus 2^20, so a crafted record
  // cannot make its decoder allocate more than a small multiple of itself.
  std::uint64_t bin_budget = (std::uint64_t{1} << 20) + 16 * std::uint64_t{r.remaining()};
  const auto n = r.u64(what);
  std::vector<time_point_statistics> at(times.size());
  std::vector<std::uint64_t> level_counts(times.size() * levels);
  for (std::size_t j = 0; j < times.size(); ++j) {
    auto& a = at[j];
    a.sticking = r.u64(what);
    for (auto* m : {&a.position, &a.velocity, &a.relative_velocity, &a.energy}) {
      const double mean = r.f64(what), m2 = r.f64(what);
      if (n == 0 && (std::bit_cast<std::uint64_t>(mean) != 0 || std::bit_cast<std::uint64_t>(m2) != 0))
        throw corrupt(fmt::format("{}: empty moments with mean {} and M2 {}", what, mean, m2));
      if (!(m2 >= 0.0)) throw corrupt(fmt::format("{}: M2 {} is negative", what, m2));
      *m = mean_variance::from_raw(n, mean, m2);
    }
    a.position_quantiles = get_quantile_sketch(r, what, bin_budget);
    a.velocity_quantiles = get_quantile_sketch(r, what, bin_budget);
    std::uint64_t at_levels = 0;
    for (std::size_t l = 0; l < levels; ++l) at_levels += level_counts[j * levels + l] = r.u64(what);
    for (auto m : {a.position.count(), a.velocity.count(), a.relative_velocity.count(),
                   a.energy.count(), a.position_quantiles.count(), a.velocity_quantiles.count(),
                   at_levels})
      if (m != n)
        throw corrupt(fmt::format("{}: a count of {} at time {} of {} realizations", what, m,
                                  times[j], n));
    if (a.sticking > n)
      throw corrupt(fmt::format("{}: {} sticking of {} realizations", what, a.sticking, n));
  }
  time_statistics t(std::move(times), static_cast<std::size_t>(levels));
  t.set_raw(n, std::move(at), std::move(level_counts));
  return t;
}

void put(writer& w, const point_statistics& s) {
  for (const auto& q : quantities()) put(w, s.*q.moments);
  for (const auto& q : quantities())
    if (q.density) put(w, s.*q.density);
  w.u64(s.realizations);
  w.u8(s.family_statistics ? 1 : 0);
  w.u8(s.means_only ? 1 : 0);
  for (const auto& c : counters()) w.u64(c.value(s));
  for (const auto& q : quantities())
    if (q.score) put(w, s.*q.score);
  w.f64(s.expected_switches);
  put(w, s.stick_fraction_causal_score);
  for (const auto& q : quantities())
    if (q.rate_score)
      for (const auto& m : s.*q.rate_score) put(w, m);
  w.f64(s.belt_rates[0]);
  w.f64(s.belt_rates[1]);
  for (const auto& q : quantities())
    if (q.generator_score) {
      w.u64((s.*q.generator_score).size());
      for (const auto& m : s.*q.generator_score) put(w, m);
    }
  w.u64(s.generator.size());
  for (double q : s.generator) w.f64(q);
  w.u8(s.stationary_start ? 1 : 0);
  for (const auto& l : level_quantities()) {
    w.u64((s.*l.moments).size());
    for (const auto& m : s.*l.moments) put(w, m);
  }
  // Joint histograms sparsely (a block's sticks fill few of the (bins + 2)^2
  // cells; the journal buffers these bytes): the cell count, the number of
  // non-zero cells, then (index, count) for each, in index order.
  for (const auto& j : joint_histograms()) {
    const auto& cells = (s.*j.counts).cells();
    w.u64(cells.size());
    std::uint64_t nonzero = 0;
    for (auto c : cells) nonzero += c != 0;
    w.u64(nonzero);
    for (std::size_t i = 0; i < cells.size(); ++i)
      if (cells[i] != 0) {
        w.u64(i);
        w.u64(cells[i]);
      }
  }
  for (const auto& l : survival_laws()) put(w, s.*l.counts);
  put(w, s.observed);
  w.u64(s.convergence.size());
  for (const auto& c : s.convergence) {
    w.u64(c.realizations);
    w.f64(c.R_mean);
    w.f64(c.R_ci95_half_width);
    w.f64(c.stick_duration_mean);
    w.f64(c.stick_duration_ci95_half_width);
  }
  put(w, s.sensitivity);
}
point_statistics get_statistics(reader& r) {
  point_statistics s;
  for (const auto& q : quantities()) s.*q.moments = get_mean_variance(r);
  for (const auto& q : quantities())
    if (q.density) s.*q.density = get_histogram(r);
  s.realizations = r.u64("realizations");
  s.family_statistics = r.boolean("family statistics flag");
  s.means_only = r.boolean("means-only flag");
  for (const auto& c : counters()) c.of(s) = r.u64(c.name);
  for (const auto& q : quantities())
    if (q.score) s.*q.score = get_five_sums<score_moments>(r, "score moments");
  s.expected_switches = r.f64("expected switches");
  s.stick_fraction_causal_score = get_five_sums<causal_score_moments>(r, "causal score moments");
  for (const auto& q : quantities())
    if (q.rate_score)
      for (auto& m : s.*q.rate_score) m = get_five_sums<score_moments>(r, "rate score moments");
  s.belt_rates[0] = r.f64("belt rate r1");
  s.belt_rates[1] = r.f64("belt rate r2");
  for (const auto& q : quantities())
    if (q.generator_score) {
      auto& moments = s.*q.generator_score;
      moments.resize(r.count("generator score moments", five_sums_bytes));
      for (auto& m : moments) m = get_five_sums<score_moments>(r, "generator score moments");
    }
  s.generator.resize(r.count("belt generator", 8));
  for (double& q : s.generator) q = r.f64("belt generator");
  if (const auto n = static_cast<std::size_t>(std::lround(std::sqrt(double(s.generator.size()))));
      n * n != s.generator.size() || (!s.generator.empty() && n < 2))
    throw corrupt(fmt::format("a belt generator of {} entries is not an n x n matrix, n >= 2",
                              s.generator.size()));
  s.stationary_start = r.boolean("stationary start flag");
  if (!s.generator.empty() && s.stationary_start)
    s.generator_start_terms = stationary_score_terms(s.generator);
  for (const auto& l : level_quantities()) {
    auto& moments = s.*l.moments;
    moments.resize(r.count(l.name, 24));
    for (auto& m : moments) m = get_mean_variance(r);
  }
  // A joint histogram has the binnings of its two quantities' histograms;
  // 0 cells: not allocated (statistics without the family's).
  for (const auto& j : joint_histograms()) {
    const auto n = r.u64(j.name);
    if (n == 0) {
      if (r.u64(j.name) != 0) throw corrupt(fmt::format("{}: cells listed without any", j.name));
      s.*j.counts = histogram2d{};
      continue;
    }
    histogram2d h(s.*quantity_table[j.x].density, s.*quantity_table[j.y].density);
    if (n != h.cells().size())
      throw corrupt(fmt::format("{}: {} cells, its binnings have {}", j.name, n, h.cells().size()));
    std::vector<std::uint64_t> cells(n, 0);
    const auto nonzero = r.count(j.name, 16);
    std::uint64_t last = 0;
    for (std::size_t k = 0; k < nonzero; ++k) {
      const auto i = r.u64(j.name);
      if (i >= n || (k > 0 && i <= last))
        throw corrupt(fmt::format("{}: cell index {} out of order or range", j.name, i));
      last = i;
      const auto count = r.u64(j.name);
      if (count == 0)  // put() lists only the non-zero cells
        throw corrupt(fmt::format("{}: cell {} listed with a zero count", j.name, i));
      cells[static_cast<std::size_t>(i)] = count;
    }
    h.set_raw(std::move(cells));
    s.*j.counts = std::move(h);
  }
  for (const auto& l : survival_laws()) s.*l.counts = get_survival_counts(r, l.name);
  s.observed = get_time_statistics(r);
  const auto n = r.count("convergence trace", 40);
  s.convergence.resize(n);
  for (auto& c : s.convergence) {
    c.realizations = r.u64("convergence point");
    c.R_mean = r.f64("convergence point");
    c.R_ci95_half_width = r.f64("convergence point");
    c.stick_duration_mean = r.f64("convergence point");
    c.stick_duration_ci95_half_width = r.f64("convergence point");
  }
  s.sensitivity = get_sobol_moments(r);
  return s;
}

constexpr std::size_t record_bytes = 8 + 8 + 8 + 1 + 4 + 4 + 8 + 8 + 8 + 1 + 8 + 8 + 8 + 8 + 40 + 8;

void put(writer& w, const realization_record& x) {
  w.u64(x.realization);
  w.f64(x.x0);
  w.f64(x.xdot0);
  w.u8(static_cast<std::uint8_t>(static_cast<std::int8_t>(x.belt_start)));
  w.u32(x.sticks);
  w.u32(x.slips);
  w.f64(x.stick_fraction);
  w.f64(x.first_stick_start);
  w.f64(x.first_stick_duration);
  w.u8(x.first_stick_censored ? 1 : 0);
  w.f64(x.friction_power);
  w.f64(x.damping_power);
  w.f64(x.stick_switch_moment);
  w.f64(x.stick_time_moment);
  put(w, x.events);
  put_values(w, x.drawn_values);
}
realization_record get_record(reader& r) {
  realization_record x;
  x.realization = r.u64("record");
  x.x0 = r.f64("record");
  x.xdot0 = r.f64("record");
  x.belt_start = static_cast<std::int8_t>(r.u8("record"));
  // +1 / -1 on a two-level belt, the level number 1..n on more levels
  // (model_realization.hpp, recorded_belt_start).
  if (x.belt_start == 0 || x.belt_start < -1)
    throw corrupt(fmt::format("record belt start {} is not +1, -1 or a level number",
                              x.belt_start));
  x.sticks = r.u32("record");
  x.slips = r.u32("record");
  x.stick_fraction = r.f64("record");
  x.first_stick_start = r.f64("record");
  x.first_stick_duration = r.f64("record");
  x.first_stick_censored = r.boolean("record censoring flag");
  x.friction_power = r.f64("record");
  x.damping_power = r.f64("record");
  x.stick_switch_moment = r.f64("record");
  x.stick_time_moment = r.f64("record");
  x.events = get_counts(r);
  x.drawn_values = get_values(r, "record drawn values");
  return x;
}

void put(writer& w, const work_unit& u) {
  w.u64(u.point);
  w.u64(u.block);
}
work_unit get_unit(reader& r) {
  work_unit u;
  u.point = static_cast<std::size_t>(r.u64("unit point"));
  u.block = r.u64("unit block");
  return u;
}

}  // namespace

std::uint64_t layout_id() noexcept {
  static const std::uint64_t id = [] {
    std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a 64
    const auto byte = [&h](unsigned char c) {
      h ^= c;
      h *= 0x100000001b3ULL;
    };
    const auto schema = statistics_schema_id();
    for (int i = 0; i < 8; ++i) byte(static_cast<unsigned char>(schema >> (8 * i)));
    for (const char* name : recorded_parameter_names) {
      for (const char* c = name; *c; ++c) byte(static_cast<unsigned char>(*c));
      byte(0);
    }
    for (const char* c = "belt_levels|belt_rates|belt_generator"; *c; ++c)
      byte(static_cast<unsigned char>(*c));
    return h;
  }();
  return id;
}

// ---- sweep spec ----
bytes serialize(const sweep_spec& s) {
  writer w;
  w.header(spec_tag);
  put(w, s.base);
  w.f64(s.initial.position_min);
  w.f64(s.initial.position_max);
  w.f64(s.initial.velocity_min);
  w.f64(s.initial.velocity_max);
  w.i64(s.initial.belt_start);
  w.u64(s.axes.size());
  for (const auto& ax : s.axes) {
    w.str(ax.name);
    w.u64(ax.values.size());
    for (double v : ax.values) w.f64(v);
  }
  w.u64(s.realizations);
  w.u64(s.seed);
  w.u64(s.block_size);
  w.u64(s.histograms.bins);
  w.f64(s.histograms.stick_duration_max);
  w.f64(s.histograms.slip_duration_max);
  w.i64(s.max_events);
  w.u8(s.keep_records ? 1 : 0);
  w.u8(static_cast<std::uint8_t>(s.engine));
  w.u8(s.common_random_numbers ? 1 : 0);
  w.str(s.target_statistic);
  w.f64(s.target_halfwidth);
  w.u64(s.min_realizations);
  w.u8(s.family_statistics ? 1 : 0);
  w.u8(s.means_only ? 1 : 0);
  w.u64(s.uncertain.size());
  for (const auto& u : s.uncertain) {
    w.str(u.symbol);
    w.u8(static_cast<std::uint8_t>(u.law.family));
    put_values(w, u.law.arguments);
  }
  w.str(s.sensitivity_statistic);
  w.u8(to_bits(s.statistics));
  w.u64(s.statistics.rows.size());
  for (const auto& row : s.statistics.rows) w.str(row);
  w.u64(s.survival.bins);
  w.f64(s.survival.stick_duration_max);
  w.f64(s.survival.slip_duration_max);
  put_values(w, s.observe_times);
  // The burn-in only when there is one: a spec without it keeps the bytes
  // (and the journal identity) it had before the field.
  if (s.burn_in != 0.0) w.f64(s.burn_in);
  return w.take();
}

sweep_spec deserialize_sweep_spec(std::string_view in) {
  reader r(in);
  r.header(spec_tag);
  sweep_spec s;
  s.base = get_parameters(r);
  s.initial.position_min = r.f64("initial law");
  s.initial.position_max = r.f64("initial law");
  s.initial.velocity_min = r.f64("initial law");
  s.initial.velocity_max = r.f64("initial law");
  const auto belt = r.i64("initial belt direction");
  if (belt < -1 || belt > 1) throw corrupt(fmt::format("initial belt direction {}", belt));
  s.initial.belt_start = static_cast<int>(belt);
  s.axes.resize(r.count("grid axes", 16));
  for (auto& ax : s.axes) {
    ax.name = r.str("axis name");
    ax.values.resize(r.count("axis values", 8));
    for (double& v : ax.values) v = r.f64("axis value");
  }
  s.realizations = r.u64("realizations");
  s.seed = r.u64("seed");
  s.block_size = r.u64("block size");
  s.histograms.bins = static_cast<std::size_t>(r.u64("bins"));
  s.histograms.stick_duration_max = r.f64("stick_duration_max");
  s.histograms.slip_duration_max = r.f64("slip_duration_max");
  s.max_events = r.i64("max_events");
  s.keep_records = r.boolean("keep_records");
  const auto engine = r.u8("engine");
  if (engine > static_cast<std::uint8_t>(sweep_engine::reference))
    throw corrupt(fmt::format("unknown engine {}", engine));
  s.engine = static_cast<sweep_engine>(engine);
  s.common_random_numbers = r.boolean("common_random_numbers");
  s.target_statistic = r.str("target statistic");
  s.target_halfwidth = r.f64("target half-width");
  s.min_realizations = r.u64("min realizations");
  s.family_statistics = r.boolean("family_statistics");
  s.means_only = r.boolean("means_only");
  s.uncertain.resize(r.count("uncertain parameters", 17));
  for (auto& u : s.uncertain) {
    u.symbol = r.str("uncertain parameter");
    const auto family = r.u8("law family");
    if (family > static_cast<std::uint8_t>(law_family::beta))
      throw corrupt(fmt::format("unknown law family {}", family));
    u.law.family = static_cast<law_family>(family);
    u.law.arguments = get_values(r, "law arguments");
    // The canonical text parses back to the same law only when the
    // arguments are the family's and meet its constraints.
    bool valid = false;
    try {
      valid = parse_law(to_string(u.law), u.symbol) == u.law;
    } catch (const error&) {
    }
    if (!valid)
      throw corrupt(fmt::format("the law of {} is not a valid {} law", u.symbol,
                                to_string(u.law.family)));
  }
  s.sensitivity_statistic = r.str("sensitivity statistic");
  if (const auto bits = r.u8("statistics selection"); !from_bits(bits, s.statistics))
    throw corrupt(fmt::format("statistics selection {:#04x} names unknown groups", bits));
  s.statistics.rows.resize(r.count("statistics rows", 8));
  for (auto& row : s.statistics.rows) row = r.str("statistics row");
  if (!canonical_rows(s.statistics))
    throw corrupt(fmt::format("statistics selection '{}' is not canonical", to_string(s.statistics)));
  s.survival.bins = static_cast<std::size_t>(r.u64("survival bins"));
  s.survival.stick_duration_max = r.f64("survival stick_duration_max");
  s.survival.slip_duration_max = r.f64("survival slip_duration_max");
  s.observe_times = get_values(r, "observe times");
  if (r.remaining() > 0) {
    s.burn_in = r.f64("burn-in");
    if (!(s.burn_in > 0.0)) throw corrupt(fmt::format("burn-in {}", s.burn_in));
  }
  r.finish("sweep spec");
  return s;
}

// ---- work unit ----
bytes serialize(const work_unit& u) {
  writer w;
  w.header(unit_tag);
  put(w, u);
  return w.take();
}

work_unit deserialize_work_unit(std::string_view in) {
  reader r(in);
  r.header(unit_tag);
  auto u = get_unit(r);
  r.finish("work unit");
  return u;
}

// ---- block result ----
bytes serialize(const work_unit& u, const block_result& b) {
  writer w;
  w.header(result_tag);
  put(w, u);
  put(w, b.stats);
  w.u64(b.records.size());
  for (const auto& x : b.records) put(w, x);
  return w.take();
}

std::pair<work_unit, block_result> deserialize_unit_result(std::string_view in) {
  reader r(in);
  r.header(result_tag);
  std::pair<work_unit, block_result> out;
  out.first = get_unit(r);
  out.second.stats = get_statistics(r);
  out.second.records.resize(r.count("records", record_bytes));
  for (auto& x : out.second.records) x = get_record(r);
  r.finish("block result");
  return out;
}

namespace {
// What makes `got` not fit the point whose fresh statistics are `fresh`:
// another histogram binning, or another number of belt levels.
std::optional<std::string> shape_difference(const point_statistics& got,
                                            const point_statistics& fresh) {
  for (const auto& q : quantities())
    if (q.density && !(got.*q.density).same_binning(fresh.*q.density))
      return fmt::format("histogram binning of {} differs", q.name);
  for (const auto& l : survival_laws())
    if (!(got.*l.counts).same_binning(fresh.*l.counts))
      return fmt::format("{} survival grid differs (another statistics selection or survival "
                         "grid)", l.name);
  if (got.observed.times() != fresh.observed.times() ||
      got.observed.levels() != fresh.observed.levels())
    return std::string("observe times differ");
  for (const auto& l : level_quantities())
    if ((got.*l.moments).size() != (fresh.*l.moments).size())
      return fmt::format("{} values of {}, the point has {} belt levels", (got.*l.moments).size(),
                         l.name, (fresh.*l.moments).size());
  // Held only with the family statistics (point_statistics' constructor).
  for (const auto& j : joint_histograms())
    if ((got.*j.counts).cells().size() != (fresh.*j.counts).cells().size())
      return fmt::format("{}: {} cells, the point has {}", j.name, (got.*j.counts).cells().size(),
                         (fresh.*j.counts).cells().size());
  return std::nullopt;
}
}  // namespace

// ---- merged prefix ----
bytes serialize_merged_prefix(std::size_t point, std::uint64_t blocks,
                              const point_statistics& stats) {
  writer w;
  w.header(prefix_tag);
  w.u64(point);
  w.u64(blocks);
  put(w, stats);
  return w.take();
}

bytes serialize(const merged_prefix& p) { return serialize_merged_prefix(p.point, p.blocks, p.stats); }

merged_prefix deserialize_merged_prefix(std::string_view in) {
  reader r(in);
  r.header(prefix_tag);
  merged_prefix p;
  p.point = static_cast<std::size_t>(r.u64("prefix point"));
  p.blocks = r.u64("prefix blocks");
  p.stats = get_statistics(r);
  r.finish("merged prefix");
  return p;
}

bool is_merged_prefix(std::string_view in) noexcept { return in.starts_with(prefix_tag); }

void check_prefix_shape(const sweep_spec& s, const merged_prefix& p) {
  auto bad = [&](const std::string& what) {
    return error(exit_code::io_failure,
                 fmt::format("merged blocks of point {} do not fit this sweep: {}", p.point, what));
  };
  if (p.point >= point_count(s)) throw bad(fmt::format("only {} grid points", point_count(s)));
  const auto nb = blocks_per_point(s);
  if (p.blocks == 0 || p.blocks > nb)
    throw bad(fmt::format("{} blocks, the point has {}", p.blocks, nb));
  const std::uint64_t expected = std::min(s.realizations, p.blocks * s.block_size);
  if (p.stats.realizations != expected)
    throw bad(fmt::format("{} realizations, expected {}", p.stats.realizations, expected));
  point_statistics fresh(histogram_parameters(s, p.point), s.histograms, s.family_statistics,
                         s.initial.belt_start == 0, s.means_only);
  select_statistics(fresh, s);
  if (auto why = shape_difference(p.stats, fresh)) throw bad(*why);
  if (p.stats.family_statistics != fresh.family_statistics)
    throw bad("another selection of statistics");
  if (s.keep_records) throw bad("a sweep that keeps raw records journals every block");
}

void check_block_shape(const sweep_spec& s, const work_unit& u, const block_result& b) {
  auto bad = [&](const std::string& what) {
    return error(exit_code::io_failure,
                 fmt::format("block result for point {} block {} does not fit this sweep: {}",
                             u.point, u.block, what));
  };
  if (u.point >= point_count(s)) throw bad(fmt::format("only {} grid points", point_count(s)));
  if (u.block >= blocks_per_point(s))
    throw bad(fmt::format("only {} blocks per point", blocks_per_point(s)));
  const std::uint64_t first = u.block * s.block_size;
  const std::uint64_t expected = std::min(s.realizations, first + s.block_size) - first;
  if (b.stats.realizations != expected)
    throw bad(fmt::format("{} realizations, expected {}", b.stats.realizations, expected));
  point_statistics fresh(histogram_parameters(s, u.point), s.histograms, s.family_statistics,
                         s.initial.belt_start == 0, s.means_only);
  select_statistics(fresh, s);
  if (auto why = shape_difference(b.stats, fresh)) throw bad(*why);
  if (!b.stats.convergence.empty()) throw bad("a block carries no convergence trace");
  if (b.records.size() != (s.keep_records ? expected : 0))
    throw bad(fmt::format("{} raw records", b.records.size()));
  for (std::size_t i = 0; i < b.records.size(); ++i) {
    if (b.records[i].realization != first + i) throw bad("raw records out of order");
    if (b.records[i].drawn_values.size() != s.uncertain.size())
      throw bad(fmt::format("a raw record with {} drawn values, the sweep has {} uncertain "
                            "parameters",
                            b.records[i].drawn_values.size(), s.uncertain.size()));
  }
}

// ---- checksums ----
std::uint32_t crc32(std::string_view data, std::uint32_t crc) noexcept {
  static constexpr auto table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  crc = ~crc;
  for (char ch : data) crc = table[(crc ^ static_cast<std::uint8_t>(ch)) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

namespace {
// The spec with the fields that cannot change results reset: the engine.
sweep_spec results_relevant(sweep_spec s) {
  s.engine = sweep_engine{};
  return s;
}
}  // namespace

bool same_results(const sweep_spec& a, const sweep_spec& b) {
  return serialize(results_relevant(a)) == serialize(results_relevant(b));
}

std::uint64_t fingerprint(const sweep_spec& s) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a 64
  // The build is part of the identity: another version, revision or SIMD
  // target may round differently, and its units must not be mixed in.
  const std::string build = std::string(stickslip::version) + '|' + stickslip::git_revision +
                            '|' + detail::fm::target_name();
  for (char c : build + serialize(results_relevant(s))) {
    h ^= static_cast<std::uint8_t>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

std::string first_difference(const sweep_spec& a, const sweep_spec& b) {
  auto num = [](double x) { return fmt::format("{}", x); };
  for (const char* name : recorded_parameter_names) {
    const double x = parameter_value(a.base, name), y = parameter_value(b.base, name);
    if (std::bit_cast<std::uint64_t>(x) != std::bit_cast<std::uint64_t>(y))
      return fmt::format("parameter {}: {} vs {}", name, num(x), num(y));
  }
  if (a.base.levels() != b.base.levels()) return "belt levels";
  if (a.base.generator() != b.base.generator()) return "belt rates or generator";
  if (!(a.initial == b.initial)) return "initial-condition law (x0, xdot0 ranges or belt start)";
  if (a.axes.size() != b.axes.size())
    return fmt::format("number of grid axes: {} vs {}", a.axes.size(), b.axes.size());
  for (std::size_t i = 0; i < a.axes.size(); ++i) {
    if (a.axes[i].name != b.axes[i].name)
      return fmt::format("grid axis #{}: {} vs {}", i + 1, a.axes[i].name, b.axes[i].name);
    if (a.axes[i].values.size() != b.axes[i].values.size())
      return fmt::format("grid axis {}: {} values vs {}", a.axes[i].name,
                         a.axes[i].values.size(), b.axes[i].values.size());
    for (std::size_t k = 0; k < a.axes[i].values.size(); ++k)
      if (std::bit_cast<std::uint64_t>(a.axes[i].values[k]) !=
          std::bit_cast<std::uint64_t>(b.axes[i].values[k]))
        return fmt::format("grid axis {} value #{}: {} vs {}", a.axes[i].name, k + 1,
                           num(a.axes[i].values[k]), num(b.axes[i].values[k]));
  }
  if (a.realizations != b.realizations)
    return fmt::format("realizations: {} vs {}", a.realizations, b.realizations);
  if (a.seed != b.seed) return fmt::format("seed: {} vs {}", a.seed, b.seed);
  if (a.block_size != b.block_size)
    return fmt::format("block size: {} vs {}", a.block_size, b.block_size);
  if (!(a.histograms == b.histograms)) return "histogram bins or ranges";
  if (a.max_events != b.max_events)
    return fmt::format("max events: {} vs {}", a.max_events, b.max_events);
  if (a.keep_records != b.keep_records)
    return fmt::format("keep records: {} vs {}", a.keep_records, b.keep_records);
  if (a.common_random_numbers != b.common_random_numbers)
    return fmt::format("common random numbers: {} vs {}", a.common_random_numbers,
                       b.common_random_numbers);
  if (a.target_statistic != b.target_statistic || a.target_halfwidth != b.target_halfwidth ||
      a.min_realizations != b.min_realizations)
    return fmt::format("target CI: {}:{} (min {}) vs {}:{} (min {})", a.target_statistic,
                       a.target_halfwidth, a.min_realizations, b.target_statistic,
                       b.target_halfwidth, b.min_realizations);
  // The selection first: the engine settings below follow from it.
  if (!(a.statistics == b.statistics))
    return fmt::format("statistics: {} vs {}", to_string(a.statistics), to_string(b.statistics));
  if (a.family_statistics != b.family_statistics)
    return fmt::format("family statistics: {} vs {}", a.family_statistics, b.family_statistics);
  if (a.means_only != b.means_only)
    return fmt::format("means only: {} vs {}", a.means_only, b.means_only);
  auto laws = [](const sweep_spec& s) {
    std::string t;
    for (const auto& u : s.uncertain)
      t += (t.empty() ? "" : ", ") + u.symbol + " ~ " + to_string(u.law);
    return t.empty() ? std::string("none") : t;
  };
  if (a.uncertain != b.uncertain)
    return fmt::format("uncertain parameters: {} vs {}", laws(a), laws(b));
  if (a.sensitivity_statistic != b.sensitivity_statistic)
    return fmt::format("sensitivity statistic: '{}' vs '{}'", a.sensitivity_statistic,
                       b.sensitivity_statistic);
  if (a.statistics.survival && !(a.survival == b.survival))
    return fmt::format("survival grid: {} bins on [0, {}] s and [0, {}] s vs {} bins on [0, {}] s "
                       "and [0, {}] s",
                       a.survival.bins, a.survival.stick_duration_max,
                       a.survival.slip_duration_max, b.survival.bins,
                       b.survival.stick_duration_max, b.survival.slip_duration_max);
  if (a.burn_in != b.burn_in) return fmt::format("burn-in: {} s vs {} s", a.burn_in, b.burn_in);
  if (a.observe_times != b.observe_times)
    return fmt::format("observe times: {} vs {}", a.observe_times.size(), b.observe_times.size());
  if (!same_results(a, b)) return "bit patterns of some value";
  return {};
}

}  // namespace stickslip
