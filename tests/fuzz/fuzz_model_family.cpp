// The model family simulator (model/model_engine.hpp) over decoded models:
// the input bytes choose mu_k, mu_s >= mu_k (equal one time in two), c >= 0
// (0, under-, critically or over-damped), k, m, g, 2-5 belt levels (some 0,
// some symmetric pairs v, -v), two rates or a generator (or lambda), a start
// level, x0 and x'0 (inside the stick band, on its edge, anywhere, or raw
// bits), t_a, and a replayed list of level switches with increasing times,
// each to another level. A flag overrides one value with raw bits and lets
// the switch list be invalid, for the validation. What the CLI's checks
// accept (validate(sweep_spec), validate(model_initial_state, belt),
// validate_level_switches: replay.cpp) is simulated by simulate_model with
// given_level_switches and a small event bound. The only error allowed is
// the work bound. Invariants:
//   - episodes tile [0, t_a]: first start 0, each start the previous end,
//     last end t_a, none of zero length, stick and slip alternate;
//   - every stick starts at x' = v (its stick_onset, or the initial state)
//     with |k x + c v| <= mu_s m g (+ rounding), and every stick piece stays
//     in that band at x' = v;
//   - every time, position, velocity finite; pieces continue each other
//     (x' exactly, x up to the contact's clamp);
//   - R in [0, 1], the level fractions sum to 1;
//   - energy, piece by piece (motion_piece): a slip piece moves against its
//     friction (sigma (v dt - dx) >= 0), an undamped slip conserves
//     E - sigma mu_k m g x, a damped one dissipates (>= 0); and over the run
//     the belt's work (computed here from the pieces: v (k x + c v) over the
//     sticks, sigma mu_k m g v over the slips) equals the friction and
//     damping dissipation the realization_observer reports (friction_power,
//     damping_power times t_a) plus E(t_a) - E(0), within a relative
//     tolerance of the energy turnover.
// Where the lane engine applies (detail::runs_in_lanes: undamped, two
// levels; not the paper's model, which fuzz_simulator covers), the decoded
// sweep_spec's first realizations through the lane engine
// (trace_realizations_lanes) must equal simulate_model with the Markov belt
// (simulate_family_realization) bit for bit, episode by episode and event by
// event, and simulate_block must give the same bytes with either engine
// (sweep_engine::reference runs simulate_block_reference).
// The inputs of faults it found are in the corpus (known-*: the two found
// at omega a_s / |v| ~ 1e52 are now refused by validate()). FUZZ_TRACE=1
// prints what an input decodes to and every event, episode and piece.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "fuzz_common.hpp"
#include "stickslip/detail/fast_block.hpp"
#include "stickslip/error.hpp"
#include "stickslip/model/model_realization.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/statistics.hpp"
#include "stickslip/sweep.hpp"

namespace {

using namespace stickslip;

constexpr std::int64_t max_events = 2000;
// The lane engine's comparisons run 3 realizations through a whole SIMD
// batch and whole blocks through both engines, 60 % of the time per input
// with the bound above; a realization's branches all occur within its first
// few hundred events, so they use a lower bound (both engines the same one:
// hitting it is still compared).
constexpr std::int64_t lane_max_events = 400;
constexpr double rel = 1e-9;  // relative rounding tolerance of the invariants
// FUZZ_TRACE=1: print the model, the switches, every event, episode and piece
// (to read a crash input).
const bool trace = std::getenv("FUZZ_TRACE") != nullptr;

struct byte_source {
  const std::uint8_t* p;
  std::size_t n;
  std::uint8_t u8() {
    if (n == 0) return 0;
    --n;
    return *p++;
  }
  std::uint16_t u16() { return static_cast<std::uint16_t>(u8() | (u8() << 8)); }
  double unit() { return u16() / 65535.0; }
  double log_uniform(double lo, double hi) { return lo * std::pow(hi / lo, unit()); }
  double raw() {
    double d = 0;
    if (n >= 8) {
      std::memcpy(&d, p, 8);
      p += 8;
      n -= 8;
    }
    return d;
  }
};

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}
bool same(const episode& a, const episode& b) {
  return a.kind == b.kind && same_bits(a.start, b.start) && same_bits(a.end, b.end) &&
         same_bits(a.position_at_start, b.position_at_start) &&
         same_bits(a.belt_velocity, b.belt_velocity) && a.censored == b.censored &&
         same_bits(a.switches_before, b.switches_before);
}
bool same(const event& a, const event& b) {
  return a.kind == b.kind && same_bits(a.time, b.time) && same_bits(a.position, b.position) &&
         same_bits(a.velocity, b.velocity) && same_bits(a.belt_velocity, b.belt_velocity);
}
bool same(const event_counts& a, const event_counts& b) {
  return a.belt_switches == b.belt_switches && a.stick_onsets == b.stick_onsets &&
         a.stick_breaks == b.stick_breaks && a.slip_reversals == b.slip_reversals &&
         same_bits(a.switch_time_sum, b.switch_time_sum);
}

