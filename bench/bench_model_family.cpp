// The model family's scalar engine (simulate_model) beside the paper's
// simulate(), on the paper's point (m = 1, k = 4, mu = 5, V = 1, t_a = 50 s)
// against lambda, same seeds and initial conditions. Items are events.
//   BM_paper:       simulate() with poisson_switches (the baseline).
//   BM_family/...:  simulate_model with markov_level_switches; the second
//                   argument picks the variant: 0 the paper model (same bits),
//                   1 mu_s = 6 > mu_k = 5, 2 zeta = 0.1, 3 zeta = 0.1 and
//                   mu_s = 6, 4 zeta = 2 (over-damped).
#include <benchmark/benchmark.h>

#include <cmath>

#include "stickslip/belt_switches.hpp"
#include "stickslip/initial_conditions.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/model/belt_chain.hpp"
#include "stickslip/model/model_engine.hpp"

namespace {

using namespace stickslip;

constexpr std::uint64_t seed = 1, point = 5, pool = 256;

struct null_model_observer : observer_base {
  void on_segment(const segment&) noexcept {}
  using observer_base::on_segment;
};

model_parameters paper_point(benchmark::State& state) {
  model_parameters p;
  p.switch_rate = static_cast<double>(state.range(0)) / 10.0;
  return p;
}

void finish(benchmark::State& state, const event_counts& c, std::int64_t runs) {
  state.SetItemsProcessed(static_cast<std::int64_t>(c.total()));
  state.counters["realizations/s"] =
      benchmark::Counter(static_cast<double>(runs), benchmark::Counter::kIsRate);
}

void BM_paper(benchmark::State& state) {
  const model_parameters p = paper_point(state);
  null_model_observer obs;
  event_counts c;
  std::int64_t runs = 0;
  for (auto _ : state) {
    const std::uint64_t r = static_cast<std::uint64_t>(runs++) % pool;
    const initial_conditions ic = draw_initial_conditions({}, seed, point, r);
    poisson_switches sw(p.switch_rate, seed, point, r);
    c += simulate(p, ic, sw, obs);
  }
  finish(state, c, runs);
}

void BM_family(benchmark::State& state) {
  const model_parameters p = paper_point(state);
  oscillator_model m = model_of(p);
  const auto variant = state.range(1);
  if (variant == 1 || variant == 3) m.static_friction = 6.0;
  const double zeta = variant == 2 || variant == 3 ? 0.1 : variant == 4 ? 2.0 : 0.0;
  m.damping = 2.0 * zeta * std::sqrt(m.stiffness * m.mass);
  const belt_chain chain(m.belt);
  null_model_observer obs;
  event_counts c;
  std::int64_t runs = 0;
  for (auto _ : state) {
    const std::uint64_t r = static_cast<std::uint64_t>(runs++) % pool;
    const initial_conditions ic = draw_initial_conditions({}, seed, point, r);
    const std::size_t level = ic.belt_direction > 0 ? 0 : 1;
    markov_level_switches sw(chain, level, seed, point, r);
    c += simulate_model(m, {ic.position, ic.velocity, level}, sw, obs);
  }
  finish(state, c, runs);
}

BENCHMARK(BM_paper)->ArgName("lambda*10")->Arg(1)->Arg(10)->Arg(100);
BENCHMARK(BM_family)
    ->ArgNames({"lambda*10", "variant"})
    ->ArgsProduct({{1, 10, 100}, {0, 1, 2, 3, 4}});

}  // namespace
