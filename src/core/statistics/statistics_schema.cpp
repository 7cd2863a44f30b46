// The identity of the statistics schema and the histogram range rules (the
// table itself is in statistics_schema.hpp).
#include "stickslip/statistics_schema.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>

#include "fnv1a.hpp"

namespace stickslip {

std::uint64_t statistics_schema_id() noexcept {
  static const std::uint64_t id = [] {
    detail::fnv1a f;
    for (const auto& q : quantity_table) {
      f.add("quantity");
      f.add(q.name);
      if (q.rate_score) f.add("rate scores");
      if (q.generator_score) f.add("generator scores");
      f.byte(static_cast<unsigned char>(q.sampled));
      f.byte(static_cast<unsigned char>(q.range));
    }
    for (const auto& c : counter_table) {
      f.add("counter");
      f.add(c.name);
    }
    for (const auto& l : level_table) {
      f.add("level quantity");
      f.add(l.name);
    }
    for (const auto& l : survival_laws()) {
      f.add("survival law");
      f.add(l.name);
      f.byte(static_cast<unsigned char>(l.sampled));
    }
    for (const auto& j : joint_table) {
      f.add("joint histogram");
      f.add(j.name);
      f.byte(static_cast<unsigned char>(j.x));
      f.byte(static_cast<unsigned char>(j.y));
    }
    return f.h;
  }();
  return id;
}

std::string mean_statistic_names() {
  std::string out;
  for (const auto& q : quantities())
    if (per_realization(q.sampled)) out += (out.empty() ? "" : ", ") + std::string(q.summary_name);
  return out;
}

const quantity_info* find_mean_statistic(std::string_view name) noexcept {
  for (const auto& q : quantities())
    if (per_realization(q.sampled) &&
        (name == q.summary_name || name == q.name || name == q.symbol))
      return &q;
  return nullptr;
}

estimate belt_rate_derivative(const point_accumulators& s, const quantity_info& q,
                              std::size_t j) noexcept {
  if (!q.rate_score || !(s.belt_rates[j] > 0.0)) return {};
  return score_derivative((s.*q.rate_score)[j], s.*q.moments, s.belt_rates[j]);
}

estimate belt_generator_derivative(const point_accumulators& s, const quantity_info& q,
                                   std::size_t i, std::size_t j) noexcept {
  if (!q.generator_score) return {};
  const auto& m = s.*q.generator_score;
  const std::size_t n = s.level_fraction.size();
  if (i == j || i >= n || j >= n || m.size() != n * n || s.generator.size() != n * n) return {};
  const double rate = s.generator[i * n + j];
  if (!(rate > 0.0)) return {};
  return score_derivative(m[i * n + j], s.*q.moments, rate);
}

namespace {
// b = a_s + c max|v_i| / k: the band |x + c v / k| <= a_s at every level.
double stick_band_half_width(const model_parameters& p) {
  double v = 0.0;
  for (double u : p.levels()) v = std::max(v, std::abs(u));
  return p.band_half_width() + p.damping * v / p.stiffness;
}
}  // namespace

double histogram_lower(histogram_range range, const model_parameters& p,
                       const histogram_spec&) noexcept {
  return range == histogram_range::stick_band ? -stick_band_half_width(p) : 0.0;
}

double histogram_upper(histogram_range range, const model_parameters& p,
                       const histogram_spec& h) noexcept {
  switch (range) {
    case histogram_range::unit_interval: return 1.0;
    case histogram_range::stick_duration:
      return h.stick_duration_max > 0 ? h.stick_duration_max : p.max_stick_duration();
    case histogram_range::slip_duration:
      return h.slip_duration_max > 0 ? h.slip_duration_max
                                     : std::min(p.window, 5.0 / p.switch_rate);
    case histogram_range::stick_band: return stick_band_half_width(p);
    case histogram_range::none: break;
  }
  return 1.0;
}

}  // namespace stickslip
