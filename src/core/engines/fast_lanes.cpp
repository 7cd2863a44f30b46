// The lane engine behind simulate_block (sweep_engine::fast): several
// realizations of one work unit advance together, one event each per round,
// so that their serial dependency chains overlap and their transcendentals
// are evaluated as one SIMD vector (Highway: 4 doubles with AVX2, 8 with
// AVX-512, 2 with SSE4, 1 with the SCALAR baseline). This file is compiled once per Highway
// target (foreach_target.h re-includes it) and the entry points at its end
// dispatch at run time to the target of the CPU, the same target the scalar
// kernels of fast_math.hpp use.
//
// Each round, for every lane (= one realization in flight):
//   1. scalar: start a realization in an idle lane;
//   2. vector: both the stick and the slip outcome of every lane: the stick's
//      end (band edge, switch or t_a), the slip's root by atan (mirror
//      return) or atan2 (general root), and the sin and cos of the phase
//      w * (min(t_switch, t_a) - t) when some slip ends at a switch or at t_a,
//      with the same kernels (engines/fast_math_simd.hpp) that the scalar
//      integrator calls one lane at a time through fast_math.hpp;
//   3. vector: finish both outcomes exactly as `simulate` does, count the
//      events, and leave one bit per lane for each piece of bookkeeping
//      (close an episode, draw the next switch, finish the realization);
//   4. scalar: that bookkeeping, only for the lanes whose bit is set.
// In the common round (every lane busy) step 1
// is a vector step as well: count the event, check the max_events bound.
// The closed-form steps of an event (stick end, slip orbit, rotation, root
// position and angle arguments, mirror return) and its decisions (the
// contact at x' = v: decide_contact; the phase run to the root:
// root_angle_from_raw, reversal_arc_from_alpha) are the templates of
// event_physics.hpp that `simulate` (include/stickslip/integrator.hpp) and
// `simulate_model` (model/model_engine.hpp) call with doubles, here called
// with vectors and masks; the scalar paths call the scalar decisions
// themselves (physics::mode_at_start, resolve_contact, leave_edge). What
// the vector step still writes in mask form is the next state of each
// branch (which of the computed outcomes a lane takes), held to `simulate`
// by tests/unit/test_fast_path_episodes.cpp, every episode and event field
// by bit pattern.
//
// Lanes take realizations in order; a finished realization waits in a small
// ring until all earlier ones are finished, and is then added to the block's
// statistics by point_statistics::add in realization order, exactly as the
// reference engine adds it: every accumulator update happens in the same order.
// A realization that exceeds max_events makes the whole block rerun on the
// reference engine (simulate_model), which throws the error the reference
// throws.
//
// The same engine runs the undamped two-level models of the family
// (detail::runs_in_lanes; lane_engine<..., Family = true>) with
// simulate_model's physics (model/model_engine.hpp with c = 0) and
// markov_level_switches' draws (two_level_switch_times): the point's
// constants (band a_s, slip centre a_k, the two levels, what a departure
// from the outward edge leaves, whether a switch out of a stick mirrors)
// are broadcast once per step; per lane, |v| times the stick and the other
// level is a blend on v == v1. After a stick break with mu_s > mu_k the slip
// starts at x' = v and runs the reversal arc. In both instances a slip that
// starts at a reversal runs in the vector step (its atan2 shares the step's
// Atan; run one lane at a time it took a quarter of the time at mu = 0.5,
// docs/performance.md). The paper's instance (Family = false) compiles none
// of the family's branches. tests/unit/test_fast_path_family.cpp holds
// the family instance to simulate_model, every episode and event field.
//
// The engine is a template over what it does with a finished realization
// (a collector: statistics for the sweep, or a full trace for the tests) and
// so over the observer type: it gives the observer every episode with every
// field, and every event when the observer takes events (observes_events;
// realization_observer does not, so the sweep builds none), and refuses an
// observer of segments at compile time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engines/fast_lanes.cpp"  // src/core is on the core's include path
#include <hwy/foreach_target.h>  // must come before highway.h

#include <hwy/highway.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <type_traits>
#include <vector>

#include "stickslip/belt_switches.hpp"
#include "stickslip/burn_in.hpp"
#include "stickslip/event_physics.hpp"
#include "stickslip/detail/fast_block.hpp"
#include "stickslip/engines/point_engine.hpp"
#include "stickslip/fast_math.hpp"
#include "engines/fast_math_simd.hpp"
#include "stickslip/error.hpp"
#include "stickslip/initial_conditions.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/model/model_realization.hpp"
#include "stickslip/observer.hpp"
#include "stickslip/random_stream.hpp"
#include "stickslip/statistics.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::detail {
// Defined once, after the per-target code (HWY_ONCE).
void count_lane_reference_rerun() noexcept;
}  // namespace stickslip::detail

HWY_BEFORE_NAMESPACE();
namespace stickslip::detail {
namespace HWY_NAMESPACE {
namespace {
namespace hn = hwy::HWY_NAMESPACE;
namespace sk = simd::HWY_NAMESPACE;
using sk::dtag;

using vec = hn::Vec<dtag>;
constexpr std::size_t N = hn::MaxLanes(dtag());  // doubles per vector: 8 AVX3, 4 AVX2, 2 SSE4, 1 SCALAR
constexpr int groups = 4;                          // independent vectors per round
constexpr int lanes = groups * static_cast<int>(N);  // realizations in flight per thread
static_assert(lanes <= 32, "lane bit masks are 32 bits");
static_assert(N <= 8, "lane_bits reads one byte of mask bits per vector");
constexpr std::size_t ring = 64;  // finished realizations waiting for their turn
constexpr double inf = std::numeric_limits<double>::infinity();

struct bound_exceeded {};

// The closed-form steps and decisions of event_physics.hpp, instantiated for
// this target's vectors and masks (see event_physics_steps.inl); the scalar
// paths call physics:: (stickslip::detail::physics), the same text for
// doubles, and its scalar-only decisions (mode_at_start, leave_edge).
namespace vphysics {
#include "stickslip/event_physics_steps.inl"
}  // namespace vphysics

// The draw kernel of this target (the Philox rounds of a chunk's blocks,
// the conversion to doubles, the log), inlined into the switch draws of the
// lanes: the same bits as fm::log_uniforms, which dispatches to this very
// target.
struct target_log_uniforms {
  void operator()(random_stream& rs, double* HWY_RESTRICT w, std::size_t blocks) const noexcept {
    sk::log_uniforms(rs, w, blocks);
  }
};

// A switch source's refill compiled for this target: its refill_with (the
// Philox rounds, the conversion to doubles, the log, the waits) is inlined
// here. The same bits: the integer rounds and the exact conversions do not
// depend on the target or on the vector width, the log is this target's
// either way, and the waits are the same products (no multiply-add fused:
// -ffp-contract=off, src/core/CMakeLists.txt); the source sums them as it
// hands the times out.
template <class SwitchSource>
HWY_NOINLINE void refill_for_target(SwitchSource& source) noexcept {
  target_log_uniforms draw;
  source.refill_with(draw);
}

// Event codes of one round (what the vector step decided for a lane).
enum : int {
  ev_none = 0,       // lane idle this round
  ev_stick_ta,       // stick runs to t_a: realization ends
  ev_stick_switch,   // belt switch ends the stick (mirror slip follows)
  ev_stick_break,    // stick breaks at the band edge (grazing orbit follows)
  ev_slip_ta,        // slip runs to t_a: realization ends
  ev_slip_switch,    // belt switch during the slip
  ev_slip_onset,     // x' = v inside the band: a stick starts
  ev_slip_edge,      // x' = v exactly on the outward edge: grazing, no stick
  ev_slip_reversal,  // x' = v outside the band: slip reversal
};

// Collectors: what the engine does with the realizations it runs.
//   using observer = ...;                      the per-realization observer
//   observer make() const;                     a fresh one (pool of the ring)
//   void begin(observer&, r, ic);              before realization r
//   void end(observer&, counts);               after its last episode
//   void deliver(r, observer&);                in realization order
//   void fallback();                           max_events exceeded: redo on the
//                                              model's reference engine

// The sweep's statistics: realization_observer, then point_statistics::add
// in realization order into the block of each realization.
template <class Observer>
class statistics_collector {
 public:
  using observer = Observer;
  statistics_collector(const sweep_spec& s, const model_parameters& p,
                       std::vector<block_result>& outs, std::size_t point,
                       std::uint64_t first_block)
      : s_(s), p_(p), outs_(outs), point_(point), first_block_(first_block) {}
  [[nodiscard]] observer make() const {
    observer o(p_, s_.family_statistics, s_.burn_in, &s_.observe_times);
    if constexpr (observer::keeps_durations) o.reserve_episodes(p_);
    return o;
  }
  void begin(observer& o, std::uint64_t r, const initial_conditions& ic) const {
    o.reset(r, ic.position, ic.velocity, ic.belt_direction);
  }
  void end(observer& o, const event_counts& counts) const {
    o.finish();
    o.record().events = counts;
  }
  void deliver(std::uint64_t r, observer& o) {
    auto& out = outs_[r / s_.block_size - first_block_];
    out.stats.add(o.samples(), p_.window);
    if (s_.keep_records) out.records.push_back(o.record());
  }
  void fallback() {
    // Rerun on the reference engine, which throws what the reference throws.
    count_lane_reference_rerun();
    for (std::uint64_t b = 0; b < outs_.size(); ++b)
      outs_[b] = simulate_block_reference(s_, work_unit{point_, first_block_ + b});
  }

