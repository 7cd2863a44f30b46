// The paper's statistical model (Sec. 4) for one grid point.
// Per realization on [0, t_a]:
//   S_T  number of sticks of positive length beginning in [0, t_a)
//        (a stick cut off by t_a counts, its duration clipped)
//   S_L  number of slips beginning after the first stick (the slip before the
//        first stick is not counted, as in the paper's Fig. 2)
//   T_i, D_i   start and duration of stick i;  L_i, H_i  of slip i
//   D_1  first stick duration (may be censored by t_a; absent if no stick)
//   R    total stick time / t_a
// Per grid point: mergeable accumulators of these, with densities and a
// convergence trace. Memory is independent of the number of realizations.
// Every accumulator of point_statistics has a row in the statistics schema
// (statistics_schema.hpp), which says how it is sampled, binned, merged,
// serialized and written.
#pragma once
#include <cstdint>
#include <vector>

#include "stickslip/accumulators/histogram.hpp"
#include "stickslip/accumulators/mean_variance.hpp"
#include "stickslip/accumulators/score_moments.hpp"
#include "stickslip/episode.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/observer.hpp"
#include "stickslip/parameters.hpp"

namespace stickslip {

// Histogram binning. Ranges are derived per grid point unless set (> 0):
// D and D_1 on [0, d_max], H on [0, min(t_a, 5/lambda)], R on [0, 1].
struct histogram_spec {
  std::size_t bins = 50;
  double stick_duration_max = 0.0;  // 0 = d_max
  double slip_duration_max = 0.0;   // 0 = min(t_a, 5/lambda)
  friend bool operator==(const histogram_spec&, const histogram_spec&) = default;
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
  event_counts events;
};

struct convergence_point {
  std::uint64_t realizations;
  double R_mean, R_ci95_half_width;
  double stick_duration_mean, stick_duration_ci95_half_width;
};

// Whether the belt switches at the Poisson rate lambda (two levels left at
// the same rate lambda: no belt_rates, no belt_generator), so that the
// score N/lambda - t_a, hence the likelihood-ratio derivative over lambda and
// the control variate N of score_moments.hpp, apply. Writers report NaN for
// these estimates at other points.
[[nodiscard]] inline bool has_poisson_switching(const model_parameters& p) noexcept {
  return p.belt_rates.empty() && p.belt_generator.empty();
}

class point_statistics {
 public:
  point_statistics() = default;
  point_statistics(const model_parameters& p, const histogram_spec& h);

  // Add one finished realization; `sticks` and `slips` hold its D_i and H_i.
  void add(const realization_record& r, const std::vector<double>& sticks,
           const std::vector<double>& slips, double window);
  // Exact merge (see mean_variance). Precondition: same binning.
  point_statistics& operator+=(const point_statistics& o);
  void record_convergence();

  // The accumulators; each one has a row in statistics_schema.cpp.
  mean_variance stick_fraction;        // R
  mean_variance sticks_per_time;       // S_T / t_a
  mean_variance slips_per_time;        // S_L / t_a
  mean_variance stick_duration;        // D, pooled over all sticks
  mean_variance first_stick_duration;  // D_1, realizations with a stick
  mean_variance slip_duration;         // H, pooled over counted slips
  histogram stick_fraction_hist, stick_duration_hist, first_stick_duration_hist,
      slip_duration_hist;
  // Against K = N - lambda t_a (N belt switches): d mean/dlambda and the
  // control-variate means of R, S_T/t_a, S_L/t_a (score_moments.hpp).
  score_moments stick_fraction_score, sticks_per_time_score, slips_per_time_score;
  double expected_switches = 0.0;  // lambda t_a of the point (not merged: the same)
  std::uint64_t realizations = 0;
  std::uint64_t no_stick = 0;              // realizations without any stick
  std::uint64_t first_stick_censored = 0;  // D_1 cut off by t_a
  event_counts events;
  std::vector<convergence_point> convergence;

  friend bool operator==(const point_statistics&, const point_statistics&) = default;
};

// Observer that turns the episode stream of one realization into a
// realization_record plus the lists of stick and slip durations.
class realization_observer : public observer_base {
 public:
  explicit realization_observer(double window) : window_(window) {}
  void reset(std::uint64_t realization, double x0, double xdot0, int belt);
  // Inline: the engines call it once per episode. It is also compiled into
  // the SIMD translation unit (fast_lanes.cpp, other -m flags), so it must
  // stay free of anything a compiler could round differently there (the
  // core is built with -ffp-contract=off: no fused multiply-adds).
  // always_inline: the lane engine is compiled once per SIMD target, and GCC
  // otherwise leaves this call out of line there (+8 % CPU in the study).
  [[gnu::always_inline, gnu::flatten]] void on_episode(const episode& e) {
    const double d = e.duration();
    if (e.kind == mode::stick) {
      if (!(d > 0.0)) return;  // sticks of positive length only
      if (rec_.sticks == 0) {
        rec_.first_stick_start = e.start;
        rec_.first_stick_duration = d;
        rec_.first_stick_censored = e.censored;
      }
      ++rec_.sticks;
      total_stick_ += d;
      sticks_.push_back(d);
    } else if (rec_.sticks > 0) {  // slips after the first stick
      ++rec_.slips;
      slips_.push_back(d);
    }
  }
  [[nodiscard]] realization_record& record() noexcept { return rec_; }
  [[nodiscard]] const std::vector<double>& stick_durations() const noexcept { return sticks_; }
  [[nodiscard]] const std::vector<double>& slip_durations() const noexcept { return slips_; }
  void finish() noexcept;

 private:
  double window_;
  double total_stick_ = 0;
  realization_record rec_;
  std::vector<double> sticks_, slips_;
};

}  // namespace stickslip