struct recorder : observer_base {
  std::vector<episode> episodes;
  std::vector<event> events;
  void on_event(const event& e) { events.push_back(e); }
  void on_episode(const episode& e) { episodes.push_back(e); }
};

// realization_observer plus the invariants, checked as the engine reports.
struct checker : realization_observer {
  const oscillator_model& m;
  const model_initial_state& ic;
  double F, as, ak;       // mu_k m g, a_s, a_k
  double last_end = 0.0;  // of the last episode
  int episodes = 0;
  mode last_kind = mode::stick;
  event onset{};  // the last stick_onset
  bool have_onset = false;
  event last_event{};
  bool have_event = false;
  bool have_piece = false;
  bool last_slip_at_rest = false;  // the last piece: a slip that ended at x' = v
  double last_slip_dx = 0.0;       // and how far it moved
  double x = 0, z = 0;             // end state of the last piece
  double belt_work = 0, turnover = 0;

  checker(const model_parameters& p, const oscillator_model& model, const model_initial_state& s)
      : realization_observer(p),
        m(model),
        ic(s),
        F(model.kinetic_friction * model.mass * model.gravity),
        as(model.static_band_half_width()),
        ak(model.kinetic_offset()) {}

  double energy(double x1, double z1) const {
    return 0.5 * m.mass * z1 * z1 + 0.5 * m.stiffness * x1 * x1;
  }
  // |k x + c v| <= mu_s m g, up to rounding.
  bool in_band(double x1, double v) const {
    const double f = m.stiffness * x1 + m.damping * v;
    const double cap = m.static_friction * m.mass * m.gravity;
    return std::abs(f) <= cap + rel * (std::abs(m.stiffness * x1) + std::abs(m.damping * v) + cap);
  }

  void on_event(const event& e) {
    if (trace)
      std::fprintf(stderr, "EVENT %s t %.17g x %.17g z %.17g v %.17g\n", to_string(e.kind), e.time,
                   e.position, e.velocity, e.belt_velocity);
    FUZZ_CHECK(std::isfinite(e.time) && std::isfinite(e.position) && std::isfinite(e.velocity) &&
                   std::isfinite(e.belt_velocity),
               "event at t = %g: x = %g, x' = %g, v = %g", e.time, e.position, e.velocity,
               e.belt_velocity);
    FUZZ_CHECK(e.time >= 0 && e.time <= m.window, "event at t = %g outside [0, %g]", e.time,
               m.window);
    if (e.kind == event_kind::stick_onset) {
      FUZZ_CHECK(e.velocity == e.belt_velocity,
                 "stick onset at t = %.17g with x' = %.17g != v = %.17g", e.time, e.velocity,
                 e.belt_velocity);
      FUZZ_CHECK(
          in_band(e.position, e.belt_velocity),
          "stick onset at t = %.17g outside the band: |k x + c v| = %.17g > mu_s m g = %.17g",
          e.time, std::abs(m.stiffness * e.position + m.damping * e.belt_velocity),
          m.static_friction * m.mass * m.gravity);
      onset = e;
      have_onset = true;
    }
    // A stick shorter than the resolution of t is a grazing touch: no onset
    // and break at one time (tests/regression/test_stick_shorter_than_time_resolution.cpp).
    FUZZ_CHECK(!(have_event && e.time == last_event.time && e.kind == event_kind::stick_break &&
                 last_event.kind == event_kind::stick_onset),
               "a stick of no length at t = %.17g (an onset and a break at one time)", e.time);
    last_event = e;
    have_event = true;
    realization_observer::on_event(e);
  }