 private:
  const sweep_spec& s_;
  const model_parameters& p_;
  std::vector<block_result>& outs_;
  std::size_t point_;
  std::uint64_t first_block_;
};

// Every episode and event of every realization (the tests' view).
struct trace_observer : observer_base {
  realization_trace trace;
  void on_episode(const episode& e) { trace.episodes.push_back(e); }
  void on_event(const event& e) { trace.events.push_back(e); }
};
static_assert(observes_events<trace_observer> && !observes_segments<trace_observer>);
static_assert(observes_pieces<realization_observer> && !observes_pieces<paper_statistics_observer>,
              "the lane engine sums pieces of motion only with the family statistics");
static_assert(!observes_events<realization_observer> && !observes_segments<realization_observer>,
              "the lane engine builds events only for observers that take them");

class trace_collector {
 public:
  using observer = trace_observer;
  trace_collector(const sweep_spec& s, const model_parameters& p, std::uint64_t first,
                  std::vector<realization_trace>& out)
      : s_(s), p_(p), first_(first), out_(out) {}
  [[nodiscard]] observer make() const { return {}; }
  void begin(observer& o, std::uint64_t, const initial_conditions&) const { o.trace = {}; }
  void end(observer& o, const event_counts& counts) const { o.trace.counts = counts; }
  void deliver(std::uint64_t r, observer& o) { out_[r - first_] = std::move(o.trace); }
  void fallback() {
    // Rerun on the reference engine (simulate_model, engines/point_engine.hpp).
    count_lane_reference_rerun();
    count_engine_run(point_engine::reference);
    const family_point fp(p_, stream_key(s_, p_));
    for (std::size_t i = 0; i < out_.size(); ++i) {
      trace_observer o;
      const std::uint64_t r = first_ + i;
      const auto start = draw_model_initial_state(fp, s_.initial, s_.seed, r);
      o.trace.counts = simulate_family_realization(fp, start, s_.seed, r, s_.max_events, o);
      out_[i] = std::move(o.trace);
    }
  }

 private:
  const sweep_spec& s_;
  const model_parameters& p_;
  std::uint64_t first_;
  std::vector<realization_trace>& out_;
};

// Family = false: the paper's model (poisson_switches, levels +-V, mu_s =
// mu_k). Family = true: an undamped two-level belt, levels v1, v2 (either may
// be 0: a stick there lasts until the next switch, and its band has no
// outward edge), mu_s >= mu_k (simulate_model's physics, model/model_engine.hpp, with
// c = 0): the stick band |x| <= a_s, the slip centre sigma a_k, the switch
// times of two_level_switch_times, and after a stick break (or a touch of the
// outward edge) with mu_s > mu_k a slip that starts at x' = v and returns by
// the reversal arc (after_reversal, in the vector step), with mu_s = mu_k the
// paper's grazing orbit. A belt switch goes to the other level; a stick
// ended by one leaves a mirror slip only when v2 = -v1 and the stick is on
// the inner side of the new slip's centre (|x| < a_k; model_engine.hpp).
template <class Collector, bool Family>
class lane_engine {
  using observer = typename Collector::observer;
  using switch_source = std::conditional_t<Family, two_level_switch_times, poisson_switches>;
  static_assert(!observes_segments<observer>,
                "the lane engine reports no segments: observe them with simulate()");
  static constexpr bool with_events = observes_events<observer>;
  // An observer of pieces of motion gets their sums instead (set_paper_sums):
  // the time at +V and at -V and the slips' relative travel |v dt - dx|,
  // accumulated here piece by piece in simulate()'s order, so the same bits.
  static constexpr bool with_pieces = observes_pieces<observer>;
  // episode::switches_before and event_counts::switch_time_sum (observer.hpp)
  static constexpr bool with_causal = wants_causal_score<observer>;
  // An observer with a state sampler (realization_observer::
  // sampler_to_fill): with observe times, the round that holds a lane's next
  // observe time writes the round's start state at it in the sampler's
  // states (queue_observe_times), and they are evaluated in place when the
  // realization ends (evaluate_observed).
  static constexpr bool samples_states = requires(observer& o) { o.sampler_to_fill(); };
  // An observer that takes the tallies of the closed episodes instead of
  // each one (realization_observer::set_closed_episode_tallies: the means of
  // a `sweep --statistics R`): the vector step sums them, lane-wise in the
  // observer's order, so the same bits; side_effects closes only the rare
  // slip ended by a contact at a switch (contact_at_switch), in scalar form.
  // Not with a burn-in (tallying_), which cuts episodes at T. The last,
  // censored episode then carries only its kind and times: an observer of
  // events, pieces or the causal score must take every episode.
  static constexpr bool tallies_episodes = takes_episode_tallies<observer>;
  static_assert(!tallies_episodes || (!with_causal && !with_events && !with_pieces),
                "an observer that takes episode tallies reads no other episode field");

 public:
  // Realizations [first, last) of one point, handed to `collect` in order.
  // family: the point's family_point (Family), else nullptr.
  lane_engine(const sweep_spec& s, const model_parameters& p, const family_point* family,
              Collector& collect, std::uint64_t first, std::uint64_t last)
      : s_(s), p_(p), family_(family), collect_(collect), first_(first), last_(last),
        next_(first), flush_(first),
        a_(p.band_half_width()), ak_(a_), w_(p.natural_frequency()), V_(p.belt_speed),
        ta_(p.window), key_(stream_key(s, p)), burn_in_(p, with_pieces ? s.burn_in : 0.0),
        observing_(samples_states && !s.observe_times.empty()),
        tallying_(tallies_episodes && s.burn_in == 0.0),
        max_steps_(static_cast<double>(s.max_events)) {
    if constexpr (Family) {
      const oscillator_model& m = family_->model;
      a_ = m.static_band_half_width();
      ak_ = m.kinetic_offset();
      w_ = m.natural_frequency();
      ta_ = m.window;
      v1_ = m.belt.levels[0];
      v2_ = m.belt.levels[1];
      V_ = 0.0;  // unused: |v| per lane
      equal_friction_ = m.static_friction == m.kinetic_friction;
      opposite_levels_ = v2_ == -v1_;
      key_ = family_->key;
    }
    ta_up_ = std::nextafter(ta_, inf);
    const std::size_t n = std::min<std::size_t>(ring, last - first);
    pool_.reserve(n);
    for (std::size_t i = 0; i < n; ++i) pool_.push_back(collect_.make());
    done_.assign(n, 0);
    if constexpr (samples_states)
      if (observing_) {
        // one point: every observer's sampler has the same mass, stiffness
        // and levels (two: the lanes run two-level belts only)
        const state_sampler& sm = pool_.front().sampler();
        observed_mass_ = sm.mass(), observed_stiffness_ = sm.stiffness();
        if (sm.levels().size() != 2)
          throw error(exit_code::internal, "the lane engine samples two belt levels only");
        observed_levels_[0] = sm.levels()[0], observed_levels_[1] = sm.levels()[1];
      }
    for (int l = 0; l < lanes; ++l) {
      time_[l] = position_[l] = velocity_[l] = next_switch_time_[l] = 0.0;
      belt_velocity_[l] = slip_centre_sign_[l] = 1.0;
      sticking_[l] = grazing_[l] = mirror_[l] = after_reversal_[l] = steps_this_round_[l] = 0.0;
      step_event_[l] = ev_none;
    }
  }

  void run() {
    const dtag d;
    while (prepare_round(d)) {
      vector_step(d);
      side_effects();
    }
  }

