// How much of a run's expected work is done: each unit weighs its expected
// events (expected_unit_cost), so that an ETA extrapolated from it is honest
// although the costliest units run first (a unit-count ETA starts far too
// high). Calls to add() must be serialized (sweep_hooks::unit_done is).
#pragma once
#include <functional>

#include "stickslip/sweep.hpp"

namespace stickslip::run {

class work_meter {
 public:
  // `to_run`: the units this run will compute (not resumed, in its shard).
  work_meter(const sweep_spec& s, const std::function<bool(const work_unit&)>& to_run);
  void add(const work_unit& u);
  // 0 .. 1 (1 when there is nothing to do).
  [[nodiscard]] double fraction() const noexcept { return total_ > 0 ? done_ / total_ : 1.0; }

 private:
  const sweep_spec* spec_;
  double total_ = 0, done_ = 0;
};

// Seconds left when `elapsed` seconds did `work_done` of the work (0 .. 1);
// negative when nothing is done yet.
[[nodiscard]] double eta_seconds(double elapsed, double work_done) noexcept;

}  // namespace stickslip::run
