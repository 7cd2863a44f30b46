// The floor of the full study: the time to draw every belt switch
// time of the same study and nothing else. Per realization: Philox4x64 blocks
// from substream::belt_switches (the same counters the engines use), the
// 64-bit words to (0,1) by u01fixedpt, the exponential transform
// -log(u)/lambda with Highway's vector Log at the full vector width of the
// build (8 doubles with AVX-512, 4 with AVX2), and the running sum up to t_a.
// Drawn in batches of 8 Philox blocks (32 times), as the lane engine draws
// them: batching the log calls was 20 % faster than one block at a time
// (0.256 s against 0.317 s for the k = 4 study on 2 threads), so the floor is
// the faster one. Same threads, same work units ordering (most expensive
// points first) as run_units.
#pragma once
#include <cstdint>

#include "stickslip/sweep.hpp"

namespace stickslip::bench {

struct floor_result {
  double seconds = 0;
  std::uint64_t switch_times = 0;  // drawn and below t_a: the study's belt switches
  double checksum = 0;             // keeps the work observable
};

[[nodiscard]] floor_result draw_all_switch_times(const sweep_spec& s, unsigned threads);

}  // namespace stickslip::bench