 private:
  // ---- realization start and end ----
  void start(int l, std::uint64_t r) {
    initial_conditions ic;
    double v;
    if constexpr (Family) {
      // draw_model_initial_state and markov_level_switches, as simulate_block_reference
      const model_initial_state st = draw_model_initial_state(*family_, s_.initial, s_.seed, r);
      ic = initial_conditions{st.position, st.velocity, recorded_belt_start(st.level, 2)};
      switch_times_[l] = two_level_switch_times(family_->chain.mean_wait(st.level),
                                      family_->chain.mean_wait(1 - st.level), s_.seed, key_, r);
      v = st.level == 0 ? v1_ : v2_;
    } else {
      ic = draw_initial_conditions(s_.initial, s_.seed, key_, r);
      switch_times_[l] = poisson_switches(p_.switch_rate, s_.seed, key_, r);
      v = ic.belt_direction >= 0 ? V_ : -V_;
    }
    realization_[l] = r;
    observer_[l] = &pool_[(r - first_) % pool_.size()];
    collect_.begin(*observer_[l], r, ic);
    if constexpr (samples_states) {
      observe_cursor_[l] = 0;
      next_observe_time_[l] = observing_ ? s_.observe_times.front() : inf;
      if (observing_) observed_[l] = &observer_[l]->sampler_to_fill().states_to_fill();
    }
    active_[l] = true;
    busy_[l] = 1.0;
    belt_switches_[l] = stick_onsets_[l] = stick_breaks_[l] = slip_reversals_[l] = 0.0;
    steps_[l] = 0.0;
    time_at_first_level_[l] = time_at_second_level_[l] = relative_travel_[l] = 0.0;
    // simulate(): initial state and mode.
    const double a = a_;
    const double x = ic.position, z = ic.velocity;
    time_[l] = 0.0, position_[l] = x, velocity_[l] = z, belt_velocity_[l] = v;
    next_switch_time_[l] = next_switch(l);
    const auto m = physics::mode_at_start(x, z, v, a);
    const bool stick = m.kind == mode::stick;
    slip_centre_sign_[l] = m.sigma;
    sticking_[l] = stick ? 1.0 : 0.0;
    // a start on the outward edge leaves it (physics::leave_edge)
    const auto departure = physics::leave_edge(v, !Family || equal_friction_);
    grazing_[l] = m.on_outward_edge && departure.grazing ? 1.0 : 0.0;
    after_reversal_[l] =
        m.after_reversal || (m.on_outward_edge && departure.after_reversal) ? 1.0 : 0.0;
    mirror_[l] = 0.0;
    episode_kind_[l] = stick ? mode::stick : mode::slip;
    episode_start_[l] = 0.0;
    episode_position_[l] = x;
    episode_belt_velocity_[l] = v;
    episode_switches_before_[l] = 0.0;
    switch_time_sum_[l] = 0.0;
    tally_sticks_[l] = tally_slips_[l] = tally_stick_time_[l] = 0.0;
    tally_first_start_[l] = tally_first_duration_[l] = -1.0;  // -1: no stick yet
  }

  HWY_INLINE double next_switch(int l) noexcept {
    return switch_times_[l].next_refilled_by([](auto& source) { refill_for_target(source); });
  }

  void finish_realization(int l) {
    if constexpr (samples_states)
      if (observing_) {
        // every time queued (the rounds tile [0, t_a]) and evaluated
        // (side_effects): the sampler counts them, so the observer hands
        // its states over (realization_observer::samples)
        if (observe_cursor_[l] != s_.observe_times.size())
          throw error(exit_code::internal, "the lane engine missed an observe time");
        evaluate_observed(dtag(), *observed_[l]);
        observer_[l]->sampler_to_fill().mark_sampled();
      }
    if constexpr (tallies_episodes)
      if (tallying_) {
        observer_[l]->set_closed_episode_tallies(tally_sticks_[l], tally_slips_[l],
                                                 tally_stick_time_[l], tally_first_start_[l],
                                                 tally_first_duration_[l]);
        // the vector step does not keep episode_kind_: the lane's mode is the episode's
        episode_kind_[l] = sticking_[l] > 0.5 ? mode::stick : mode::slip;
      }
    observer_[l]->on_episode(episode{episode_kind_[l], episode_start_[l], ta_, episode_position_[l],
                                     episode_belt_velocity_[l], true, episode_switches_before_[l]});
    if constexpr (with_pieces)
      observer_[l]->set_paper_sums(time_at_first_level_[l], time_at_second_level_[l],
                                   relative_travel_[l]);
    collect_.end(*observer_[l],
                 event_counts{static_cast<std::uint64_t>(belt_switches_[l]),
                              static_cast<std::uint64_t>(stick_onsets_[l]),
                              static_cast<std::uint64_t>(stick_breaks_[l]),
                              static_cast<std::uint64_t>(slip_reversals_[l]), switch_time_sum_[l]});
    active_[l] = false;
    busy_[l] = 0.0;
    done_[(realization_[l] - first_) % pool_.size()] = 1;
    flush();
  }

  // Hands the finished realizations at the head of the order over, in order.
  void flush() {
    while (flush_ < last_) {
      const std::size_t slot = (flush_ - first_) % pool_.size();
      if (!done_[slot]) return;
      collect_.deliver(flush_, pool_[slot]);
      done_[slot] = 0;
      ++flush_;
    }
  }

  // simulate()'s close_episode: the next episode starts with the state just
  // after the event (position_, belt_velocity_ are already updated when this is called).
  void close_episode(int l, double when, mode next_mode) {
    if (tallying_) return tally_closed_episode(l, when, next_mode);
    if (when > episode_start_[l])
      observer_[l]->on_episode(episode{episode_kind_[l], episode_start_[l], when,
                                       episode_position_[l], episode_belt_velocity_[l], false,
                                       episode_switches_before_[l]});
    episode_kind_[l] = next_mode;
    episode_start_[l] = when;
    if constexpr (with_causal) episode_switches_before_[l] = belt_switches_[l];
    episode_position_[l] = position_[l];
    episode_belt_velocity_[l] = belt_velocity_[l];
  }

  // close_episode's tallies (tallies_episodes), as the vector step sums
  // them: the closed episode is the other kind than the next one.
  void tally_closed_episode(int l, double when, mode next_mode) {
    const double start = episode_start_[l];
    if (when > start) {
      const double length = when - start;
      if (next_mode == mode::slip) {  // a stick closes
        if (tally_first_start_[l] < 0.0) tally_first_start_[l] = start, tally_first_duration_[l] = length;
        tally_stick_time_[l] += length;
        tally_sticks_[l] += 1.0;
      } else if (tally_sticks_[l] > 0.0) {
        tally_slips_[l] += 1.0;  // slips after the first stick
      }
    }
    episode_start_[l] = when;
  }

  // simulate()'s on_event, with the state just after the event.
  void emit(int l, event_kind kind) {
    if constexpr (with_events)
      observer_[l]->on_event(event{kind, time_[l], position_[l], velocity_[l], belt_velocity_[l]});
  }

  void count_step(int l) {
    if ((steps_[l] += 1.0) > max_steps_) throw bound_exceeded{};
  }
  // Before the vector step. Every busy lane counts its event (and the
  // max_events bound is checked) in vector form; the scalar prepare() runs
  // only for idle lanes and for lanes whose slip starts at a reversal.
  // Returns whether any lane runs this round.
  bool prepare_round(dtag d) {
    const vec half = hn::Set(d, 0.5), one = hn::Set(d, 1.0), zero = hn::Zero(d);
    auto over = hn::FirstN(d, 0);
    std::uint32_t special = 0;
    for (int k = 0; k < groups; ++k) {
      const std::size_t j = static_cast<std::size_t>(k) * N;
      const auto act = hn::Gt(hn::Load(d, busy_ + j), half);
      const vec st = hn::Add(hn::Load(d, steps_ + j), hn::IfThenElseZero(act, one));
      hn::Store(st, d, steps_ + j);
      hn::Store(hn::IfThenElse(act, one, zero), d, steps_this_round_ + j);
      over = hn::Or(over, hn::And(act, hn::Gt(st, hn::Set(d, max_steps_))));
      // idle lanes (the vector step runs every busy lane, also a slip that
      // starts at a reversal)
      const auto sp = hn::Not(act);
      special |= lane_bits(d, sp) << static_cast<unsigned>(j);
    }
    if (!hn::AllFalse(d, over)) throw bound_exceeded{};
    for (unsigned m = special; m != 0; m &= m - 1) prepare(std::countr_zero(m));
    auto any = hn::FirstN(d, 0);
    for (int k = 0; k < groups; ++k)
      any = hn::Or(any,
                   hn::Gt(hn::Load(d, steps_this_round_ + static_cast<std::size_t>(k) * N), half));
    return !hn::AllFalse(d, any);
  }

  // Start a realization in an idle lane (counting its first event).
  // Returns whether the lane runs.
  bool prepare(int l) {
    steps_this_round_[l] = 0.0;
    if (!active_[l]) {
      if (next_ >= last_ || next_ - flush_ >= pool_.size()) return false;
      start(l, next_++);
    }
    count_step(l);
    steps_this_round_[l] = 1.0;
    return true;
  }

