// The fast engine behind simulate_block (sweep_engine::fast).
//
// It runs the same exact integrator (`simulate`, same formulas, same order of
// floating-point operations) as the reference engine, so every statistic is
// bit-identical to the reference path for a given seed. What differs is
// everything around the integrator:
//   - belt switch times come in batches (batched_poisson_switches: the same
//     values as poisson_switches);
//   - episodes stream straight into the point_statistics accumulators
//     (streaming_statistics_observer), with the same sequence of add() calls
//     per accumulator as point_statistics::add makes from the duration lists,
//     so there are no per-realization vectors to fill and walk again.
#pragma once
#include <cstdint>
#include <vector>

#include "stickslip/episode.hpp"
#include "stickslip/observer.hpp"
#include "stickslip/statistics.hpp"

namespace stickslip {
struct sweep_spec;
struct work_unit;
struct block_result;
}  // namespace stickslip

namespace stickslip::detail {

// Observer that does what realization_observer + point_statistics::add do,
// without the intermediate duration lists. Accumulator updates happen in the
// same per-accumulator order, hence bitwise-equal results.
class streaming_statistics_observer : public observer_base {
 public:
  streaming_statistics_observer(point_statistics& stats, double window) noexcept
      : stats_(stats), window_(window) {}

  void reset(std::uint64_t realization, double x0, double xdot0, int belt) noexcept {
    total_stick_ = 0;
    rec_ = realization_record{};
    rec_.realization = realization;
    rec_.x0 = x0;
    rec_.xdot0 = xdot0;
    rec_.belt_start = belt;
  }

  void on_episode(const episode& e) noexcept {
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
      stats_.stick_duration.add(d);
      stats_.stick_duration_hist.add(d);
    } else if (rec_.sticks > 0) {  // slips after the first stick
      ++rec_.slips;
      stats_.slip_duration.add(d);
      stats_.slip_duration_hist.add(d);
    }
  }

  // The per-realization part of point_statistics::add.
  void finish(const event_counts& counts) noexcept {
    rec_.stick_fraction = total_stick_ / window_;
    rec_.events = counts;
    auto& s = stats_;
    ++s.realizations;
    s.stick_fraction.add(rec_.stick_fraction);
    s.stick_fraction_hist.add(rec_.stick_fraction);
    s.sticks_per_time.add(rec_.sticks / window_);
    s.slips_per_time.add(rec_.slips / window_);
    if (rec_.sticks == 0) {
      ++s.no_stick;
    } else {
      s.first_stick_duration.add(rec_.first_stick_duration);
      s.first_stick_duration_hist.add(rec_.first_stick_duration);
      if (rec_.first_stick_censored) ++s.first_stick_censored;
    }
    s.events += counts;
  }

  [[nodiscard]] const realization_record& record() const noexcept { return rec_; }

 private:
  point_statistics& stats_;
  double window_;
  double total_stick_ = 0;
  realization_record rec_;
};

// simulate_block with the previous, one-realization-at-a-time fast engine
// (kept for tests and comparisons). Pure: depends only on (spec, unit).
[[nodiscard]] block_result simulate_block_fast(const sweep_spec& s, const work_unit& u);

// Which implementation sweep_engine::fast runs. All give bit-identical
// results (tests/unit/test_fast_path*.cpp), so this only changes speed; it is
// process-wide and meant for benchmarks (bench_study --engine lanes).
// Default: lanes, ~10-15 % less CPU per event than one_at_a_time on the
// 2-core development machine (docs/performance.md).
enum class fast_variant : unsigned char { one_at_a_time, lanes };
void set_fast_variant(fast_variant v) noexcept;
[[nodiscard]] fast_variant get_fast_variant() noexcept;

// simulate_block with the lane engine (src/core/fast_lanes.cpp), what
// sweep_engine::fast runs: several realizations per thread in lock step, with
// their transcendentals evaluated as SIMD vectors. Bit-identical to both
// engines above. Pure: depends only on (spec, unit).
[[nodiscard]] block_result simulate_block_lanes(const sweep_spec& s, const work_unit& u);
// The same for `count` consecutive blocks of one point at once (what
// run_units uses with the lanes variant): lanes move on to the next block's
// realizations instead of idling at a block's tail. Element i is exactly
// simulate_block_lanes(s, {point, first_block + i}).
[[nodiscard]] std::vector<block_result> simulate_blocks_lanes(const sweep_spec& s,
                                                              std::size_t point,
                                                              std::uint64_t first_block,
                                                              std::uint64_t count);

}  // namespace stickslip::detail