  void on_segment(const segment& s) {
    FUZZ_CHECK(std::isfinite(s.start) && std::isfinite(s.end) && s.end >= s.start &&
                   std::isfinite(s.position) && std::isfinite(s.velocity),
               "segment [%g, %g] x = %g x' = %g", s.start, s.end, s.position, s.velocity);
  }

  void on_episode(const episode& e) {
    if (trace)
      std::fprintf(stderr, "EPISODE %s [%.17g, %.17g] x %.17g v %.17g\n", to_string(e.kind),
                   e.start, e.end, e.position_at_start, e.belt_velocity);
    FUZZ_CHECK(std::isfinite(e.start) && std::isfinite(e.end) && std::isfinite(e.position_at_start),
               "episode [%g, %g] x = %g", e.start, e.end, e.position_at_start);
    FUZZ_CHECK(e.start == last_end, "episode %d starts at %.17g, the one before ended at %.17g",
               episodes, e.start, last_end);
    FUZZ_CHECK(e.end > e.start, "episode %d [%.17g, %.17g] has no length", episodes, e.start,
               e.end);
    // A slip shorter than the resolution of t would leave two sticks next to
    // each other. validate() refuses belts slower than omega a_s / 1e12,
    // where this target found such slips (at omega a_s / |v| ~ 1e52).
    FUZZ_CHECK(episodes == 0 || e.kind != last_kind, "episodes %d and %d are both %s",
               episodes - 1, episodes, to_string(e.kind));
    FUZZ_CHECK(e.end <= m.window, "episode ends at %.17g after t_a = %.17g", e.end, m.window);
    if (e.kind == mode::stick) {
      if (!(have_onset && onset.time == e.start)) {  // a stick from the initial state
        FUZZ_CHECK(e.start == 0.0 && episodes == 0,
                   "stick episode at t = %.17g without a stick onset there", e.start);
        FUZZ_CHECK(ic.velocity == m.belt.levels[ic.level],
                   "initial stick with x' = %.17g != v = %.17g", ic.velocity,
                   m.belt.levels[ic.level]);
        FUZZ_CHECK(in_band(ic.position, ic.velocity), "initial stick outside the band");
        FUZZ_CHECK(e.position_at_start == ic.position, "initial stick at x = %.17g, not x0 = %.17g",
                   e.position_at_start, ic.position);
      } else {
        FUZZ_CHECK(
            e.position_at_start == onset.position && e.belt_velocity == onset.belt_velocity,
            "stick episode at t = %.17g: x = %.17g, v = %.17g; its onset: x = %.17g, v = %.17g",
            e.start, e.position_at_start, e.belt_velocity, onset.position, onset.belt_velocity);
      }
    }
    last_end = e.end;
    last_kind = e.kind;
    ++episodes;
    realization_observer::on_episode(e);
  }