  // simulate()'s contact_at (physics::resolve_contact): a stick, a grazing
  // touch on the outward edge, or a reversal (counted as a slip reversal at a
  // root; simulate() counts none when a belt switch lands exactly on x' = v:
  // contact_at_switch).
  void root_contact(int l, double from_sigma, bool count_reversal = true) {
    mirror_[l] = 0.0;
    const auto c =
        physics::resolve_contact(time_[l], position_[l], from_sigma, belt_velocity_[l], a_);
    position_[l] = c.x;
    switch (c.outcome) {
      case physics::contact_outcome::reversal:
        slip_centre_sign_[l] = c.sigma;
        after_reversal_[l] = 1.0;
        if (count_reversal) {
          slip_reversals_[l] += 1.0;
          emit(l, event_kind::slip_reversal);
        }
        return;
      case physics::contact_outcome::grazing: {  // zero-length stick: leave the edge
        const auto departure = physics::leave_edge(belt_velocity_[l], !Family || equal_friction_);
        slip_centre_sign_[l] = departure.sigma;
        (departure.grazing ? grazing_ : after_reversal_)[l] = 1.0;
        return;
      }
      case physics::contact_outcome::stick:
        sticking_[l] = 1.0;
        stick_onsets_[l] += 1.0;
        emit(l, event_kind::stick_onset);
        close_episode(l, time_[l], mode::stick);
        return;
    }
  }
  // simulate(): a belt switch during a slip landed exactly on x' = v.
  void contact_at_switch(int l) { root_contact(l, position_[l] > 0 ? -1.0 : 1.0, false); }

