// The grid of a sweep and its work units.
#include "stickslip/sweep_spec.hpp"

#include "stickslip/uncertainty/uncertain_draws.hpp"

namespace stickslip {

void apply_statistics_selection(sweep_spec& s) {
  s.family_statistics = needs_family_statistics(s.statistics);
  s.means_only = needs_means_only(s.statistics);
}

void select_statistics(point_statistics& stats, const sweep_spec& s) {
  if (s.statistics.survival) stats.select_survival(s.survival);
  if (!s.observe_times.empty()) stats.select_observe_times(s.observe_times, s.base.levels().size());
}

bool keeps_causal_score(const sweep_spec& s) noexcept {
  return s.family_statistics || (s.means_only && selects_derivatives(s.statistics));
}

point_statistics block_statistics(const sweep_spec& s, const model_parameters& p) {
  point_statistics stats(p, s.histograms, s.family_statistics, s.initial.belt_start == 0,
                         s.means_only, keeps_causal_score(s));
  select_statistics(stats, s);
  return stats;
}

std::size_t point_count(const sweep_spec& s) noexcept {
  std::size_t n = 1;
  for (const auto& ax : s.axes) n *= ax.values.size();
  return n;
}

std::vector<std::size_t> point_index(const sweep_spec& s, std::size_t point) {
  std::vector<std::size_t> idx(s.axes.size());
  for (std::size_t k = s.axes.size(); k-- > 0;) {
    idx[k] = point % s.axes[k].values.size();
    point /= s.axes[k].values.size();
  }
  return idx;
}

model_parameters point_parameters(const sweep_spec& s, std::size_t point) {
  model_parameters p = s.base;
  const auto idx = point_index(s, point);
  for (std::size_t k = 0; k < s.axes.size(); ++k)
    set_parameter(p, s.axes[k].name, s.axes[k].values[idx[k]]);
  if (!s.uncertain.empty()) return with_medians(p, s.uncertain);  // what the point stands for
  return p.is_paper_model() ? paper_form(p) : p;
}

model_parameters histogram_parameters(const sweep_spec& s, std::size_t point) {
  model_parameters p = point_parameters(s, point);
  if (s.uncertain.empty()) return p;
  for (const auto& u : s.uncertain) {
    const auto& sym = u.symbol;
    const bool smaller = sym == "k" || sym == "V" || sym == "lambda" || sym == "r1" || sym == "r2";
    const bool larger = sym == "mu" || sym == "mu_s" || sym == "mu_k" || sym == "m" ||
                        sym == "g" || sym == "c" || sym == "ta";
    if (smaller || larger) set_parameter(p, sym, quantile(u.law, smaller ? 0.001 : 0.999));
  }
  return p;
}

std::uint64_t blocks_per_point(const sweep_spec& s) noexcept {
  return (s.realizations + s.block_size - 1) / s.block_size;
}
std::uint64_t unit_count(const sweep_spec& s) noexcept {
  return point_count(s) * blocks_per_point(s);
}
work_unit unit_at(const sweep_spec& s, std::uint64_t i) noexcept {
  const auto b = blocks_per_point(s);
  return {static_cast<std::size_t>(i / b), i % b};
}

}  // namespace stickslip
