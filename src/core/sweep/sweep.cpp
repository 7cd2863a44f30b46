// The merge of a sweep's block results in block order, and the stop rule of
// a precision target.
#include "stickslip/sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>

#include "stickslip/error.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"

namespace stickslip {

const quantity_info* target_quantity(const sweep_spec& s) {
  if (s.target_statistic.empty()) return nullptr;
  if (const auto* q = find_mean_statistic(s.target_statistic)) return q;
  throw invalid_value("target CI statistic", s.target_statistic,
                      "a statistic with one value per realization: " + mean_statistic_names());
}

std::string unmet_target_note(const result_set& rs) {
  const sweep_spec& s = rs.spec;
  const quantity_info* q = is_sensitivity(s) ? nullptr : target_quantity(s);
  if (!q) return {};
  std::size_t unmet = 0, undefined = 0;  // undefined: fewer than 2 values (e.g. no stick for D_1)
  const point_result* widest = nullptr;
  double widest_h = 0.0;
  for (const auto& p : rs.points) {
    const double h = (p.stats.*q->moments).ci95_half_width();
    if (h <= s.target_halfwidth) continue;
    ++unmet;
    if (std::isnan(h)) {
      ++undefined;
      continue;
    }
    if (!widest || h > widest_h) widest = &p, widest_h = h;
  }
  if (unmet == 0) return {};
  std::string widest_text;
  if (widest) {
    std::string at;
    for (const auto& ax : s.axes) {
      const std::string sym = canonical_symbol(ax.name);
      at += fmt::format("{}{} = {}", at.empty() ? "" : ", ", sym,
                        parameter_value(widest->parameters, sym));
    }
    widest_text = fmt::format(" (the widest: {:.3g}{}{})", widest_h, at.empty() ? "" : ", at ", at);
  }
  const std::string no_width =
      undefined == 0 ? ""
                     : fmt::format("; {} of them had fewer than 2 values of {}, and no half-width",
                                   undefined, q->summary_name);
  return fmt::format(
      "{} of {} grid point{} did not reach the target 95 % half-width {} of the mean of {} within "
      "the cap of {} realizations per point{}{}; raise the cap, or read each point's interval in "
      "the results",
      unmet, rs.points.size(), rs.points.size() == 1 ? "" : "s", s.target_halfwidth,
      q->summary_name, s.realizations, widest_text, no_width);
}

bool meets_target(const sweep_spec& s, const point_statistics& p) {
  if (is_sensitivity(s)) return meets_sensitivity_target(s, p);
  const quantity_info* q = target_quantity(s);
  if (!q || p.realizations < s.min_realizations) return false;
  return (p.*q->moments).ci95_half_width() <= s.target_halfwidth;
}

ordered_merger::ordered_merger(const sweep_spec& s)
    : spec_(&s), records_(point_count(s)), next_block_(point_count(s), 0),
      finished_(point_count(s)) {
  points_.reserve(point_count(s));
  for (std::size_t i = 0; i < point_count(s); ++i) {
    points_.emplace_back(histogram_parameters(s, i), s.histograms, s.family_statistics);
    select_statistics(points_.back(), s);
  }
}

bool records_convergence_after(std::uint64_t b, std::uint64_t total) noexcept {
  if (b <= 64 || b == total) return true;
  // Above 64 blocks keep 32 trace points per doubling of n: the stride is
  // 2^(bit_width(b) - 6), so the trace grows with log N, not N.
  return b % (std::uint64_t{1} << (std::bit_width(b) - 6)) == 0;
}

void ordered_merger::add(const work_unit& u, block_result r) {
  if (discard_) {
    ++merged_;
    return;
  }
  if (point_finished(u.point)) return;  // a block after the point met its target
  pending_.emplace(u, std::move(r));
  const auto nb = blocks_per_point(*spec_);
  auto it = pending_.find(work_unit{u.point, next_block_[u.point]});
  while (it != pending_.end()) {
    auto& dst = points_[u.point];
    dst += it->second.stats;
    const std::uint64_t merged_blocks = next_block_[u.point] + 1;
    const bool stop = merged_blocks < nb && meets_target(*spec_, dst);
    if (records_convergence_after(merged_blocks, nb) || stop) dst.record_convergence();
    auto& rec = records_[u.point];
    rec.insert(rec.end(), std::make_move_iterator(it->second.records.begin()),
               std::make_move_iterator(it->second.records.end()));
    pending_.erase(it);
    ++merged_;
    if (++next_block_[u.point] >= nb) {
      finished_[u.point].store(1, std::memory_order_relaxed);
      dst.finish();
      break;
    }
    if (stop) {
      dst.finish();
      // The blocks this point no longer needs count as done; any of them
      // computed ahead (pending now or arriving later) are dropped.
      merged_ += nb - next_block_[u.point];
      finished_[u.point].store(1, std::memory_order_relaxed);
      std::erase_if(pending_, [&](const auto& kv) { return kv.first.point == u.point; });
      break;
    }
    it = pending_.find(work_unit{u.point, next_block_[u.point]});
  }
}

void ordered_merger::restore(merged_prefix p) {
  const auto nb = blocks_per_point(*spec_);
  points_[p.point] = std::move(p.stats);
  next_block_[p.point] = p.blocks;
  merged_ += p.blocks;
  // The stop rule as add() applied it after the prefix's last block.
  const bool stop = p.blocks < nb && meets_target(*spec_, points_[p.point]);
  if (stop) merged_ += nb - p.blocks;
  if (stop || p.blocks >= nb) {
    finished_[p.point].store(1, std::memory_order_relaxed);
    points_[p.point].finish();
  }
}

bool ordered_merger::complete() const noexcept { return merged_ == unit_count(*spec_); }

result_set make_result_set(const sweep_spec& s, ordered_merger&& m) {
  result_set rs;
  rs.spec = s;
  for (std::size_t i = 0; i < point_count(s); ++i)
    rs.points.push_back({point_parameters(s, i), point_index(s, i), std::move(m.points()[i])});
  if (s.keep_records) rs.records = std::move(m.records());
  return rs;
}

}  // namespace stickslip
