// Whether decoded (well-formed) units and merged prefixes fit the sweep
// they are to be merged into.
#include "stickslip/serialize.hpp"

#include <algorithm>
#include <optional>
#include <fmt/format.h>

#include "stickslip/error.hpp"

namespace stickslip {
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

// The statistics a unit of `point` starts from: its binnings, belt levels and
// selection of statistics, as the engines make them.
point_statistics fresh_statistics(const sweep_spec& s, std::size_t point) {
  return block_statistics(s, histogram_parameters(s, point));
}
}  // namespace

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
  const point_statistics fresh = fresh_statistics(s, p.point);
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
  if (auto why = shape_difference(b.stats, fresh_statistics(s, u.point))) throw bad(*why);
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

}  // namespace stickslip
