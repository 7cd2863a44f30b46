// The codec of a point's statistics (statistics.hpp): its accumulators in
// the order of the statistics schema (statistics_schema.cpp), so that a new
// statistic changes the layout id instead of being misread.
#include "serialize/codecs.hpp"

#include <cmath>
#include <fmt/format.h>

#include "stickslip/statistics.hpp"
#include "stickslip/statistics_schema.hpp"

namespace stickslip::serial {
namespace {

// A list of accumulators: its length, then each.
template <class T>
void put_list(writer& w, const std::vector<T>& list) {
  w.u64(list.size());
  for (const auto& m : list) put(w, m);
}
// Its length checked against the bytes left at `min_bytes` an element.
template <class T, class Get>
void get_list(reader& r, std::vector<T>& list, std::string_view what, std::size_t min_bytes,
              Get get) {
  list.resize(r.count(what, min_bytes));
  for (auto& m : list) m = get(r);
}

// The means-only flag's byte: bit 0 means only; bit 1 set when the causal
// score is kept otherwise than with the family statistics or means only
// (the rule before point_statistics::keeps_causal_score had a flag of its
// own), so that the bytes of every journal from before stay the same.
std::uint8_t means_flags(const point_statistics& s) noexcept {
  const bool by_old_rule = s.family_statistics || s.means_only;
  return static_cast<std::uint8_t>((s.means_only ? 1 : 0) |
                                   (s.keeps_causal_score() != by_old_rule ? 2 : 0));
}
void set_means_flags(point_statistics& s, std::uint8_t flags) {
  if (flags > 3) throw corrupt(fmt::format("means-only flag: {} is not 0 to 3", flags));
  s.means_only = (flags & 1) != 0;
  s.causal_score_kept = (s.family_statistics || s.means_only) != ((flags & 2) != 0);
}

}  // namespace

// The accumulators in schema order (statistics_schema.cpp): every quantity's
// moments, every binned quantity's histogram, the realization count, every
// counter; then the convergence trace.
void put(writer& w, const point_statistics& s) {
  for (const auto& q : quantities()) put(w, s.*q.moments);
  for (const auto& q : quantities())
    if (q.density) put(w, s.*q.density);
  w.u64(s.realizations);
  w.u8(s.family_statistics ? 1 : 0);
  w.u8(means_flags(s));
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
    if (q.generator_score) put_list(w, s.*q.generator_score);
  put_values(w, s.generator);
  w.u8(s.stationary_start ? 1 : 0);
  for (const auto& l : level_quantities()) put_list(w, s.*l.moments);
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
  set_means_flags(s, r.u8("means-only flag"));
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
    if (q.generator_score)
      get_list(r, s.*q.generator_score, "generator score moments", five_sums_bytes,
               [](reader& in) { return get_five_sums<score_moments>(in, "generator score moments"); });
  s.generator = get_values(r, "belt generator");
  if (const auto n = static_cast<std::size_t>(std::lround(std::sqrt(double(s.generator.size()))));
      n * n != s.generator.size() || (!s.generator.empty() && n < 2))
    throw corrupt(fmt::format("a belt generator of {} entries is not an n x n matrix, n >= 2",
                              s.generator.size()));
  s.stationary_start = r.boolean("stationary start flag");
  if (!s.generator.empty() && s.stationary_start)
    s.generator_start_terms = stationary_score_terms(s.generator);
  for (const auto& l : level_quantities())
    get_list(r, s.*l.moments, l.name, 24, get_mean_variance);
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
      const auto i = sparse_index(r.u64(j.name), n, k, last, j.name, "cell index");
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

}  // namespace stickslip::serial