  // ---- the vector step: one event for every lane ----
  // Every expression is simulate()'s, operation for operation, lane-wise.
  // The lanes form K independent vectors; each phase is written for all K
  // before the next phase starts, so that the K dependency chains (sqrt, the
  // divisions, Atan, Sin/Cos) are in flight together instead of one after
  // the other.
  HWY_NOINLINE void vector_step(dtag d) {  // kept apart: run() stays small enough to inline its helpers
    using hn::Add, hn::Sub, hn::Mul, hn::Div, hn::Min, hn::Max, hn::IfThenElse, hn::Set;
    using mask = hn::Mask<dtag>;
    constexpr int K = groups;
#define K_LOOP for (int k = 0; k < K; ++k)
    const vec A = Set(d, a_), W = Set(d, w_), VV = Set(d, V_), TA = Set(d, ta_);
    const vec TA_UP = Set(d, ta_up_);  // the next double after t_a (observe times)
    const vec zero = hn::Zero(d), one = Set(d, 1.0), m_one = Set(d, -1.0), half = Set(d, 0.5);
    const vec mA = hn::Neg(A);
    // Family: the slip centre sigma a_k (the paper: sigma a, the band's edge),
    // the two levels, and what an outward-edge departure leaves (EDGE_GRAZES:
    // the grazing orbit, with mu_s = mu_k; EDGE_SLIPS_AWAY: a slip after a
    // reversal, otherwise), whether a switch out of a stick can leave a mirror
    // slip (SWITCH_MIRRORS: opposite levels, v2 = -v1). 0/1 per lane.
    const vec AK = Family ? Set(d, ak_) : A;
    const vec V1 = Set(d, v1_), V2 = Set(d, v2_);
    const vec EDGE_GRAZES = Family && !equal_friction_ ? zero : one;
    const vec EDGE_SLIPS_AWAY = Family && !equal_friction_ ? one : zero;
    const vec SWITCH_MIRRORS = Family && !opposite_levels_ ? zero : one;
    const auto set = [&](double c) { return Set(d, c); };
    const physics::decision_constants<double>& sc = physics::scalar_constants;
    const vphysics::decision_constants<vec> DC{
        set(sc.zero), set(sc.one),    set(sc.minus_one),     set(sc.two), set(sc.pi),
        set(sc.two_pi), set(sc.minus_half_pi), set(sc.near), set(sc.tiny)};
    const auto any_lane = [&](mask m) { return !hn::AllFalse(d, m); };
    vec t[K], x[K], z[K], v[K], t_switch[K], sig[K], s[K], t_edge[K], sq[K];
    vphysics::slip_orbit<vec> o[K];
    // the lane's mode (sticking_, grazing_, mirror_, after_reversal_), whether
    // it runs this round, how its stick would end (at t_a or at a switch), and
    // whether its slip has a root
    mask sticking[K], grazing[K], mirror[K], run[K], stick_to_ta[K], stick_to_switch[K],
        has_root[K], after_reversal[K];
    K_LOOP {
      const std::size_t j = static_cast<std::size_t>(k) * N;
      t[k] = hn::Load(d, time_ + j), x[k] = hn::Load(d, position_ + j),
      z[k] = hn::Load(d, velocity_ + j);
      v[k] = hn::Load(d, belt_velocity_ + j), t_switch[k] = hn::Load(d, next_switch_time_ + j),
      sig[k] = hn::Load(d, slip_centre_sign_ + j);
      sticking[k] = hn::Gt(hn::Load(d, sticking_ + j), half);
      grazing[k] = hn::Gt(hn::Load(d, grazing_ + j), half);
      mirror[k] = hn::Gt(hn::Load(d, mirror_ + j), half);
      run[k] = hn::Gt(hn::Load(d, steps_this_round_ + j), half);
      after_reversal[k] = hn::Gt(hn::Load(d, after_reversal_ + j), half);
    }
    K_LOOP {
      s[k] = IfThenElse(hn::Gt(v[k], zero), one, m_one);
      // stick
      t_edge[k] = vphysics::stick_edge_time(t[k], A, s[k], x[k], Family ? hn::Abs(v[k]) : VV);
      if constexpr (Family)  // a stick at a level 0 lasts until the next switch
        t_edge[k] = IfThenElse(hn::Eq(v[k], zero), Set(d, inf), t_edge[k]);
      stick_to_ta[k] = hn::Ge(Min(t_edge[k], t_switch[k]), TA);
      stick_to_switch[k] = hn::AndNot(stick_to_ta[k], hn::Le(t_switch[k], t_edge[k]));
      // slip
      o[k] = vphysics::orbit_of(x[k], z[k], v[k], sig[k], AK, W);
      has_root[k] = hn::AndNot(hn::Or(sticking[k], grazing[k]), hn::Gt(o[k].disc, zero));
      sq[k] = hn::Sqrt(hn::IfThenElseZero(has_root[k], o[k].disc));
    }
    vec r[K], ay[K], ax[K], at[K];
    K_LOOP {
      r[k] = vphysics::root_ordinate(sig[k], sq[k]);
      const auto q = vphysics::root_angle_arguments(o[k].wy, z[k], v[k], r[k]);
      ay[k] = q.y;
      ax[k] = q.x;
      {  // reversal_arc_angle: alpha = atan2(|w y|, v)
        ay[k] = IfThenElse(after_reversal[k], hn::Abs(o[k].wy), ay[k]);
        ax[k] = IfThenElse(after_reversal[k], v[k], ax[k]);
      }
      // one division for both kinds of root: |wy| / |z| (mirror return) or
      // atan2_ratio's min(|ay|, |ax|) / max(|ay|, |ax|)
      vec num, den;
      sk::atan2_ratio_operands(ay[k], ax[k], num, den);
      const vec ratio = Div(IfThenElse(mirror[k], hn::Abs(o[k].wy), num),
                            IfThenElse(mirror[k], hn::Abs(z[k]), den));
      at[k] = IfThenElse(has_root[k], ratio, zero);
    }
    K_LOOP at[k] = sk::atan(d, at[k]);
    vec t_root[K];
    mask slip_to_ta[K], slip_to_switch[K], slip_to_root[K];
    bool any_rotation = false;
    K_LOOP {
      const vec raw = sk::atan2_finish(d, at[k], ay[k], ax[k]);
      const vec dtheta_general =
          vphysics::root_angle_from_raw(raw, o[k].wy, v[k], sig[k], r[k], DC);
      const vec dtheta_mirror = vphysics::mirror_return_from_atan(at[k], DC.pi, DC.two);
      vec dtheta = IfThenElse(mirror[k], dtheta_mirror, dtheta_general);
      dtheta = IfThenElse(after_reversal[k], vphysics::reversal_arc_from_alpha(raw, sig[k], DC),
                          dtheta);
      t_root[k] = IfThenElse(has_root[k], vphysics::time_after_phase(t[k], dtheta, W), Set(d, inf));
      slip_to_ta[k] = hn::Ge(Min(t_root[k], t_switch[k]), TA);
      slip_to_switch[k] = hn::AndNot(slip_to_ta[k], hn::Le(t_switch[k], t_root[k]));
      slip_to_root[k] = hn::Not(hn::Or(slip_to_ta[k], slip_to_switch[k]));
      any_rotation |=
          !hn::AllFalse(d, hn::AndNot(sticking[k], hn::AndNot(slip_to_root[k], run[k])));
    }
    std::uint32_t took_switch = 0, close_stick = 0, close_slip = 0, finished = 0;
    std::uint32_t observe_lanes = 0, observe_sticking = 0;  // lanes holding an observe time
    // slip: the rotation to a switch or to t_a
    vec x_rotated[K], z_rotated[K];
    K_LOOP x_rotated[k] = x[k], z_rotated[k] = z[k];
    if (any_rotation) {
      vec u[K], sn[K], cs[K];
      K_LOOP {
        u[k] = Mul(W, Sub(Min(t_switch[k], TA), t[k]));
        if (!hn::AllFalse(d, hn::Gt(hn::Abs(u[k]), Set(d, fm::max_direct_phase)))) {
          HWY_ALIGN double ph[hn::MaxLanes(dtag())];
          hn::Store(u[k], d, ph);
          for (std::size_t i = 0; i < N; ++i) ph[i] = fm::reduce_phase(ph[i]);
          u[k] = hn::Load(d, ph);
        }
      }
      K_LOOP sn[k] = sk::sin(d, u[k]);
      K_LOOP cs[k] = sk::cos(d, u[k]);
      K_LOOP {
        x_rotated[k] = vphysics::rotated_position(o[k], z[k], W, cs[k], sn[k]);
        z_rotated[k] = vphysics::rotated_velocity(o[k], z[k], cs[k], sn[k]);
      }
    }
    K_LOOP {
      const std::size_t j = static_cast<std::size_t>(k) * N;
      // slip: the root, and its resolution
      const vec x_root =
          IfThenElse(mirror[k], x[k], vphysics::root_position(o[k], sig[k], sq[k], W));
      // the contact at the root (physics::resolve_contact, lane-wise)
      const auto contact =
          vphysics::decide_contact<Family>(t_root[k], x_root, sig[k], v[k], A,
                                           vphysics::band_at_zero{},
                                           hn::AndNot(sticking[k], slip_to_root[k]), DC, any_lane);
      const mask onset = contact.stick, edge = contact.grazing;
      const mask slip_switch = slip_to_switch[k], slip_root = slip_to_root[k];

      // new state, slip lanes
      const vec v_after_switch = Family ? IfThenElse(hn::Eq(v[k], V1), V2, V1) : hn::Neg(v[k]);
      vec nx = IfThenElse(slip_root, contact.x, x_rotated[k]);
      vec nz = IfThenElse(slip_root, v[k], z_rotated[k]);
      vec nt = IfThenElse(slip_root, t_root[k], IfThenElse(slip_switch, t_switch[k], TA));
      vec nv = IfThenElse(slip_switch, v_after_switch, v[k]);
      vec nsig = IfThenElse(
          slip_switch, IfThenElse(hn::Gt(v_after_switch, z_rotated[k]), one, m_one),
          IfThenElse(slip_root, contact.sigma, sig[k]));
      vec next_sticking = IfThenElse(hn::And(slip_root, onset), one, zero);
      vec next_grazing =
          IfThenElse(slip_switch, zero,
                     IfThenElse(hn::And(slip_root, edge), EDGE_GRAZES,
                                IfThenElse(grazing[k], one, zero)));
      vec next_mirror =
          IfThenElse(hn::Or(slip_switch, slip_root), zero, IfThenElse(mirror[k], one, zero));
      vec next_after_reversal = IfThenElse(hn::And(contact.reversal, slip_root), one, zero);
      if constexpr (Family)
        next_after_reversal =
            IfThenElse(hn::And(slip_root, edge), EDGE_SLIPS_AWAY, next_after_reversal);
      vec code = IfThenElse(slip_to_ta[k], Set(d, ev_slip_ta),
                 IfThenElse(slip_switch, Set(d, ev_slip_switch),
                 IfThenElse(onset, Set(d, ev_slip_onset),
                 IfThenElse(edge, Set(d, ev_slip_edge), Set(d, ev_slip_reversal)))));

      // stick lanes
      const mask in_stick = sticking[k], stick_ta = stick_to_ta[k],
                 stick_switch = stick_to_switch[k];
      const mask stick_break = hn::Not(hn::Or(stick_ta, stick_switch));
      const vec x_at_switch =
          Min(Max(vphysics::stick_position(x[k], v[k], t[k], t_switch[k]), mA), A);
      nx = IfThenElse(in_stick,
                      IfThenElse(stick_switch, x_at_switch,
                                 IfThenElse(stick_break, Mul(s[k], A), x[k])),
                      nx);
      nz = IfThenElse(in_stick, IfThenElse(stick_ta, z[k], v[k]), nz);
      nt = IfThenElse(in_stick,
                      IfThenElse(stick_switch, t_switch[k], IfThenElse(stick_break, t_edge[k], TA)),
                      nt);
      nv = IfThenElse(in_stick, IfThenElse(stick_switch, v_after_switch, v[k]), nv);
      // after a switch: sigma = sgn(v_new - old v) (the paper: -s)
      const vec sigma_after_switch =
          Family ? IfThenElse(hn::Gt(v_after_switch, v[k]), one, m_one) : hn::Neg(s[k]);
      nsig = IfThenElse(in_stick,
                        IfThenElse(stick_switch, sigma_after_switch,
                                   IfThenElse(stick_break, s[k], sig[k])),
                        nsig);
      next_sticking = IfThenElse(in_stick, IfThenElse(stick_ta, one, zero), next_sticking);
      next_grazing = IfThenElse(in_stick, IfThenElse(stick_break, EDGE_GRAZES, zero), next_grazing);
      // a mirror return only from the inner side of the new slip's centre
      // (simulate_model): sigma (x - sigma a_k) < 0; from the outer side
      // (a_k < |x| <= a_s, mu_s > mu_k) the general root, half a period on
      vec mirror_after_switch = SWITCH_MIRRORS;
      if constexpr (Family)
        mirror_after_switch = hn::IfThenElseZero(
            hn::Lt(Mul(sigma_after_switch, Sub(x_at_switch, Mul(sigma_after_switch, AK))), zero),
            SWITCH_MIRRORS);
      next_mirror =
          IfThenElse(in_stick, IfThenElse(stick_switch, mirror_after_switch, zero), next_mirror);
      next_after_reversal =
          IfThenElse(in_stick, Family ? IfThenElse(stick_break, EDGE_SLIPS_AWAY, zero) : zero,
                     next_after_reversal);
      code = IfThenElse(in_stick,
                        IfThenElse(stick_ta, Set(d, ev_stick_ta),
                                   IfThenElse(stick_switch, Set(d, ev_stick_switch),
                                              Set(d, ev_stick_break))),
                        code);

      // observe times (state_sampler.hpp): the round's segment [t, min(nt, t_a))
      // holds the lane's next observe time, or ends at t_a and t_a is one
      if constexpr (samples_states) {
        if (observing_) [[unlikely]] {
          // t_j < min(nt, t_a), or t_j <= t_a when the round reaches t_a:
          // t_j < the round's end, with t_a's end moved to the next double
          // (The lanes that hold one are kept and queued after the loop: a
          // call here made the loop save its vectors around it every round.)
          const vec end = IfThenElse(hn::Ge(nt, TA), TA_UP, nt);
          const mask holds = hn::And(run[k], hn::Lt(hn::Load(d, next_observe_time_ + j), end));
          if (!hn::AllFalse(d, holds)) [[unlikely]] {
            hn::Store(t[k], d, round_start_ + j), hn::Store(end, d, round_end_ + j);
            hn::Store(x[k], d, round_position_ + j), hn::Store(z[k], d, round_velocity_ + j);
            hn::Store(v[k], d, round_belt_velocity_ + j), hn::Store(o[k].c, d, round_centre_ + j);
            const unsigned shift = static_cast<unsigned>(j);
            observe_lanes |= lane_bits(d, holds) << shift;
            observe_sticking |= lane_bits(d, in_stick) << shift;
          }
        }
      }

      // the piece of motion of this round (simulate()'s piece(): from the
      // state at the start of the round to the unresolved end, x_root or the
      // rotated x): time at the level, and a slip's |v dt - dx|
      if constexpr (with_pieces) {
        const vec dt = Sub(nt, t[k]);
        const vec x_end = IfThenElse(slip_root, x_root, x_rotated[k]);
        const vec travel = hn::Abs(Sub(Mul(v[k], dt), Sub(x_end, x[k])));
        // time at the first level: v = v1 (the paper's first level is +V;
        // a family belt's levels may have any signs, e.g. 0.5 and 1)
        const mask up = Family ? hn::Eq(v[k], V1) : hn::Gt(v[k], zero);
        mask counts_piece = run[k];
        // A burn-in T (burn_in.hpp): whole pieces only from T on; a piece in
        // progress at T adds its part after T below (burn_in_cut, as the
        // observer does for the scalar engines).
        mask at_burn_in = hn::FirstN(d, 0);
        bool cut_at_burn_in = false;
        if (burn_in_.active()) [[unlikely]] {
          const vec T = Set(d, burn_in_.time());
          at_burn_in = hn::And(counts_piece, hn::And(hn::Lt(t[k], T), hn::Gt(nt, T)));
          cut_at_burn_in = !hn::AllFalse(d, at_burn_in);
          counts_piece = hn::And(counts_piece, hn::Ge(t[k], T));
        }
        hn::Store(
            Add(hn::Load(d, time_at_first_level_ + j), hn::IfThenElseZero(hn::And(counts_piece, up), dt)), d,
            time_at_first_level_ + j);
        hn::Store(Add(hn::Load(d, time_at_second_level_ + j),
                      hn::IfThenElseZero(hn::AndNot(up, counts_piece), dt)),
                  d, time_at_second_level_ + j);
        hn::Store(Add(hn::Load(d, relative_travel_ + j),
                      hn::IfThenElseZero(hn::AndNot(in_stick, counts_piece), travel)),
                  d, relative_travel_ + j);
        if (cut_at_burn_in) [[unlikely]]
          add_piece_after_burn_in(d, j, at_burn_in, in_stick, up, t[k], nt, x[k], x_end, z[k], v[k], sig[k]);
      }

      // idle lanes keep their state
      const mask runs = run[k];
      hn::Store(IfThenElse(runs, nt, t[k]), d, time_ + j);
      hn::Store(IfThenElse(runs, nx, x[k]), d, position_ + j);
      hn::Store(IfThenElse(runs, nz, z[k]), d, velocity_ + j);
      hn::Store(IfThenElse(runs, nv, v[k]), d, belt_velocity_ + j);
      hn::Store(IfThenElse(runs, nsig, sig[k]), d, slip_centre_sign_ + j);
      hn::Store(IfThenElse(runs, next_sticking, hn::Load(d, sticking_ + j)), d, sticking_ + j);
      hn::Store(IfThenElse(runs, next_grazing, hn::Load(d, grazing_ + j)), d, grazing_ + j);
      hn::Store(IfThenElse(runs, next_mirror, hn::Load(d, mirror_ + j)), d, mirror_ + j);
      hn::Store(IfThenElse(runs, next_after_reversal, hn::Load(d, after_reversal_ + j)), d,
                after_reversal_ + j);
      hn::Store(IfThenElse(runs, code, zero), d, step_event_ + j);
      // the bookkeeping after the round: event counts, and lane bits
      const vec round_event = IfThenElse(runs, code, zero);
      const mask is_stick_switch = hn::Eq(round_event, Set(d, ev_stick_switch));
      const mask is_slip_switch = hn::Eq(round_event, Set(d, ev_slip_switch));
      const mask is_stick_break = hn::Eq(round_event, Set(d, ev_stick_break));
      const mask is_stick_onset = hn::Eq(round_event, Set(d, ev_slip_onset));
      const mask is_switch = hn::Or(is_stick_switch, is_slip_switch);
      const mask closes_stick = hn::Or(is_stick_switch, is_stick_break);
      const mask ends_at_ta =
          hn::Or(hn::Eq(round_event, Set(d, ev_stick_ta)), hn::Eq(round_event, Set(d, ev_slip_ta)));
      hn::Store(Add(hn::Load(d, belt_switches_ + j), hn::IfThenElseZero(is_switch, one)), d,
                belt_switches_ + j);
      hn::Store(Add(hn::Load(d, stick_breaks_ + j), hn::IfThenElseZero(is_stick_break, one)), d,
                stick_breaks_ + j);
      hn::Store(Add(hn::Load(d, stick_onsets_ + j), hn::IfThenElseZero(is_stick_onset, one)), d,
                stick_onsets_ + j);
      hn::Store(Add(hn::Load(d, slip_reversals_ + j),
                    hn::IfThenElseZero(hn::Eq(round_event, Set(d, ev_slip_reversal)), one)),
                d, slip_reversals_ + j);
      if constexpr (tallies_episodes)
        if (tallying_) {  // tally_closed_episode, lane-wise
          const vec start = hn::Load(d, episode_start_ + j);
          const mask has_length = hn::Gt(nt, start);
          const vec length = Sub(nt, start);
          const mask stick = hn::And(closes_stick, has_length);
          const vec sticks = hn::Load(d, tally_sticks_ + j);
          const vec first_start = hn::Load(d, tally_first_start_ + j);
          const mask first = hn::And(stick, hn::Lt(first_start, zero));
          hn::Store(IfThenElse(first, start, first_start), d, tally_first_start_ + j);
          hn::Store(IfThenElse(first, length, hn::Load(d, tally_first_duration_ + j)), d,
                    tally_first_duration_ + j);
          hn::Store(Add(hn::Load(d, tally_stick_time_ + j), hn::IfThenElseZero(stick, length)), d,
                    tally_stick_time_ + j);
          hn::Store(Add(sticks, hn::IfThenElseZero(stick, one)), d, tally_sticks_ + j);
          const mask slip = hn::And(hn::And(is_stick_onset, has_length), hn::Gt(sticks, zero));
          hn::Store(Add(hn::Load(d, tally_slips_ + j), hn::IfThenElseZero(slip, one)), d,
                    tally_slips_ + j);
          hn::Store(IfThenElse(hn::Or(closes_stick, is_stick_onset), nt, start), d,
                    episode_start_ + j);
        }
      const unsigned shift = static_cast<unsigned>(j);
      took_switch |= lane_bits(d, is_switch) << shift;
      close_stick |= lane_bits(d, closes_stick) << shift;
      close_slip |= lane_bits(d, is_stick_onset) << shift;
      finished |= lane_bits(d, ends_at_ta) << shift;
    }
    took_switch_ = took_switch, close_stick_ = close_stick, close_slip_ = close_slip;
    finished_ = finished;
    if constexpr (samples_states)
      if (observe_lanes != 0) queue_observe_times(d, observe_lanes, observe_sticking);
#undef K_LOOP
  }

