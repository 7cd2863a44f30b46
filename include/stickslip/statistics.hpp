// The paper's statistical model (Sec. 4) for one grid point.
// Per realization on [0, t_a]:
//   S_T  number of sticks of positive length beginning in [0, t_a)
//        (a stick cut off by t_a counts, its duration clipped)
//   S_L  number of slips beginning after the first stick (the slip before the
//        first stick is not counted, as in the paper's Fig. 2)
//   T_i, D_i   start and duration of stick i;  L_i, H_i  of slip i
//   D_1  first stick duration (may be censored by t_a; absent if no stick)
//   R    total stick time / t_a
// and, for every model of the family (docs/model.md, "Statistics of the family"):
//   X_i  stick-onset position: x at the start of stick i
//   P_j  fraction of [0, t_a] spent at belt level j (one value per level)
//   W_f  power dissipated by friction, (1/t_a) int mu_k m g |v - x'| dt over slips
//   W_c  power dissipated by damping,  (1/t_a) int c x'^2 dt
// Per grid point: mergeable accumulators of these, with densities and a
// convergence trace. Memory is independent of the number of realizations.
// The accumulators are point_accumulators (point_accumulators.hpp); each has
// a row in the statistics schema (statistics_schema.hpp), which says how it
// is sampled, binned, merged, serialized and written.
#pragma once
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "stickslip/burn_in.hpp"
#include "stickslip/episode.hpp"
#include "stickslip/observer.hpp"
#include "stickslip/parameters.hpp"
#include "stickslip/point_accumulators.hpp"
#include "stickslip/state_sampler.hpp"

namespace stickslip {

// What one finished realization adds to the statistics: its record, the
// duration D_i and onset position X_i of every stick (in order), the duration
// H_i of every counted slip, and the fraction P_j of t_a at each belt level.
struct realization_samples {
  const realization_record& record;
  const std::vector<double>& sticks;
  const std::vector<double>& slips;
  const std::vector<double>& onsets;
  const std::vector<double>& level_fractions;
  // N_ij, the belt's jumps from level i to level j in [0, t_a] (row-major,
  // n x n), for belts of more than two levels with the family statistics;
  // else empty (two levels alternate: N and the start level give them).
  const std::vector<std::uint32_t>& jumps;
  // Whether the last entry of `sticks` (of `slips`) is the episode cut by
  // t_a: right-censored at the duration it had reached (survival_counts).
  bool last_stick_censored = false;
  bool last_slip_censored = false;
  // With a burn-in T (burn_in.hpp): whether the first entry of `sticks` is
  // the stick in progress at T, left-truncated (counted from T; no onset
  // position, so `onsets` starts with the next stick), and the length
  // t_a - T of the observed window [T, t_a] that the rates and fractions of
  // the record are over (0: the whole window t_a). A slip in progress at T
  // is never counted (it comes before the window's first stick).
  bool first_stick_left_truncated = false;
  double observed_window = 0.0;
  // The states at the observe times (sweep_spec::observe_times,
  // state_sampler.hpp), one per time; nullptr without observe times.
  const stickslip::observed_states* observed_states = nullptr;
};

// Whether the belt switches at the Poisson rate lambda (two levels left at
// the same rate lambda: no belt_rates, no belt_generator), so that the
// score N/lambda - t_a, hence the likelihood-ratio derivative over lambda and
// the control variate N of score_moments.hpp, apply. Writers report NaN for
// these estimates at other points.
[[nodiscard]] inline bool has_poisson_switching(const model_parameters& p) noexcept {
  return p.belt_rates.empty() && p.belt_generator.empty();
}

// The accumulators of one grid point (point_accumulators.hpp) and what
// fills and merges them: every operation iterates the statistics schema.
class point_statistics : public point_accumulators {
 public:
  point_statistics() = default;
  // `family`: whether add() fills the family statistics
  // (sweep_spec::family_statistics).
  // `stationary_start`: the belt's start level is drawn from the stationary
  // law (initial_condition_law::belt_start = 0), which depends on the rates.
  // `means_only`: add() fills only the moments of the per-realization
  // quantities (sweep_spec::means_only). `causal_score`: add() keeps R's
  // causal score (keeps_causal_score(const sweep_spec&) in sweep_spec.hpp;
  // by default with the family statistics or means only, as before the
  // flag).
  point_statistics(const model_parameters& p, const histogram_spec& h, bool family = true,
                   bool stationary_start = true, bool means_only = false);
  point_statistics(const model_parameters& p, const histogram_spec& h, bool family,
                   bool stationary_start, bool means_only, bool causal_score);

