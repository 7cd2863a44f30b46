// The data of the paper's statistical model for one grid point
// (statistics.hpp has the definitions): a realization's record and the
// accumulators of a point, with no operation of their own. The statistics
// schema (statistics_schema.hpp) points at these members row by row;
// point_statistics (statistics.hpp) adds what fills, merges and finishes
// them by iterating the schema, so neither the schema nor the statistics
// depend on each other both ways.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "stickslip/accumulators/histogram.hpp"
#include "stickslip/accumulators/histogram2d.hpp"
#include "stickslip/accumulators/mean_variance.hpp"
#include "stickslip/accumulators/score_moments.hpp"
#include "stickslip/accumulators/survival_counts.hpp"
#include "stickslip/accumulators/time_statistics.hpp"
#include "stickslip/episode.hpp"
#include "stickslip/uncertainty/sobol.hpp"

namespace stickslip {

// Histogram binning. Ranges are derived per grid point unless set (> 0):
// D and D_1 on [0, d_max], H on [0, min(t_a, 5/lambda)], R on [0, 1].
struct histogram_spec {
  std::size_t bins = 50;
  double stick_duration_max = 0.0;  // 0 = d_max
  double slip_duration_max = 0.0;   // 0 = min(t_a, 5/lambda)
  friend bool operator==(const histogram_spec&, const histogram_spec&) = default;
};

// The grid of the survival group (sweep --statistics survival;
// survival_estimate.hpp): `bins` equal bins over [0, stick_duration_max] for
// the stick durations D and over [0, slip_duration_max] for the slip
// durations H, the same at every grid point so that the curves share one
// duration coordinate. 0 = automatic: resolve_survival_grid (sweep.hpp) sets
// the largest d_max and the largest t_a over the grid's points.
struct survival_spec {
  std::size_t bins = 200;
  double stick_duration_max = 0.0;
  double slip_duration_max = 0.0;
  friend bool operator==(const survival_spec&, const survival_spec&) = default;
};

struct realization_record {
  std::uint64_t realization = 0;
  double x0 = 0, xdot0 = 0;
  int belt_start = 1;
  std::uint32_t sticks = 0;  // S_T
  std::uint32_t slips = 0;   // S_L
  double stick_fraction = 0; // R
  double first_stick_start = -1, first_stick_duration = -1;  // -1: no stick
  bool first_stick_censored = false;
  double friction_power = 0;  // W_f [W]
  double damping_power = 0;   // W_c [W]
  // Over the sticks (positive length): sum of N(start) D_i and of the mid
  // time (start + end)/2 D_i, i.e. int N(t) dt and int t dt over the sticks
  // (N(t) is constant during a stick): the causal score's Z
  // (causal_score_moments).
  double stick_switch_moment = 0, stick_time_moment = 0;
  event_counts events;
  // The values of the uncertain parameters (sweep_spec::uncertain, in that
  // order) this realization drew; empty without laws.
  std::vector<double> drawn_values;
};

// Where the statistics keep no causal score (point_statistics::
// keeps_causal_score: the paper study's configuration, and means only
// without the derivatives, whose lane observers skip the bookkeeping), the scalar engines drop theirs from the record,
// so that the records are the same bits whichever engine ran.
inline void drop_causal_score(realization_record& r) noexcept {
  r.stick_switch_moment = r.stick_time_moment = 0.0;
  r.events.switch_time_sum = 0.0;
}

// Whether a realization has a first stick D_1: a stick that starts in the
// window (with a burn-in T, a stick in progress at T is not one; burn_in.hpp).
[[nodiscard]] inline bool has_first_stick(const realization_record& r) noexcept {
  return r.sticks > 0 && r.first_stick_duration >= 0.0;
}

struct convergence_point {
  std::uint64_t realizations;
  double R_mean, R_ci95_half_width;
  double stick_duration_mean, stick_duration_ci95_half_width;
  friend bool operator==(const convergence_point&, const convergence_point&) = default;
};

// The accumulators of one grid point; each one has a row in the statistics
// schema (statistics_schema.hpp), or is listed there as written by hand.
struct point_accumulators {
  mean_variance stick_fraction;        // R
  mean_variance sticks_per_time;       // S_T / t_a
  mean_variance slips_per_time;        // S_L / t_a
  mean_variance stick_duration;        // D, pooled over all sticks
  mean_variance first_stick_duration;  // D_1, realizations with a stick
  mean_variance slip_duration;         // H, pooled over counted slips
  mean_variance stick_onset_position;  // X, pooled over all sticks
  mean_variance friction_power;        // W_f
  mean_variance damping_power;         // W_c
  histogram stick_fraction_hist, stick_duration_hist, first_stick_duration_hist,
      slip_duration_hist, stick_onset_position_hist;
  // R's causal score (Z, Y of causal_score_moments), at points with
  // Poisson switching (has_poisson_switching): the peak finder's derivative.
  causal_score_moments stick_fraction_causal_score;
  // Against K = N - lambda t_a (N belt switches): d mean/dlambda and the
  // control-variate means of R, S_T/t_a, S_L/t_a (score_moments.hpp).
  score_moments stick_fraction_score, sticks_per_time_score, slips_per_time_score;
  double expected_switches = 0.0;  // lambda t_a of the point (not merged: the same)
  // A two-level belt with its own rates (--belt-rates r1,r2): the same
  // moments against K_j = r_j x (score of r_j), j = 1, 2, for d mean/dr_j
  // (belt_rate_scores, statistics.hpp; filled with the family statistics).
  std::array<score_moments, 2> stick_fraction_rate_score, sticks_per_time_rate_score,
      slips_per_time_rate_score;
  std::array<double, 2> belt_rates{0.0, 0.0};  // r1, r2; 0: no rate scores (not merged)
  // The same against the scores of the generator's entries q_ij (i != j,
  // q_ij > 0; row-major n x n, the rest unused) of a belt given by its
  // generator (belt_generator_scores, statistics.hpp; filled with the family
  // statistics). `generator`: that Q, empty for other belts (not merged).
  std::vector<score_moments> stick_fraction_generator_score, sticks_per_time_generator_score,
      slips_per_time_generator_score;
  std::vector<double> generator;
  std::vector<double> generator_start_terms;  // stationary_score_terms(generator), derived
  bool stationary_start = true;  // the start level drawn from the stationary law
  std::vector<mean_variance> level_fraction;  // P_j, one per belt level
  histogram2d stick_duration_onset;            // (D_i, X_i) of every stick
  // Whether point_statistics::add fills the five above; whether it fills
  // only the moments of the per-realization quantities.
  bool family_statistics = true;
  bool means_only = false;
  // Whether add() fills stick_fraction_causal_score (point_statistics::
  // keeps_causal_score).
  bool causal_score_kept = true;
  // The survival group (point_statistics::select_survival): D_i and H_i ended or censored.
  survival_counts stick_survival, slip_survival;
  // The ensemble at the observe times (point_statistics::select_observe_times;
  // sweep_spec::observe_times): empty (not selected) by default.
  time_statistics observed;
  std::uint64_t realizations = 0;
  std::uint64_t no_stick = 0;  // realizations without a D_1 (no stick starts in [T, t_a))
  std::uint64_t first_stick_censored = 0;  // D_1 cut off by t_a
  event_counts events;
  std::vector<convergence_point> convergence;
  // The pick-freeze moments of a sensitivity study (sweep_spec::
  // sensitivity_statistic); empty (0 inputs) otherwise.
  sobol_moments sensitivity;

  friend bool operator==(const point_accumulators&, const point_accumulators&) = default;
};

}  // namespace stickslip