  // The part after the burn-in T of the pieces in progress at T (lanes
  // `at` of the vector at j): built as simulate() builds the piece, cut by
  // burn_in_cut::after (the observer's cut), its time and travel added as
  // realization_observer::add_piece adds them. A slip's end velocity is set
  // to v here, not the true x'(t_end): right for the time and travel the
  // lanes add, wrong for any energy; damped slips never run in the lanes.
  HWY_NOINLINE void add_piece_after_burn_in(dtag d, std::size_t j, hn::Mask<dtag> at,
                                            hn::Mask<dtag> stick, hn::Mask<dtag> up, vec t,
                                            vec t_end, vec x, vec x_end, vec z, vec v, vec sig) {
    HWY_ALIGN double ts[N], te[N], xs[N], xe[N], zs[N], vs[N], ss[N];
    hn::Store(t, d, ts), hn::Store(t_end, d, te), hn::Store(x, d, xs), hn::Store(x_end, d, xe);
    hn::Store(z, d, zs), hn::Store(v, d, vs), hn::Store(sig, d, ss);
    const auto stick_bits = lane_bits(d, stick), up_bits = lane_bits(d, up);
    for (std::uint32_t m = lane_bits(d, at); m != 0; m &= m - 1) {
      const auto i = static_cast<std::size_t>(std::countr_zero(m));
      const bool sticking = (stick_bits >> i) & 1u;
      const motion_piece whole{sticking ? mode::stick : mode::slip,
                               (up_bits >> i) & 1u ? std::size_t{0} : std::size_t{1},
                               te[i] - ts[i], xs[i], xe[i], sticking ? vs[i] : zs[i],
                               vs[i], vs[i], sticking ? 0.0 : ss[i], ts[i], te[i]};
      const motion_piece part = burn_in_.after(whole);
      (part.level == 0 ? time_at_first_level_ : time_at_second_level_)[j + i] += part.duration;
      if (!sticking) relative_travel_[j + i] += part.relative_travel();
    }
  }

  // The lanes `at` (bits) whose round [t, end) holds their next observe time
  // (end: the round's end, t_a's moved to the next double, so that
  // t_j < end; the round's start state in round_*): each time t_j the round
  // holds gets the round's start state, written in place in the lane's own
  // states at j (x, x', v and whether sticking where they belong; the start
  // time and the centre in the energy and level slots, which
  // evaluate_observed overwrites when the realization ends).
  HWY_NOINLINE void queue_observe_times(dtag, std::uint32_t at, std::uint32_t stick_bits) {
    if constexpr (samples_states) {
      const double* times = s_.observe_times.data();
      const std::size_t count = s_.observe_times.size();
      for (std::uint32_t m = at; m != 0; m &= m - 1) {
        const auto l = static_cast<std::size_t>(std::countr_zero(m));
        const double sticking = (stick_bits >> l) & 1u ? 1.0 : 0.0;
        const double end = round_end_[l];
        const double start = round_start_[l], x = round_position_[l], z = round_velocity_[l];
        const double v = round_belt_velocity_[l], centre = round_centre_[l];
        observed_states& o = *observed_[l];
        double *position = o.position(), *velocity = o.velocity(), *belt = o.belt_velocity();
        double *start_at = o.energy(), *centre_at = o.level(), *stick = o.sticking();
        std::size_t c = observe_cursor_[l];
        do {
          position[c] = x, velocity[c] = z, belt[c] = v;
          start_at[c] = start, centre_at[c] = centre, stick[c] = sticking;
        } while (++c < count && times[c] < end);
        observe_cursor_[l] = c;
        next_observe_time_[l] = c < count ? times[c] : inf;
      }
    }
  }

