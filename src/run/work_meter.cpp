#include "stickslip/run/work_meter.hpp"

#include <algorithm>

namespace stickslip::run {

work_meter::work_meter(const sweep_spec& s, const std::function<bool(const work_unit&)>& to_run)
    : spec_(&s) {
  for (std::uint64_t i = 0, n = unit_count(s); i < n; ++i)
    if (const auto u = unit_at(s, i); to_run(u)) total_ += expected_unit_cost(s, u);
}

void work_meter::add(const work_unit& u) { done_ += expected_unit_cost(*spec_, u); }

double eta_seconds(double elapsed, double work_done) noexcept {
  if (!(work_done > 0)) return -1;
  return elapsed * std::max(0.0, 1.0 - work_done) / work_done;
}

}  // namespace stickslip::run