  // Whether add() keeps R's causal score. Not in the paper study's
  // configuration (neither family statistics nor means only), whose lane
  // observer skips its bookkeeping (paper_statistics_observer), nor for
  // means only without the derivatives (a `sweep --statistics R`:
  // mean_statistics_observer); the reference engines drop theirs there too
  // (sweep/block_engines.cpp).
  [[nodiscard]] bool keeps_causal_score() const noexcept { return causal_score_kept; }
  // Sizes the survival counts (empty, not selected, by default) on the grid `g`.
  void select_survival(const survival_spec& g);
  // Sizes the observe-time statistics (empty, not selected, by default).
  void select_observe_times(const std::vector<double>& times, std::size_t levels);
  // Add one finished realization. Precondition: one level fraction per level.
  void add(const realization_samples& r, double window);
  // Exact merge (see mean_variance). Precondition: same binning.
  point_statistics& operator+=(const point_statistics& o);
  void record_convergence();
  // After the last realization (ordered_merger, when a point is complete):
  // frees the room to grow and computes what the outputs read once
  // (time_statistics::finish). Changes no value.
  void finish() { observed.finish(); }

  friend bool operator==(const point_statistics&, const point_statistics&) = default;
};

// The centred scores of the rates of a two-level belt (docs/precision.md,
// "Markov belt rates"): with N_j the jumps out of level j and T_j the time at
// level j on [0, t_a], the log-likelihood of the belt path has the score
//   d/dr_j = N_j / r_j - T_j  (+ d log pi(s0) / dr_j for a stationary start),
// so K_j = N_j - r_j T_j + r_j d log pi(s0)/dr_j has mean 0 and
// d E[X]/dr_j = Cov(X, K_j) / r_j. With pi = (r2, r1)/(r1 + r2):
//   r1 d log pi(first)/dr1 = -r1/(r1 + r2),  r1 d log pi(second)/dr1 = r2/(r1 + r2),
//   r2 d log pi(first)/dr2 = r1/(r1 + r2),   r2 d log pi(second)/dr2 = -r2/(r1 + r2).
// `start_level` 0 or 1, `switches` N = N_1 + N_2 (the levels alternate), `time` T_1, T_2.
[[nodiscard]] std::array<double, 2> belt_rate_scores(const std::array<double, 2>& rates,
                                                     std::size_t start_level,
                                                     std::uint64_t switches,
                                                     const std::array<double, 2>& time,
                                                     bool stationary_start) noexcept;

// The centred scores K_ij = N_ij - q_ij T_i + q_ij d log pi(s0)/dq_ij of the
// off-diagonal entries of a generator Q (n x n, row-major; the last term for
// a start drawn from the stationary law pi): the log-likelihood of the belt
// path on [0, t_a] is sum_{i != j} N_ij log q_ij - sum_i q_i T_i + log pi(s0),
// so d E[X]/dq_ij = Cov(X, K_ij) / q_ij. `stationary_terms[i n + j]` =
// q_ij d log pi(s0)/dq_ij for each start level s0 is precomputed by
// stationary_score_terms. K is 0 on the diagonal and where q_ij = 0.
[[nodiscard]] std::vector<double> stationary_score_terms(const std::vector<double>& generator);
void belt_generator_scores(const std::vector<double>& generator, std::size_t start_level,
                           const std::vector<std::uint32_t>& jumps,
                           const std::vector<double>& level_time,
                           const std::vector<double>* stationary_terms,
                           std::vector<double>& k) noexcept;

// Observer that turns the episode stream of one realization into a
// realization_record plus the lists of stick and slip durations.
class realization_observer : public observer_base {
 public:
  // The model's window, kinetic friction force mu_k m g, damping c, and
  // belt level count. `family`: whether to collect the stick-onset positions
  // (sweep_spec::family_statistics). `burn_in`: T, 0 <= T < t_a; only
  // [T, t_a] is counted (burn_in.hpp), and the rates and fractions of the
  // record are over t_a - T. `observe_times`: the observe times
  // (sweep_spec::observe_times; nullptr or empty: none), whose states the
  // engines hand to sample_segment; the vector must outlive the observer.
  explicit realization_observer(const model_parameters& p, bool family = true,
                                double burn_in = 0.0,
                                const std::vector<double>* observe_times = nullptr);
  void reset(std::uint64_t realization, double x0, double xdot0, int belt);
  // Inline: the engines call it once per episode. It is also compiled into
  // the SIMD translation unit (fast_lanes.cpp, other -m flags), so it must
  // stay free of anything a compiler could round differently there (the
  // core is built with -ffp-contract=off: no fused multiply-adds).
  // always_inline: the lane engine is compiled once per SIMD target, and GCC
  // otherwise leaves this call out of line there (+8 % CPU in the study).
  [[gnu::always_inline, gnu::flatten]] void on_episode(const episode& e) {
    collect_episode<true>(e);
  }
  // The onset positions only when `Onsets` (and the observer's flag): the
  // lane engine's paper_statistics_observer compiles them out.
  // With a burn-in T, an episode that ends at or before T is left out, and
  // one in progress at T counts from T, left-truncated (burn_in.hpp).
  template <bool Onsets, bool Durations = true, bool Causal = true>
  [[gnu::always_inline, gnu::flatten]] void collect_episode(const episode& e) {
    if (burn_in_.active()) [[unlikely]] {
      if (!(e.end > burn_in_.time())) return;
      if (e.start < burn_in_.time()) {
        episode in_window = e;
        in_window.start = burn_in_.time();
        collect_in_window<Onsets, Durations, Causal, true>(in_window);
        return;
      }
    }
    collect_in_window<Onsets, Durations, Causal, false>(e);
  }
  // One episode of the window. D_1 is the first stick that starts in the
  // window: not a left-truncated one.
  template <bool Onsets, bool Durations, bool Causal, bool LeftTruncated>
  [[gnu::always_inline]] void collect_in_window(const episode& e) {
    const double d = e.duration();
    if (e.kind == mode::stick) {
      if (!(d > 0.0)) return;  // sticks of positive length only
      if constexpr (LeftTruncated) {
        stick_left_truncated_ = true;
      } else if (rec_.first_stick_start < 0.0) {
        rec_.first_stick_start = e.start;
        rec_.first_stick_duration = d;
        rec_.first_stick_censored = e.censored;
      }
      ++rec_.sticks;
      // Only the last episode is cut; a branch, not a store per episode:
      // the lane engine passes the flag as a constant, so it folds away.
      if (e.censored) stick_cut_ = true;
      total_stick_ += d;
      if constexpr (Causal) {
        rec_.stick_switch_moment += e.switches_before * d;
        rec_.stick_time_moment += 0.5 * (e.start + e.end) * d;
      }
      if constexpr (Durations) sticks_.push_back(d);
      if constexpr (Onsets && !LeftTruncated) {
        if (family_) onsets_.push_back(e.position_at_start);
      }
    } else if (rec_.sticks > 0) {  // slips after the first stick
      ++rec_.slips;
      if (e.censored) slip_cut_ = true;
      if constexpr (Durations) slips_.push_back(d);
    }
  }
  // The sums over pieces of motion (motion_piece, docs/model.md): the time at
  // each level, the relative travel |v dt - dx| of the slips, and the damping
  // work (c v^2 dt over a stick; over a slip the energy identity
  // c int x'^2 = sigma mu_k m g dx - d(m x'^2 / 2 + k x^2 / 2)).
  // With a burn-in T only the pieces' parts in [T, t_a] (burn_in_cut); the
  // jumps N_ij over the whole window.
  void on_piece(const motion_piece& p) noexcept {
    if (!jumps_.empty()) {  // every piece is emitted, so a level change is a jump
      if (p.level != last_level_ && last_level_ < level_time_.size())
        ++jumps_[last_level_ * level_time_.size() + p.level];
      last_level_ = p.level;
    }
    if (burn_in_.active()) [[unlikely]] {
      if (!(p.end_time > burn_in_.time())) return;
      if (p.start_time < burn_in_.time()) return add_piece(burn_in_.after(p));
    }
    add_piece(p);
  }
  void add_piece(const motion_piece& p) noexcept {
    level_time_[p.level] += p.duration;
    if (p.kind == mode::slip) slip_travel_ += p.relative_travel();
    if (damping_ > 0.0) {
      if (p.kind == mode::stick) {
        damping_work_ += damping_ * p.belt_velocity * p.belt_velocity * p.duration;
      } else {
        const double de = 0.5 * mass_ * (p.end_velocity * p.end_velocity -
                                         p.start_velocity * p.start_velocity) +
                          0.5 * stiffness_ * (p.end_position * p.end_position -
                                              p.start_position * p.start_position);
        damping_work_ += p.sigma * kinetic_force_ * (p.end_position - p.start_position) - de;
      }
    }
  }
  // What collect_in_window sums over the closed (not censored) episodes of a
  // window without a burn-in, summed by the lane engine itself in the same
  // order (takes_episode_tallies): the sticks of positive length, the slips
  // after the first stick, the stick time, the first stick's start and
  // length (-1: none). Before the last, censored episode.
  void set_closed_episode_tallies(double sticks, double slips, double stick_time,
                                  double first_start, double first_duration) noexcept {
    rec_.sticks = static_cast<std::uint32_t>(sticks);
    rec_.slips = static_cast<std::uint32_t>(slips);
    total_stick_ = stick_time;
    rec_.first_stick_start = first_start;
    rec_.first_stick_duration = first_duration;
  }
  // The same sums, accumulated by the lane engine itself in the same order
  // (the paper's model: two levels, no damping).
  void set_paper_sums(double time_first, double time_second, double slip_travel) noexcept {
    level_time_[0] = time_first;
    level_time_[1] = time_second;
    slip_travel_ = slip_travel;
  }
  // The state at the observe times: the engines pass the closed-form
  // segments (all of them, or those that hold the sampler's next time); not
  // named on_segment, so that the lane engine, which builds no segments for
  // other observers, can still take this one (state_sampler.hpp).
  [[nodiscard]] bool observes_times() const noexcept { return sampler_.active(); }
  [[nodiscard]] const state_sampler& sampler() const noexcept { return sampler_; }
  void sample_segment(const segment& s) { sampler_.on_segment(s); }
  // The lane engine's path: it fills the states at the observe times itself
  // (state_sampler::states_to_fill, mark_sampled).
  [[nodiscard]] state_sampler& sampler_to_fill() noexcept { return sampler_; }
  [[nodiscard]] realization_record& record() noexcept { return rec_; }
  // Without every observe time sampled (an engine that missed a segment),
  // observed_states is nullptr, and point_statistics::add refuses it.
  [[nodiscard]] realization_samples samples() const noexcept {
    return {rec_,      sticks_,    slips_,    onsets_,
            level_fraction_, jumps_, stick_cut_, slip_cut_,
            stick_left_truncated_, window_,
            sampler_.active() && sampler_.complete() ? &sampler_.states() : nullptr};
  }
  [[nodiscard]] const std::vector<double>& stick_durations() const noexcept { return sticks_; }
  [[nodiscard]] const std::vector<double>& slip_durations() const noexcept { return slips_; }
  void finish() noexcept;
  // Room for a realization's stick and slip durations (and onsets): an
  // estimate from the belt's switch rate and t_a. For the lane engine's
  // observers that keep them (keeps_durations).
  void reserve_episodes(const model_parameters& p);
  static constexpr bool keeps_durations = true;