  // A finished realization's states at the observe times, from the start
  // states queue_observe_times left at each t_j: the state at t_j, as
  // evaluate() (episode.cpp) gives it for the segment simulate() and
  // simulate_model() would build for the round (a stick moves at v from x; a
  // slip rotates (w (x - c), x') about the centre c = sigma a_k by
  // w (t_j - t)), and the energy and level as state_sampler::record_next
  // gives them, with the vector forms of the same formulas and kernels: the
  // same bits, a vector of times at a time (each lane on its own: the
  // vectors' other lanes change nothing in it).
  HWY_NOINLINE void evaluate_observed(dtag d, observed_states& o) {
    if constexpr (samples_states) {
      const vec W = Set(d, w_), zero = hn::Zero(d), one = Set(d, 1.0);
      const vec half_m = Set(d, 0.5 * observed_mass_), half_k = Set(d, 0.5 * observed_stiffness_);
      const vec L0 = Set(d, observed_levels_[0]), L1 = Set(d, observed_levels_[1]);
      const double* times = s_.observe_times.data();
      const std::size_t n = o.size();
      double *position = o.position(), *velocity = o.velocity(), *belt = o.belt_velocity();
      double *start_at = o.energy(), *centre_at = o.level(), *stick = o.sticking();
      // One vector of times: the round start t, the time t_j, the start
      // state x, x', v, the centre and whether sticking; out: x, x', the
      // energy and the level at t_j.
      struct inputs {
        vec t, tj, x, z, v, centre, sticking;
      };
      auto load = [&](std::size_t j) {
        return inputs{hn::LoadU(d, start_at + j), hn::LoadU(d, times + j),
                      hn::LoadU(d, position + j), hn::LoadU(d, velocity + j),
                      hn::LoadU(d, belt + j),     hn::LoadU(d, centre_at + j),
                      hn::LoadU(d, stick + j)};
      };
      auto evaluate = [&](const inputs& in, vec out[4]) {
        const auto sticking = hn::Eq(in.sticking, one);
        vec xj = vphysics::stick_position(in.x, in.v, in.t, in.tj), zj = in.v;
        if (!hn::AllTrue(d, sticking)) {
          vec u = Mul(W, Sub(in.tj, in.t));
          if (!hn::AllFalse(d, hn::Gt(hn::Abs(u), Set(d, fm::max_direct_phase)))) {
            HWY_ALIGN double ph[N];
            hn::Store(u, d, ph);
            for (std::size_t i = 0; i < N; ++i) ph[i] = fm::reduce_phase(ph[i]);
            u = hn::Load(d, ph);
          }
          const vec sn = sk::sin(d, u), cs = sk::cos(d, u);
          const vec y = Sub(in.x, in.centre);
          const vphysics::slip_orbit<vec> orbit{in.centre, y, Mul(W, y), zero};
          xj = IfThenElse(sticking, xj, vphysics::rotated_position(orbit, in.z, W, cs, sn));
          zj = IfThenElse(sticking, zj, vphysics::rotated_velocity(orbit, in.z, cs, sn));
        }
        out[0] = xj, out[1] = zj;
        // record_next: m x'^2 / 2 + k x^2 / 2 as ((m / 2) x') x' + ((k / 2) x) x
        out[2] = hn::Add(Mul(Mul(half_m, zj), zj), Mul(Mul(half_k, xj), xj));
        out[3] = IfThenElse(hn::Eq(in.v, L0), zero, IfThenElse(hn::Eq(in.v, L1), one, Set(d, 2.0)));
      };
      double* const to[4] = {position, velocity, start_at, centre_at};
      const std::size_t whole = n - n % N;  // the times in whole vectors
      vec out[4];
      if (n < N) {  // fewer times than lanes: through a padded copy (a stick at t = 0)
        HWY_ALIGN double pad[7][N];
        const double* from[7] = {start_at, times, position, velocity, belt, centre_at, stick};
        for (std::size_t f = 0; f < 7; ++f) {
          std::fill_n(pad[f], N, f == 6 ? 1.0 : 0.0);
          std::copy_n(from[f], n, pad[f]);
        }
        evaluate(inputs{hn::Load(d, pad[0]), hn::Load(d, pad[1]), hn::Load(d, pad[2]),
                        hn::Load(d, pad[3]), hn::Load(d, pad[4]), hn::Load(d, pad[5]),
                        hn::Load(d, pad[6])},
                 out);
        HWY_ALIGN double kept[N];
        for (std::size_t f = 0; f < 4; ++f) {
          hn::Store(out[f], d, kept);
          std::copy_n(kept, n, to[f]);
        }
        return;
      }
      // The last, partial vector as the whole vector that ends at n: its
      // inputs read before the loop overwrites the times it shares with the
      // last whole vector, and only its last n % N lanes stored.
      std::optional<inputs> last;
      if (whole < n) last = load(n - N);
      for (std::size_t j = 0; j < whole; j += N) {
        evaluate(load(j), out);
        for (std::size_t f = 0; f < 4; ++f) hn::StoreU(out[f], d, to[f] + j);
      }
      if (last) {
        evaluate(*last, out);
        const auto tail = hn::Not(hn::FirstN(d, N - (n - whole)));
        for (std::size_t f = 0; f < 4; ++f) hn::BlendedStore(out[f], tail, d, to[f] + (n - N));
      }
    }
  }

  // ---- after the vector step: counts, episodes, switch draws ----
  // Lanes are grouped by what they have to do (bit masks), so that the
  // branches go per group, not per lane through an unpredictable 9-way jump.
  HWY_NOINLINE void side_effects() {  // apart: small enough to inline on_episode
    const std::uint32_t took_switch = took_switch_, close_stick = close_stick_,
                        close_slip = close_slip_, finished = finished_;
    if constexpr (with_events) emit_round_events();
    if (!tallying_) {  // else the vector step closed them
      for (unsigned m = close_stick; m != 0; m &= m - 1) {
        const int l = std::countr_zero(m);
        close_episode(l, time_[l], mode::slip);
      }
      for (unsigned m = close_slip; m != 0; m &= m - 1) {
        const int l = std::countr_zero(m);
        close_episode(l, time_[l], mode::stick);
      }
    }
    for (unsigned m = took_switch; m != 0; m &= m - 1) {
      const int l = std::countr_zero(m);
      if constexpr (with_causal)
        switch_time_sum_[l] += time_[l];  // the switch just taken, at time_ (simulate()'s order)
      next_switch_time_[l] = next_switch(l);
      if (velocity_[l] == belt_velocity_[l] && sticking_[l] == 0.0 &&
          static_cast<int>(step_event_[l]) == ev_slip_switch)
        contact_at_switch(l);
    }
    for (unsigned m = finished; m != 0; m &= m - 1) finish_realization(std::countr_zero(m));
  }

  // The events of the vector step, in simulate()'s order within each lane
  // (a contact at a switch emits its stick onset later, in side_effects' loop
  // over the lanes that took a switch).
  void emit_round_events() {
    for (int l = 0; l < lanes; ++l) {
      switch (static_cast<int>(step_event_[l])) {
        case ev_stick_switch:
        case ev_slip_switch: emit(l, event_kind::belt_switch); break;
        case ev_stick_break: emit(l, event_kind::stick_break); break;
        case ev_slip_onset: emit(l, event_kind::stick_onset); break;
        case ev_slip_reversal: emit(l, event_kind::slip_reversal); break;
        default: break;  // idle, t_a, or a grazing touch of the outward edge
      }
    }
  }

  static std::uint32_t lane_bits([[maybe_unused]] dtag d, hn::Mask<dtag> m) {
#if HWY_TARGET == HWY_AVX3 || HWY_TARGET == HWY_AVX3_DL
    return static_cast<std::uint32_t>(m.raw);  // the AVX-512 mask register itself
#else
    std::uint8_t b[8] = {};
    hn::StoreMaskBits(d, m, b);
    return b[0];
#endif
  }

