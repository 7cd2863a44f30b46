// Cost of one paper realization (t_a = 50 s, mu = 5) against lambda. The
// number of events grows linearly with lambda, so events/s (items/s) should
// stay roughly flat while realizations/s falls.
//   BM_realization_poisson: the production path, simulate_realization with
//     Poisson switch draws (Philox + log) and the statistics observer.
//   BM_realization_given:   the same realizations replayed from pre-drawn
//     switch times with a null observer: the integrator alone.
#include <benchmark/benchmark.h>

#include <vector>

#include "stickslip/belt_switches.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/observer.hpp"
#include "stickslip/statistics.hpp"
#include "stickslip/sweep.hpp"

namespace {

using namespace stickslip;

constexpr std::uint64_t pool = 256;  // realizations cycled through

model_parameters point(benchmark::State& state) {
  model_parameters p;
  p.switch_rate = static_cast<double>(state.range(0)) / 10.0;
  p.stiffness = static_cast<double>(state.range(1));
  return p;
}

void finish(benchmark::State& state, const event_counts& c, std::int64_t runs) {
  state.SetItemsProcessed(static_cast<std::int64_t>(c.total()));
  state.counters["realizations/s"] = benchmark::Counter(static_cast<double>(runs), benchmark::Counter::kIsRate);
  state.counters["events_per_realization"] = static_cast<double>(c.total()) / static_cast<double>(runs);
}

void BM_realization_poisson(benchmark::State& state) {
  const auto p = point(state);
  sweep_spec spec;
  spec.base = p;
  event_counts total;
  std::int64_t runs = 0;
  realization_observer obs(p);
  for (auto _ : state) {
    const auto r = static_cast<std::uint64_t>(runs) % pool;
    const auto ic = draw_initial_conditions(spec.initial, spec.seed, point_key(p), r);
    obs.reset(r, ic.position, ic.velocity, ic.belt_direction);
    total += simulate_realization(spec, p, r, obs);
    obs.finish();
    benchmark::DoNotOptimize(obs.record());
    ++runs;
  }
  finish(state, total, runs);
}

void BM_realization_given(benchmark::State& state) {
  const auto p = point(state);
  const auto key = point_key(p);
  std::vector<initial_conditions> ics;
  std::vector<std::vector<double>> switches;
  for (std::uint64_t r = 0; r < pool; ++r) {
    ics.push_back(draw_initial_conditions(initial_condition_law{}, 1, key, r));
    poisson_switches sw(p.switch_rate, 1, key, r);
    auto& t = switches.emplace_back();
    for (double s = sw.next(); s < p.window; s = sw.next()) t.push_back(s);
  }
  event_counts total;
  std::int64_t runs = 0;
  for (auto _ : state) {
    const auto r = static_cast<std::size_t>(runs) % pool;
    given_switches sw(switches[r]);
    null_observer obs;
    total += simulate(p, ics[r], sw, obs);
    ++runs;
  }
  finish(state, total, runs);
}

// Arguments: {10 lambda, k}.
void lambdas(benchmark::internal::Benchmark* b) {
  for (long k : {4L, 40L})
    for (long l10 : {1L, 3L, 10L, 38L, 100L, 300L}) b->Args({l10, k});
  b->ArgNames({"lambda_x10", "k"});
}
BENCHMARK(BM_realization_poisson)->Apply(lambdas);
BENCHMARK(BM_realization_given)->Apply(lambdas);

}  // namespace
