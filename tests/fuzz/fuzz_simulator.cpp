// The simulator over the raw parameter space: the input bytes are read as
// doubles (any bit pattern: NaN, inf, denormals, huge, negative) for the
// seven model parameters, the initial state and a list of belt switch times.
// What passes validation is simulated with a small event bound, through a
// given switch list and through the sweep engine (Poisson switches, both
// engines, which must agree bit for bit). Nothing may crash, hang or break
// the invariants (episodes tile [0, t_a], R in [0, 1]); exceeding the bound
// must be reported as stickslip::error with exit_code::work_bound.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "fuzz_common.hpp"
#include "stickslip/belt_switches.hpp"
#include "stickslip/error.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/statistics.hpp"
#include "stickslip/sweep.hpp"

namespace {

constexpr std::int64_t max_events = 2000;

struct byte_source {
  const std::uint8_t* p;
  std::size_t n;
  double next() {
    double d = 0;
    if (n >= 8) {
      std::memcpy(&d, p, 8);
      p += 8;
      n -= 8;
    }
    return d;
  }
};

struct tiling_observer : stickslip::realization_observer {
  using realization_observer::realization_observer;
  double last_end = 0;
  bool ok = true;
  void on_episode(const stickslip::episode& e) {
    if (e.start != last_end || e.end < e.start) ok = false;
    last_end = e.end;
    realization_observer::on_episode(e);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stickslip;
  byte_source in{data, size};
  model_parameters p;
  for (const char* name : parameter_names) set_parameter(p, name, in.next());
  initial_conditions ic{in.next(), in.next(), in.n % 2 ? 1 : -1};
  std::vector<double> switches;
  while (in.n >= 8 && switches.size() < 64) switches.push_back(in.next());
  try {
    validate(p);
  } catch (const error&) {
    return 0;
  }
  // Found by this target: finite magnitudes so large that B^2 = (w y)^2 + x'^2
  // overflowed (e.g. V = 6.9e274) gave NaN episode times. validate() now bounds
  // every parameter and derived scale to [1e-60, 1e60], and the initial state
  // is validated like the CLI does (tests/regression/test_overflowing_magnitudes.cpp).
  try {
    validate(ic);
  } catch (const error&) {
    return 0;
  }

  // 1. given switch times (validated like the CLI does), bounded events
  bool times_ok = true;
  try {
    validate_switch_times(switches);
  } catch (const error&) {
    times_ok = false;
  }
  if (times_ok && std::isfinite(ic.position) && std::isfinite(ic.velocity)) {
    tiling_observer obs(p, true);
    obs.reset(0, ic.position, ic.velocity, ic.belt_direction);
    given_switches sw(switches);
    try {
      (void)simulate(p, ic, sw, obs, max_events);
      obs.finish();
      FUZZ_CHECK(obs.ok, "episodes do not tile the window");
      FUZZ_CHECK(obs.last_end == p.window, "last episode ends at %g, not t_a = %g", obs.last_end,
                 p.window);
      const double R = obs.record().stick_fraction;
      FUZZ_CHECK(R >= 0 && R <= 1 + 1e-12, "stick fraction %g outside [0, 1]", R);
    } catch (const error& e) {
      FUZZ_CHECK(e.code() == exit_code::work_bound, "unexpected error: %s", e.what());
    }
  }

  // 2. the sweep engines with Poisson switches: validate, then one block
  sweep_spec s;
  s.base = p;
  s.realizations = 3;
  s.block_size = 3;
  s.max_events = max_events;
  s.histograms.bins = 4;
  try {
    validate(s);
  } catch (const error&) {
    return 0;
  }
  std::string fast, reference;
  try {
    fast = serialize(work_unit{}, simulate_block(s, work_unit{}));
  } catch (const error& e) {
    FUZZ_CHECK(e.code() == exit_code::work_bound, "unexpected error: %s", e.what());
  }
  try {
    reference = serialize(work_unit{}, simulate_block_reference(s, work_unit{}));
  } catch (const error& e) {
    FUZZ_CHECK(e.code() == exit_code::work_bound, "unexpected error: %s", e.what());
  }
  FUZZ_CHECK(fast == reference, "fast and reference engines disagree");
  return 0;
}