  const sweep_spec& s_;
  const model_parameters& p_;
  const family_point* family_;
  Collector& collect_;
  std::uint64_t first_, last_, next_, flush_;
  double a_, ak_, w_, V_, ta_;  // a_: the stick band (a_s); ak_: the slip centre (a_k)
  double ta_up_ = 0.0;          // std::nextafter(ta_, inf), once: it cost 0.4 % of a sweep per round
  double v1_ = 1.0, v2_ = -1.0;  // Family: the two levels
  bool equal_friction_ = true;
  bool opposite_levels_ = true;  // v2 = -v1: a switch out of a stick can leave a mirror slip
  std::uint64_t key_;
  burn_in_cut burn_in_;  // sweep_spec::burn_in (only with pieces)
  bool observing_;       // observe times, and an observer that samples them
  bool tallying_;        // tallies_episodes, and no burn-in
  std::vector<observer> pool_;
  std::vector<unsigned char> done_;
  // Lane state, one array per variable (structure of arrays): the vector
  // step loads and stores whole vectors of it. The state (t, x, x', v) and
  // the next belt switch; sigma, the side of the slip centre sigma a_k.
  HWY_ALIGN double time_[lanes], position_[lanes], velocity_[lanes], belt_velocity_[lanes];
  HWY_ALIGN double next_switch_time_[lanes], slip_centre_sign_[lanes];
  // What the lane is doing, as 0/1 masks: sticking; leaving the band's
  // outward edge on the grazing orbit; a mirror slip after a switch out of a
  // stick; a slip that returns by the reversal arc (after_reversal).
  HWY_ALIGN double sticking_[lanes], grazing_[lanes], mirror_[lanes], after_reversal_[lanes];
  // 1 if the lane takes this round's vector step; the event that step found
  // (ev_*).
  HWY_ALIGN double steps_this_round_[lanes], step_event_[lanes];
  // Event counts and the events so far (the max_events bound), exact in
  // doubles up to 2^53; busy_: 1 while the lane runs a realization.
  HWY_ALIGN double belt_switches_[lanes] = {}, stick_onsets_[lanes] = {};
  HWY_ALIGN double stick_breaks_[lanes] = {}, slip_reversals_[lanes] = {};
  HWY_ALIGN double steps_[lanes] = {}, busy_[lanes] = {};
  // The sums of the pieces of motion (with_pieces): time at the first level
  // (+V), at the second (-V), and the slips' relative travel.
  HWY_ALIGN double time_at_first_level_[lanes] = {}, time_at_second_level_[lanes] = {};
  HWY_ALIGN double relative_travel_[lanes] = {};
  // The tallies of the closed episodes (tallies_episodes): sticks of
  // positive length, the slips after the first, the stick time, and the
  // first stick's start and length (-1: none yet).
  HWY_ALIGN double tally_sticks_[lanes] = {}, tally_slips_[lanes] = {};
  HWY_ALIGN double tally_stick_time_[lanes] = {}, tally_first_start_[lanes] = {};
  HWY_ALIGN double tally_first_duration_[lanes] = {};
  double max_steps_;
  // What the last vector step left to do, one bit per lane.
  std::uint32_t took_switch_ = 0, close_stick_ = 0, close_slip_ = 0, finished_ = 0;
  bool active_[lanes] = {};
  std::uint64_t realization_[lanes] = {};
  // The episode in progress: kind, start, and x, v at its start.
  HWY_ALIGN double episode_start_[lanes] = {};
  double episode_position_[lanes] = {};
  double episode_belt_velocity_[lanes] = {};
  double episode_switches_before_[lanes] = {};  // episode::switches_before
  double switch_time_sum_[lanes] = {};          // event_counts::switch_time_sum
  mode episode_kind_[lanes] = {};
  observer* observer_[lanes] = {};
  HWY_ALIGN double next_observe_time_[lanes] = {};  // +inf: none left
  // Per lane: the states of its realization's observer, and the index of
  // its next observe time (next_observe_time_ is that time).
  observed_states* observed_[lanes] = {};
  // The start state and end of the round of the lanes that hold an observe
  // time (vector_step), for queue_observe_times.
  HWY_ALIGN double round_start_[lanes] = {}, round_end_[lanes] = {};
  HWY_ALIGN double round_position_[lanes] = {}, round_velocity_[lanes] = {};
  HWY_ALIGN double round_belt_velocity_[lanes] = {}, round_centre_[lanes] = {};
  std::size_t observe_cursor_[lanes] = {};
  double observed_mass_ = 0.0, observed_stiffness_ = 0.0, observed_levels_[2] = {};
  switch_source switch_times_[lanes] = {};
};

// Runs the engine over [first, last); on max_events, the collector's fallback.
template <class Collector>
void run_lanes(const sweep_spec& s, const model_parameters& p, const family_point* family,
               Collector& collect, std::uint64_t first, std::uint64_t last) {
  if (first >= last) return;
  try {
    if (family)
      lane_engine<Collector, true>(s, p, family, collect, first, last).run();
    else
      lane_engine<Collector, false>(s, p, nullptr, collect, first, last).run();
  } catch (const bound_exceeded&) {
    collect.fallback();
  }
}

}  // namespace

std::vector<block_result> SimulateBlocksLanes(const sweep_spec& s, std::size_t point,
                                              std::uint64_t first_block, std::uint64_t count) {
  const auto p = point_parameters(s, point);
  std::vector<block_result> outs(count);
  const std::uint64_t first = first_block * s.block_size;
  const std::uint64_t last = std::min(s.realizations, (first_block + count) * s.block_size);
  for (std::uint64_t b = 0; b < count; ++b) {
    outs[b].stats = block_statistics(s, p);
    if (s.keep_records) outs[b].records.reserve(s.block_size);
  }
  std::optional<family_point> fp;
  if (!p.is_paper_model()) fp.emplace(p, stream_key(s, p));
  // Four instantiations: with the family statistics, without their
  // per-stick and per-round work (sweep_spec::family_statistics), without
  // the duration lists too (sweep_spec::means_only), and then without R's
  // causal score unless it is kept (keeps_causal_score: the peak finder's
  // score method keeps it, a `sweep --statistics R` does not).
  if (s.family_statistics) {
    statistics_collector<realization_observer> collect(s, p, outs, point, first_block);
    run_lanes(s, p, fp ? &*fp : nullptr, collect, first, last);
  } else if (!s.means_only) {
    statistics_collector<paper_statistics_observer> collect(s, p, outs, point, first_block);
    run_lanes(s, p, fp ? &*fp : nullptr, collect, first, last);
  } else if (keeps_causal_score(s)) {
    statistics_collector<mean_and_causal_score_observer> collect(s, p, outs, point, first_block);
    run_lanes(s, p, fp ? &*fp : nullptr, collect, first, last);
  } else {
    statistics_collector<mean_statistics_observer> collect(s, p, outs, point, first_block);
    run_lanes(s, p, fp ? &*fp : nullptr, collect, first, last);
  }
  return outs;
}

std::vector<realization_trace> TraceRealizationsLanes(const sweep_spec& s, std::size_t point,
                                                      std::uint64_t first, std::uint64_t last) {
  const auto p = point_parameters(s, point);
  std::vector<realization_trace> out(last > first ? last - first : 0);
  std::optional<family_point> fp;
  if (!p.is_paper_model()) fp.emplace(p, stream_key(s, p));
  trace_collector collect(s, p, first, out);
  run_lanes(s, p, fp ? &*fp : nullptr, collect, first, last);
  return out;
}

}  // namespace HWY_NAMESPACE
}  // namespace stickslip::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stickslip::detail {

namespace {
std::atomic<std::uint64_t> g_reference_reruns{0};
}
void count_lane_reference_rerun() noexcept {
  g_reference_reruns.fetch_add(1, std::memory_order_relaxed);
}
std::uint64_t lane_reference_reruns() noexcept {
  return g_reference_reruns.load(std::memory_order_relaxed);
}

HWY_EXPORT(SimulateBlocksLanes);
HWY_EXPORT(TraceRealizationsLanes);

namespace {
// The entry points run only the points engine_for sends to the lanes.
void require_lanes(const char* entry, const sweep_spec& s, std::size_t point) {
  if (!runs_in_lanes(point_parameters(s, point)))
    throw invalid_value(entry, "a point the lane engine does not run",
                        "the paper's model or an undamped two-level belt");
}
}  // namespace

std::vector<block_result> simulate_blocks_lanes(const sweep_spec& s, std::size_t point,
                                               std::uint64_t first_block, std::uint64_t count) {
  require_lanes("simulate_blocks_lanes", s, point);
  count_engine_run(point_engine::lanes);
  return HWY_DYNAMIC_DISPATCH(SimulateBlocksLanes)(s, point, first_block, count);
}

block_result simulate_block_lanes(const sweep_spec& s, const work_unit& u) {
  return std::move(simulate_blocks_lanes(s, u.point, u.block, 1).front());
}

std::vector<realization_trace> trace_realizations_lanes(const sweep_spec& s, std::size_t point,
                                                       std::uint64_t first, std::uint64_t last) {
  require_lanes("trace_realizations_lanes", s, point);
  count_engine_run(point_engine::lanes);
  return HWY_DYNAMIC_DISPATCH(TraceRealizationsLanes)(s, point, first, last);
}

}  // namespace stickslip::detail
#endif  // HWY_ONCE
