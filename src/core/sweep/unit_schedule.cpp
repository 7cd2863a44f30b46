// The cost model that orders the units, and running them on threads.
#include "stickslip/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "sweep/work_pool.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"

namespace stickslip {

double expected_events(const model_parameters& p) {
  // The family: the mean rate of leaving a level and the largest level stand
  // in for lambda and V (a cost model, not physics).
  double rate = p.switch_rate, speed = p.belt_speed;
  if (!p.belt_levels.empty() || !p.belt_rates.empty() || !p.belt_generator.empty()) {
    const auto v = p.levels();
    const auto q = p.generator();
    rate = speed = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) {
      rate += -q[i * v.size() + i] / static_cast<double>(v.size());
      speed = std::max(speed, std::abs(v[i]));
    }
  }
  const double switches = rate * p.window;
  const double tau = 2.0 * speed / (p.mu_k() * p.gravity);
  const double p_onset = 1.0 / (1.0 + rate * tau);
  const double p_break = p_onset * std::exp(-rate * p.max_stick_duration());
  return 2.0 + switches * (1.0 + p_onset + 1.5 * p_break);
}

double expected_unit_cost(const sweep_spec& s, const work_unit& u) {
  const std::uint64_t first = u.block * s.block_size;
  const std::uint64_t last = std::min(s.realizations, first + s.block_size);
  // A design row runs d + 3 realizations.
  const double runs = is_sensitivity(s) ? static_cast<double>(runs_per_row(s)) : 1.0;
  return runs * static_cast<double>(last - first) * expected_events(point_parameters(s, u.point));
}

std::vector<std::size_t> points_by_cost(const sweep_spec& s) {
  const std::size_t n = point_count(s);
  std::vector<double> cost(n);
  for (std::size_t i = 0; i < n; ++i) {
    cost[i] = expected_events(point_parameters(s, i));
  }
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return cost[a] > cost[b]; });
  return order;
}

void run_units(const sweep_spec& s, unsigned threads, ordered_merger& merger,
               const sweep_hooks& hooks) {
  const std::uint64_t total = unit_count(s);
  const std::uint64_t nb = blocks_per_point(s);
  const auto order = points_by_cost(s);
  // i-th unit to start: block i % nb of the (i / nb)-th most expensive point.
  auto scheduled = [&](std::uint64_t i) {
    return work_unit{order[static_cast<std::size_t>(i / nb)], i % nb};
  };
  struct computed {
    std::vector<work_unit> units;
    std::vector<block_result> results;
  };
  // Skipping the units of finished points (a precision target met) saves
  // work only; the merger drops whatever still arrives for them.
  auto compute = [&](std::uint64_t i0, std::uint64_t i1) {
    computed c;
    for (std::uint64_t i = i0; i < i1; ++i) {
      const auto u = scheduled(i);
      if (merger.point_finished(u.point)) continue;
      if (!hooks.wanted || hooks.wanted(u)) c.units.push_back(u);
    }
    c.results = simulate_units(s, c.units);
    return c;
  };
  auto merge = [&](computed& c) {
    for (std::size_t k = 0; k < c.units.size(); ++k) {
      if (hooks.unit_done) hooks.unit_done(c.units[k], c.results[k]);
      merger.add(c.units[k], std::move(c.results[k]));
      if (hooks.progress) hooks.progress(merger.merged_units(), total);
    }
  };
  detail::run_in_batches(threads, total, units_per_batch(s), compute, merge);
}

result_set run_sweep(const sweep_spec& s, unsigned threads, const sweep_hooks& hooks) {
  validate(s);
  const auto t0 = std::chrono::steady_clock::now();
  ordered_merger merger(s);
  run_units(s, threads, merger, hooks);
  auto rs = make_result_set(s, std::move(merger));
  rs.elapsed_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  rs.threads = detail::resolved_threads(threads);
  return rs;
}

}  // namespace stickslip
