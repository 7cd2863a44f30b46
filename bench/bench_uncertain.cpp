// Cost of a point with uncertain parameters (sweep_spec::uncertain) beside
// the same point with fixed values, one work unit of 500 realizations of the
// paper's model at k = 40, t_a = 50 s. Items are realizations; events/s is
// reported too (the laws change the events per realization).
//   BM_unit_reference:  the fixed point on the scalar reference engine
//                       (simulate_block_reference): the naive baseline;
//   BM_unit_lanes:      the fixed point on the lane engine (the default);
//   BM_unit_uncertain:  mu ~ uniform(2,7): every realization draws mu, builds
//                       its observer and runs the scalar engine
//                       (uncertainty/uncertain_realization.hpp);
//   BM_unit_uncertain_lambda: mu ~ uniform(2,7), lambda ~ loguniform(0.5,10),
//                       the sensitivity case.
// The uncertain units cost what the reference engine costs at the same
// events per realization, plus the per-realization draws and set-up.
#include <benchmark/benchmark.h>

#include "stickslip/sweep.hpp"
#include "stickslip/uncertainty/parameter_law.hpp"

namespace {

using namespace stickslip;

sweep_spec unit_spec(benchmark::State& state) {
  sweep_spec s;
  s.base.stiffness = 40.0;
  s.base.friction_coefficient = 4.5;  // the median of uniform(2,7)
  s.base.switch_rate = static_cast<double>(state.range(0)) / 10.0;
  s.realizations = 500;
  s.block_size = 500;
  return s;
}

void run_units(benchmark::State& state, const sweep_spec& s,
               block_result (*simulate)(const sweep_spec&, const work_unit&)) {
  validate(s);
  std::uint64_t realizations = 0, events = 0;
  for (auto _ : state) {
    const block_result b = simulate(s, work_unit{0, 0});
    realizations += b.stats.realizations;
    events += b.stats.events.total();
    benchmark::DoNotOptimize(b.stats.stick_fraction);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(realizations));
  state.counters["events/s"] =
      benchmark::Counter(static_cast<double>(events), benchmark::Counter::kIsRate);
  state.counters["events_per_realization"] =
      static_cast<double>(events) / static_cast<double>(realizations);
}

void BM_unit_reference(benchmark::State& state) {
  run_units(state, unit_spec(state), simulate_block_reference);
}

void BM_unit_lanes(benchmark::State& state) {
  run_units(state, unit_spec(state), simulate_block);
}

void BM_unit_uncertain(benchmark::State& state) {
  sweep_spec s = unit_spec(state);
  s.uncertain = {{"mu", parse_law("uniform(2,7)", "mu")}};
  run_units(state, s, simulate_block);
}

void BM_unit_uncertain_lambda(benchmark::State& state) {
  sweep_spec s = unit_spec(state);
  s.uncertain = {{"mu", parse_law("uniform(2,7)", "mu")},
                 {"lambda", parse_law("loguniform(0.5,10)", "lambda")}};
  run_units(state, s, simulate_block);
}

}  // namespace

// lambda = 1 and 3.8 (x10), as in the reproducibility sweep.
BENCHMARK(BM_unit_reference)->Arg(10)->Arg(38)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_unit_lanes)->Arg(10)->Arg(38)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_unit_uncertain)->Arg(10)->Arg(38)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_unit_uncertain_lambda)->Arg(10)->Unit(benchmark::kMillisecond);
