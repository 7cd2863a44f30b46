#include "grid_windows.hpp"

#include <algorithm>

#include "stickslip/run/result_memory.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"

namespace stickslip::run::detail {

bool splits_into_windows(const sweep_spec& spec, std::size_t window_points) {
  if (window_points == 0 || spec.axes.empty() || is_sensitivity(spec)) return false;
  if (spec.statistics.survival &&
      (spec.survival.stick_duration_max == 0.0 || spec.survival.slip_duration_max == 0.0))
    return false;
  return point_count(spec) > window_points;
}

std::vector<grid_window> windows_of(const sweep_spec& spec, std::size_t window_points) {
  if (!splits_into_windows(spec, window_points)) return {{spec, 0}};
  const auto& first_axis = spec.axes.front().values;
  const std::size_t slab = point_count(spec) / first_axis.size();  // points per slab
  const std::size_t per_window = std::max<std::size_t>(1, window_points / slab);
  std::vector<grid_window> out;
  for (std::size_t a = 0; a < first_axis.size(); a += per_window) {
    const std::size_t n = std::min(per_window, first_axis.size() - a);
    grid_window w{spec, a * slab};
    w.spec.axes.front().values.assign(first_axis.begin() + static_cast<std::ptrdiff_t>(a),
                                      first_axis.begin() + static_cast<std::ptrdiff_t>(a + n));
    out.push_back(std::move(w));
  }
  return out;
}

void restore_window(const grid_window& w, std::map<std::size_t, io::journaled_prefix>& prefixes,
                    std::map<work_unit, io::journaled_unit>& units, ordered_merger& merger) {
  const std::size_t first = w.offset, end = w.offset + point_count(w.spec);
  io::journal_readback journal;
  for (auto it = prefixes.lower_bound(first); it != prefixes.end() && it->first < end;) {
    merged_prefix prefix = it->second.decode(journal);
    prefix.point -= first;
    merger.restore(std::move(prefix));
    it = prefixes.erase(it);
  }
  // The units are read in the order they lie in the journal (segment,
  // offset), not in grid order: a merge's alternate between its shards' files
  // (every n-th unit is shard i's), more of them than journal_readback keeps
  // open.
  const auto from = units.lower_bound(work_unit{first, 0});
  const auto to = units.lower_bound(work_unit{end, 0});
  std::vector<std::map<work_unit, io::journaled_unit>::iterator> order;
  for (auto it = from; it != to; ++it) order.push_back(it);
  std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) {
    const io::journal_place &x = a->second.place, &y = b->second.place;
    return x.segment != y.segment && *x.segment != *y.segment ? *x.segment < *y.segment
                                                               : x.offset < y.offset;
  });
  for (const auto& it : order)
    merger.add({it->first.point - first, it->first.block}, it->second.decode(journal));
  units.erase(from, to);
}

void append_window(result_set& all, result_set part, std::size_t offset, bool release) {
  // Without release the window is the whole grid (offset 0): its indices hold.
  if (release) part = slab_of(all.spec, std::move(part), offset);
  for (auto& p : part.points) all.points.push_back(std::move(p));
  for (auto& rec : part.records) all.records.push_back(std::move(rec));
}

result_set slab_of(const sweep_spec& spec, result_set part, std::size_t offset) {
  part.spec = spec;
  for (std::size_t i = 0; i < part.points.size(); ++i) {
    auto& p = part.points[i];
    p.index = point_index(spec, offset + i);
    release_unselected(p.stats, spec);
  }
  return part;
}

}  // namespace stickslip::run::detail
