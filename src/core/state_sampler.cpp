#include "stickslip/state_sampler.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace stickslip {

double state_sampler::next_time() const noexcept {
  return next_ < states_.size() ? (*times_)[next_] : std::numeric_limits<double>::infinity();
}

// No SLP vectorization here: GCC paired the two halves of the energy and
// the returned (x, x') through two 8-byte spills read back as one 16-byte
// load, a failed store forward (the paper grid with 101 observe times:
// 9.42 -> 9.19 s CPU, 3 runs each).
#if defined(__GNUC__) && !defined(__clang__)
[[gnu::optimize("no-tree-slp-vectorize")]]
#endif
void state_sampler::sample(const segment& s) {
  const auto level = static_cast<std::uint32_t>(
      std::find(levels_.begin(), levels_.end(), s.belt_velocity) - levels_.begin());
  const bool sticking = s.kind == mode::stick;
  do {
    const phase_point p = evaluate(s, (*times_)[next_]);
    const double x = p.position, xd = p.velocity;
    observed_state& o = states_[next_];
    o.position = x;
    o.velocity = xd;
    o.belt_velocity = s.belt_velocity;
    o.energy = 0.5 * mass_ * xd * xd + 0.5 * stiffness_ * x * x;
    o.level = level;
    o.sticking = sticking;
    ++next_;
  } while (holds_next(s));
}

}  // namespace stickslip