 private:
  double window_, kinetic_force_, damping_, mass_, stiffness_;  // window_: t_a - T
  bool family_;
  burn_in_cut burn_in_;
  bool stick_cut_ = false, slip_cut_ = false;  // the last stick / slip is cut by t_a
  bool stick_left_truncated_ = false;          // the first stick is cut at T
  double total_stick_ = 0, slip_travel_ = 0, damping_work_ = 0;
  realization_record rec_;
  std::vector<double> sticks_, slips_, onsets_;
  std::vector<double> level_time_, level_fraction_;
  std::vector<std::uint32_t> jumps_;  // N_ij (realization_samples::jumps)
  std::size_t last_level_ = static_cast<std::size_t>(-1);
  state_sampler sampler_;  // the observe times (none by default)
};

// A realization_observer that also takes every segment, for its states at
// the observe times: what the reference engines (scalar paper, family, and
// realizations with drawn parameters) run when there are observe times.
struct state_sampling_observer : observer_base {
  realization_observer& o;
  explicit state_sampling_observer(realization_observer& obs) : o(obs) {}
  void reset(std::uint64_t realization, double x0, double xdot0, int belt) {
    o.reset(realization, x0, xdot0, belt);
  }
  void on_episode(const episode& e) { o.on_episode(e); }
  void on_piece(const motion_piece& p) { o.on_piece(p); }
  void on_segment(const segment& s) { o.sample_segment(s); }
};

// realization_observer without the family statistics
// (sweep_spec::family_statistics off): no onset positions, and no pieces of
// motion (observer_base's no-op, so the lane engine does not sum them). The
// paper study runs the lane engine with it, at the speed from before.
class paper_statistics_observer : public realization_observer {
 public:
  using realization_observer::realization_observer;
  using observer_base::on_piece;
  // Nor the causal score's sums (~3 % of the study; observer.hpp).
  static constexpr bool causal_score = false;
  [[gnu::always_inline, gnu::flatten]] void on_episode(const episode& e) {
    collect_episode<false, true, false>(e);
  }
};

// paper_statistics_observer without the lists of stick and slip durations
// (sweep_spec::means_only: the pooled statistics are not filled), with R's
// causal score's sums only when `CausalScore` (point_statistics::
// keeps_causal_score: the peak finder's score method; a `sweep --statistics
// R` does not read them, and they cost it ~5 %).
template <bool CausalScore>
class basic_mean_statistics_observer : public realization_observer {
 public:
  using realization_observer::realization_observer;
  using observer_base::on_piece;
  static constexpr bool causal_score = CausalScore;
  static constexpr bool keeps_durations = false;
  // Without the causal score (whose sums need each stick's switch count),
  // the lanes hand over the tallies of the closed episodes instead.
  static constexpr bool episode_tallies = !CausalScore;
  [[gnu::always_inline, gnu::flatten]] void on_episode(const episode& e) {
    collect_episode<false, false, CausalScore>(e);
  }
};
using mean_statistics_observer = basic_mean_statistics_observer<false>;
using mean_and_causal_score_observer = basic_mean_statistics_observer<true>;

}  // namespace stickslip
