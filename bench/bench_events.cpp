// Cost per event type of the exact integrator. Each benchmark replays a
// hand-made scenario dominated by one kind of event (given_switches, null
// observer), and reports items/s = events/s plus the share of each kind.
//   slip_reversal : tiny friction, large orbit, no switches: every root of
//                   x' = v lies outside the band.
//   slip_switch   : |x'| >> V and switches every 0.1 ms: every switch lands
//                   in a slip long before the next root.
//   stick_switch_onset : a stick ended by a switch after 1 ms, then the slip
//                   back to x' = v (a stick onset): pairs of the two events.
//   stick_break   : k = 40, sticks run to the band edge, then the grazing
//                   orbit until a switch; cycles of onset, break, switch.
#include <benchmark/benchmark.h>

#include <vector>

#include "stickslip/belt_switches.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/observer.hpp"

namespace {

using namespace stickslip;

void report(benchmark::State& state, const event_counts& c, std::int64_t runs) {
  const double n = static_cast<double>(c.total());
  state.SetItemsProcessed(static_cast<std::int64_t>(c.total()));
  state.counters["switch_share"] = static_cast<double>(c.belt_switches) / n;
  state.counters["onset_share"] = static_cast<double>(c.stick_onsets) / n;
  state.counters["break_share"] = static_cast<double>(c.stick_breaks) / n;
  state.counters["reversal_share"] = static_cast<double>(c.slip_reversals) / n;
  state.counters["events_per_run"] = n / static_cast<double>(runs);
}

void run(benchmark::State& state, const model_parameters& p, const initial_conditions& ic,
         const std::vector<double>& switches) {
  event_counts total;
  std::int64_t runs = 0;
  for (auto _ : state) {
    given_switches sw(switches);
    null_observer obs;
    total += simulate(p, ic, sw, obs);
    ++runs;
  }
  report(state, total, runs);
}

std::vector<double> regular_switches(double first, double spacing, double until) {
  std::vector<double> t;
  for (double s = first; s < until; s += spacing) t.push_back(s);
  return t;
}

void BM_event_slip_reversal(benchmark::State& state) {
  model_parameters p;
  p.friction_coefficient = 0.01;  // a = 0.0245 m
  p.window = 1000.0;              // ~640 reversals (two per period pi; the
                                  // Coulomb decay of 2a per half period needs ~20000)
  run(state, p, initial_conditions{1000.0, 0.0, 1}, {});
}
BENCHMARK(BM_event_slip_reversal);

void BM_event_slip_switch(benchmark::State& state) {
  model_parameters p;
  p.window = 0.5;  // x' = 1000 cos(2t) stays far from +-1: no root before t_a
  run(state, p, initial_conditions{0.0, 1000.0, 1}, regular_switches(1e-4, 1e-4, p.window));
}
BENCHMARK(BM_event_slip_switch);

void BM_event_stick_switch_onset(benchmark::State& state) {
  model_parameters p;  // k = 4, mu = 5: a = 12.26 m; slip back to x' = v takes ~0.04 s
  p.window = 20.0;
  run(state, p, initial_conditions{0.0, 1.0, 1}, regular_switches(0.05, 0.05, p.window));
}
BENCHMARK(BM_event_stick_switch_onset);

void BM_event_stick_break(benchmark::State& state) {
  model_parameters p;
  p.stiffness = 40.0;  // a = 1.23 m: a stick crosses the band in 2.45 s, period 1 s
  p.window = 200.0;
  run(state, p, initial_conditions{0.0, 1.0, 1}, regular_switches(4.0, 4.0, p.window));
}
BENCHMARK(BM_event_stick_break);

}  // namespace