  void on_piece(const motion_piece& p) {
    if (trace)
      std::fprintf(stderr,
                   "PIECE %s lvl %zu dt %.17g x %.17g->%.17g z %.17g->%.17g v %.17g sig %g\n",
                   to_string(p.kind), p.level, p.duration, p.start_position, p.end_position,
                   p.start_velocity, p.end_velocity, p.belt_velocity, p.sigma);
    const double x0 = p.start_position, x1 = p.end_position, z0 = p.start_velocity,
                 z1 = p.end_velocity, v = p.belt_velocity, d = p.duration;
    FUZZ_CHECK(std::isfinite(x0) && std::isfinite(x1) && std::isfinite(z0) && std::isfinite(z1) &&
                   std::isfinite(d) && d >= 0.0,
               "piece: x %g -> %g, x' %g -> %g, dt %g", x0, x1, z0, z1, d);
    FUZZ_CHECK(p.level < m.belt.level_count() && m.belt.levels[p.level] == v,
               "piece at level %zu with v = %g", p.level, v);
    const double px = have_piece ? x : ic.position, pz = have_piece ? z : ic.velocity;
    FUZZ_CHECK(z0 == pz, "piece starts at x' = %.17g, the state before has x' = %.17g", z0, pz);
    // A contact (a slip ending at x' = v) clamps x into the band (observer.hpp:
    // the next piece starts from the resolved state), by no more than that
    // slip moved; elsewhere x continues. (This target found damped slips
    // leaving x' = v with almost no relative acceleration, e.g. from the edge
    // with mu_s a few ulps above mu_k, that "returned" ~1e-10 s later while
    // x' had not left v by a representable amount; the clamp put x back on
    // the edge while the belt moved on. Fixed: damped_oscillator::returned.)
    const double tol_x = rel * (as + std::abs(px));
    const bool contact = have_piece && last_slip_at_rest;
    FUZZ_CHECK(std::abs(x0 - px) <= (contact ? last_slip_dx : 0.0) + tol_x,
               "piece starts at x = %.17g, the state before has x = %.17g", x0, px);
    const double e0 = energy(x0, z0), e1 = energy(x1, z1);
    if (p.kind == mode::stick) {
      FUZZ_CHECK(z0 == v && z1 == v && p.sigma == 0.0,
                 "stick piece with x' %.17g -> %.17g at v = %.17g", z0, z1, v);
      FUZZ_CHECK(in_band(x0, v) && in_band(x1, v), "stick piece x %.17g -> %.17g leaves the band",
                 x0, x1);
      // (d is a difference of times up to t_a: its rounding moves v d too)
      FUZZ_CHECK(std::abs(x1 - (x0 + v * d)) <=
                     rel * (std::abs(x0) + std::abs(v * d) + as) + 1e-15 * std::abs(v) * m.window,
                 "stick piece moves %.17g in %.17g s at v = %.17g", x1 - x0, d, v);
      const double wb = v * (m.stiffness * (x0 * d + 0.5 * v * d * d) + m.damping * v * d);
      belt_work += wb;
      turnover += std::abs(wb) + m.damping * v * v * d + e0 + e1;
    } else {
      FUZZ_CHECK(p.sigma == 1.0 || p.sigma == -1.0, "slip piece with sigma = %g", p.sigma);
      const double travel = p.sigma * (v * d - (x1 - x0));  // int |v - x'| dt
      const bool against = travel < -rel * (std::abs(v * d) + std::abs(x0) + std::abs(x1) + as) -
                                        1e-15 * std::abs(v) * m.window;
      // A damped slip that missed its return to x' = v would run on to its
      // centre x = sigma a_k against its friction (found by this target: on
      // long horizons, fixed, tests/regression/test_damped_root_on_a_long_horizon.cpp;
      // at omega a_s / |v| ~ 1e52, now refused by validate()).
      FUZZ_CHECK(!against, "slip piece against its friction: sigma = %g, v dt = %.17g, dx = %.17g",
                 p.sigma, v * d, x1 - x0);
      const double friction_work = p.sigma * F * (x1 - x0);  // on the mass
      const double scale = e0 + e1 + F * (std::abs(x0) + std::abs(x1) + ak);
      const double dissipated = friction_work - (e1 - e0);  // c int x'^2 dt
      if (m.damping == 0.0) {
        FUZZ_CHECK(std::abs(dissipated) <= rel * scale,
                   "undamped slip piece changes E - sigma F x by %.17g (scale %.17g)", dissipated,
                   scale);
      } else {
        FUZZ_CHECK(dissipated >= -rel * scale,
                   "damped slip piece gains %.17g of energy (scale %.17g)", -dissipated, scale);
      }
      const double wb = p.sigma * F * v * d;
      belt_work += wb;
      turnover += std::abs(wb) + F * std::abs(v * d - (x1 - x0)) + scale;
    }
    x = x1;
    z = z1;
    last_slip_at_rest = p.kind == mode::slip && z1 == v;
    last_slip_dx = std::abs(x1 - x0);
    have_piece = true;
    realization_observer::on_piece(p);
  }
};

