#include "stickslip/state_sampler.hpp"

#include <algorithm>
#include <cstdint>

namespace stickslip {

// No SLP vectorization here: GCC paired the two halves of the energy and
// (x, x') through two 8-byte spills read back as one 16-byte load, a failed
// store forward.
#if defined(__GNUC__) && !defined(__clang__)
[[gnu::optimize("no-tree-slp-vectorize")]]
#endif
void state_sampler::record_next(double x, double xd, double v, bool sticking) noexcept {
  const std::size_t j = next_++;
  states_.position()[j] = x;
  states_.velocity()[j] = xd;
  states_.belt_velocity()[j] = v;
  states_.energy()[j] = 0.5 * mass_ * xd * xd + 0.5 * stiffness_ * x * x;
  states_.level()[j] = static_cast<double>(std::find(levels_.begin(), levels_.end(), v) -
                                           levels_.begin());
  states_.sticking()[j] = sticking ? 1.0 : 0.0;
}

void state_sampler::sample(const segment& s) {
  const bool sticking = s.kind == mode::stick;
  do {
    const phase_point p = evaluate(s, (*times_)[next_]);
    record_next(p.position, p.velocity, s.belt_velocity, sticking);
  } while (holds_next(s));
}

}  // namespace stickslip
