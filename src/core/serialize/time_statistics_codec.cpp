// The codec of the observe-time statistics (accumulators/time_statistics.hpp)
// and of the quantile sketches they hold (accumulators/quantile_sketch.hpp).
#include "serialize/codecs.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <fmt/format.h>

namespace stickslip::serial {
namespace {

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
      const auto i = sparse_index(get_varint(r, what), range, k, last, what, "bin");
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

}  // namespace

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
    for (const auto* m : {&a.position, &a.velocity, &a.relative_velocity, &a.energy})
      put_mean_m2(w, *m);
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

}  // namespace stickslip::serial