// The lane engine against simulate_model, realization by realization.
void compare_lanes(const sweep_spec& s) {
  const model_parameters p = point_parameters(s, 0);
  const family_point fp(p, stream_key(s, p));
  constexpr std::uint64_t n = 3;
  std::vector<recorder> ref(n);
  std::vector<event_counts> counts(n);
  bool ref_bound = false;
  for (std::uint64_t r = 0; r < n; ++r) {
    const auto start = draw_model_initial_state(fp, s.initial, s.seed, r);
    try {
      counts[r] = simulate_family_realization(fp, start, s.seed, r, s.max_events, ref[r]);
    } catch (const error& e) {
      FUZZ_CHECK(e.code() == exit_code::work_bound, "unexpected error: %s", e.what());
      ref_bound = true;
    }
  }
  const auto reruns = detail::lane_reference_reruns();
  std::vector<detail::realization_trace> lanes;
  try {
    lanes = detail::trace_realizations_lanes(s, 0, 0, n);
  } catch (const error& e) {
    FUZZ_CHECK(e.code() == exit_code::work_bound, "unexpected error: %s", e.what());
    FUZZ_CHECK(ref_bound, "the lane engine hit the work bound, simulate_model did not: %s",
               e.what());
    return;
  }
  FUZZ_CHECK(!ref_bound, "simulate_model hit the work bound, the lane engine did not");
  FUZZ_CHECK(detail::lane_reference_reruns() == reruns, "the lane engine gave up on a realization");
  FUZZ_CHECK(lanes.size() == n, "%zu traces", lanes.size());
  for (std::uint64_t r = 0; r < n; ++r) {
    const auto& a = ref[r];
    const auto& b = lanes[r];
    FUZZ_CHECK(same(counts[r], b.counts), "realization %llu: event counts differ",
               static_cast<unsigned long long>(r));
    FUZZ_CHECK(a.episodes.size() == b.episodes.size(), "realization %llu: %zu vs %zu episodes",
               static_cast<unsigned long long>(r), a.episodes.size(), b.episodes.size());
    for (std::size_t i = 0; i < a.episodes.size(); ++i)
      FUZZ_CHECK(same(a.episodes[i], b.episodes[i]),
                 "realization %llu episode %zu: [%.17g, %.17g] vs [%.17g, %.17g]",
                 static_cast<unsigned long long>(r), i, a.episodes[i].start, a.episodes[i].end,
                 b.episodes[i].start, b.episodes[i].end);
    FUZZ_CHECK(a.events.size() == b.events.size(), "realization %llu: %zu vs %zu events",
               static_cast<unsigned long long>(r), a.events.size(), b.events.size());
    for (std::size_t i = 0; i < a.events.size(); ++i)
      FUZZ_CHECK(same(a.events[i], b.events[i]),
                 "realization %llu event %zu (%s at %.17g vs %s at %.17g)",
                 static_cast<unsigned long long>(r), i, to_string(a.events[i].kind),
                 a.events[i].time, to_string(b.events[i].kind), b.events[i].time);
  }
  // Whole blocks, every statistic (this target found the lanes booking a
  // piece's time by the sign of v instead of its level; fixed).
  std::string fast, reference;
  try {
    fast = serialize(work_unit{}, simulate_block(s, work_unit{}));
  } catch (const error& e) {
    FUZZ_CHECK(e.code() == exit_code::work_bound, "unexpected error: %s", e.what());
  }
  try {
    sweep_spec r = s;  // the reference engine: simulate_block_reference
    r.engine = sweep_engine::reference;
    reference = serialize(work_unit{}, simulate_block(r, work_unit{}));
  } catch (const error& e) {
    FUZZ_CHECK(e.code() == exit_code::work_bound, "unexpected error: %s", e.what());
  }
  FUZZ_CHECK(fast == reference, "simulate_block: fast and reference engines disagree");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  byte_source in{data, size};
  const std::uint8_t flags = in.u8();
  const bool raw_override = flags & 0x80, loose_switches = flags & 0x40;

  model_parameters p;
  p.mass = in.u8() % 4 == 0 ? 1.0 : in.log_uniform(1e-2, 1e2);
  p.stiffness = in.u8() % 4 == 0 ? 4.0 : in.log_uniform(1e-2, 1e3);
  p.gravity = in.u8() % 2 == 0 ? 9.81 : in.log_uniform(0.1, 100.0);
  const double mu_k = in.log_uniform(0.05, 10.0);
  double mu_s = mu_k;
  switch (in.u8() % 4) {
    case 2:
      mu_s = mu_k * in.log_uniform(1.0, 4.0);
      break;
    case 3:
      mu_s = std::nextafter(mu_k, 100.0);
      break;
    default:
      break;  // mu_s = mu_k
  }
  p.friction_coefficient = mu_k;
  p.kinetic_friction = mu_k;
  p.static_friction = mu_s;
  const double critical = 2.0 * std::sqrt(p.stiffness * p.mass);
  switch (in.u8() % 5) {
    case 2:
      p.damping = critical * in.log_uniform(1e-3, 0.999);
      break;   // under-damped
    case 3: {  // critical, or next to it
      const int ulps = static_cast<int>(in.u8() % 5) - 2;
      p.damping = critical;
      for (int i = 0; i < std::abs(ulps); ++i)
        p.damping = std::nextafter(p.damping, ulps > 0 ? 1e300 : 0.0);
      break;
    }
    case 4:
      p.damping = critical * in.log_uniform(1.001, 100.0);
      break;  // over-damped
    default:
      p.damping = 0.0;
  }
  const std::size_t n = 2 + in.u8() % 4;
  std::vector<double> levels;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t sel = in.u8();
    if (sel % 8 == 0) {
      levels.push_back(0.0);  // a resting level
    } else if (sel % 8 == 1 && i > 0) {
      levels.push_back(-levels.back());  // a symmetric pair
    } else {
      levels.push_back((sel & 0x80 ? -1.0 : 1.0) * in.log_uniform(0.01, 10.0));
    }
  }
  p.belt_levels = levels;
  p.switch_rate = in.log_uniform(0.01, 10.0);
  const std::uint8_t belt_sel = in.u8();
  if (n == 2 && belt_sel % 3 == 0) {
    // lambda: both levels left at switch_rate
  } else if (n == 2 && belt_sel % 3 == 1) {
    const double r1 = in.log_uniform(0.01, 10.0);
    p.belt_rates = {r1, belt_sel & 0x80 ? r1 : in.log_uniform(0.01, 10.0)};
  } else {
    std::vector<double> q(n * n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      double sum = 0.0;
      for (std::size_t j = 0; j < n; ++j) {
        if (i == j) continue;
        q[i * n + j] = in.u8() % 4 == 0 ? 0.0 : in.log_uniform(0.01, 10.0);
        sum += q[i * n + j];
      }
      q[i * n + i] = -sum;
    }
    p.belt_generator = q;
  }
  p.window = in.log_uniform(0.1, 100.0);

  // The start: level, x0, x'0 (around the band of the start level).
  model_initial_state start;
  start.level = in.u8() % n;
  const double v0 = levels[start.level];
  const double as = p.mu_s() * p.mass * p.gravity / p.stiffness;
  const double b0 = -p.damping * v0 / p.stiffness;
  double vmax = 0.0;
  for (double v : levels) vmax = std::max(vmax, std::abs(v));
  switch (in.u8() % 4) {
    case 0:
      start.position = b0 + (2.0 * in.unit() - 1.0) * as, start.velocity = v0;
      break;
    case 1:
      start.position = b0 + (in.u8() % 2 ? as : -as), start.velocity = v0;
      break;
    case 2:
      start.position = (2.0 * in.unit() - 1.0) * 4.0 * as;
      start.velocity = (2.0 * in.unit() - 1.0) * 4.0 * std::max(vmax, 0.1);
      break;
    default:
      start.position = in.raw(), start.velocity = in.raw();
  }

  sweep_spec spec;
  spec.seed = in.u16();
  spec.initial.belt_start = n == 2 ? static_cast<int>(in.u8() % 3) - 1 : 0;

  if (raw_override) {  // one value as raw bits, for the validation
    const std::uint8_t which = in.u8();
    const double r = in.raw();
    switch (which % 12) {
      case 0:
        p.mass = r;
        break;
      case 1:
        p.stiffness = r;
        break;
      case 2:
        p.gravity = r;
        break;
      case 3:
        p.kinetic_friction = r;
        break;
      case 4:
        p.static_friction = r;
        break;
      case 5:
        p.damping = r;
        break;
      case 6:
        p.belt_levels[which / 12 % n] = r;
        break;
      case 7:
        p.switch_rate = r;
        break;
      case 8:
        p.window = r;
        break;
      case 9:
        if (!p.belt_rates.empty()) p.belt_rates[which / 12 % 2] = r;
        if (!p.belt_generator.empty()) p.belt_generator[which / 12 % (n * n)] = r;
        break;
      case 10:
        start.position = r;
        break;
      default:
        start.velocity = r;
    }
  }

  // The replayed switches: increasing times, each to another level.
  std::vector<level_switch> switches;
  double t = 0.0;
  std::size_t level = start.level;
  while (in.n >= 3 && switches.size() < 64) {
    const double u = in.unit();
    const std::uint8_t l = in.u8();
    t += loose_switches || u > 0 ? p.window * 1.2 * u * u * u : p.window * 1e-9;
    level = loose_switches ? l % n : (level + 1 + l % (n - 1)) % n;
    switches.push_back({t, level});
  }

  // The CLI's checks (replay.cpp: replay_reference).
  spec.base = p;
  spec.realizations = 3;
  spec.block_size = 3;
  spec.max_events = max_events;
  spec.histograms.bins = 4;
  try {
    validate(spec);
  } catch (const error&) {
    return 0;
  }
  const family_point fp(p, stream_key(spec, p));
  try {
    validate(start, fp.model.belt);
    validate_level_switches(switches, n, start.level);
  } catch (const error&) {
    return 0;
  }
  FUZZ_CHECK(fp.model.static_friction >= fp.model.kinetic_friction && fp.model.damping >= 0.0,
             "validation accepted mu_s = %g < mu_k = %g or c = %g", fp.model.static_friction,
             fp.model.kinetic_friction, fp.model.damping);

  if (trace) {
    const auto& M = fp.model;
    std::fprintf(stderr,
                 "MODEL m %.17g k %.17g g %.17g c %.17g mu_s %.17g mu_k %.17g ta %.17g as %.17g "
                 "ak %.17g\n",
                 M.mass, M.stiffness, M.gravity, M.damping, M.static_friction, M.kinetic_friction,
                 M.window, M.static_band_half_width(), M.kinetic_offset());
    for (double v : M.belt.levels) std::fprintf(stderr, "LEVEL %.17g\n", v);
    std::fprintf(stderr, "START x %.17g z %.17g level %zu\n", start.position, start.velocity,
                 start.level);
    for (auto& w : switches) std::fprintf(stderr, "SWITCH %.17g -> %zu\n", w.time, w.level);
  }
  checker obs(p, fp.model, start);
  obs.reset(0, start.position, start.velocity, 1);
  given_level_switches sw(switches);
  bool finished = false;
  try {
    (void)simulate_model(fp.model, start, sw, obs, max_events);
    finished = true;
  } catch (const error& e) {
    FUZZ_CHECK(e.code() == exit_code::work_bound, "unexpected error: %s", e.what());
  }
  if (finished) {
    obs.finish();
    const double ta = fp.model.window;
    FUZZ_CHECK(obs.episodes > 0 && obs.last_end == ta,
               "last episode ends at %.17g, not t_a = %.17g", obs.last_end, ta);
    const auto& rec = obs.record();
    FUZZ_CHECK(rec.stick_fraction >= 0 && rec.stick_fraction <= 1 + 1e-12,
               "stick fraction %.17g outside [0, 1]", rec.stick_fraction);
    double fractions = 0.0;
    for (double f : obs.samples().level_fractions) {
      FUZZ_CHECK(f >= 0 && f <= 1 + 1e-12, "level fraction %.17g", f);
      fractions += f;
    }
    FUZZ_CHECK(std::abs(fractions - 1.0) <= 1e-9, "level fractions sum to %.17g", fractions);
    const double friction = rec.friction_power * ta, damping = rec.damping_power * ta;
    FUZZ_CHECK(std::isfinite(friction) && friction >= 0, "friction dissipation %g", friction);
    FUZZ_CHECK(fp.model.damping > 0 || damping == 0, "damping dissipation %g without damping",
               damping);
    const double de = obs.energy(obs.x, obs.z) - obs.energy(start.position, start.velocity);
    const double turnover = obs.turnover + friction + std::abs(damping) + std::abs(de) +
                            obs.energy(start.position, start.velocity);
    FUZZ_CHECK(damping >= -rel * turnover, "damping dissipation %.17g < 0 (turnover %.17g)",
               damping, turnover);
    const double imbalance = obs.belt_work - friction - damping - de;
    FUZZ_CHECK(
        std::abs(imbalance) <= rel * turnover,
        "energy: belt work %.17g != friction %.17g + damping %.17g + dE %.17g (turnover %.17g)",
        obs.belt_work, friction, damping, de, turnover);
  }

  if (detail::runs_in_lanes(p) && !p.is_paper_model()) {
    sweep_spec lane_spec = spec;
    lane_spec.max_events = lane_max_events;
    compare_lanes(lane_spec);
  }
  return 0;
}
