// See floor.hpp. Compiled once per Highway target like the lane engine
// (foreach_target.h) and dispatched at run time to the same target (AVX-512,
// AVX2, ...), so that its Log runs at the engine's vector width.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "floor.cpp"  // bench/ is on this target's include path
#include <hwy/foreach_target.h>  // must come before highway.h

#include <hwy/highway.h>
#include <hwy/contrib/math/math-inl.h>

#include "floor.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <numeric>
#include <thread>
#include <vector>

#include "stickslip/random_stream.hpp"

HWY_BEFORE_NAMESPACE();
namespace stickslip::bench {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;


// Draws the switch times of one realization; returns how many fall below t_a
// and adds their sum to `sum`.
inline std::uint64_t draw_realization(double rate, double window, std::uint64_t seed, std::uint64_t key,
                               std::uint64_t r, double& sum) {
  const hn::ScalableTag<double> d;
  const auto neg_mean = hn::Set(d, -1.0 / rate);
  random_stream rs(seed, key, r, substream::belt_switches);
  constexpr int blocks = 8;
  HWY_ALIGN double w[4 * blocks];
  double t = 0.0;
  std::uint64_t n = 0;
  const std::size_t lanes = hn::Lanes(d);
  while (true) {
    for (int b = 0; b < blocks; ++b) {
      const auto blk = rs.next_block();
      for (int j = 0; j < 4; ++j) w[4 * b + j] = random_stream::open_uniform(blk.v[j]);
    }
    for (std::size_t j = 0; j < 4 * blocks; j += lanes)
      hn::Store(hn::Mul(hn::Log(d, hn::Load(d, w + j)), neg_mean), d, w + j);
    for (int j = 0; j < 4 * blocks; ++j) {
      t += w[j];
      if (t >= window) return n;
      sum += t;
      ++n;
    }
  }
}

floor_result DrawAllSwitchTimes(const sweep_spec& s, unsigned threads) {
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t points = point_count(s);
  std::vector<std::size_t> order(points);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::vector<double> rate(points);
  for (std::size_t i = 0; i < points; ++i) rate[i] = point_parameters(s, i).switch_rate;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return rate[a] > rate[b]; });
  const std::uint64_t nb = blocks_per_point(s);
  const std::uint64_t total = points * nb;
  std::atomic<std::uint64_t> next{0};
  std::vector<std::uint64_t> counts(threads, 0);
  std::vector<double> sums(threads, 0.0);

  const auto t0 = std::chrono::steady_clock::now();
  auto worker = [&](unsigned id) {
    std::uint64_t n = 0;
    double sum = 0;
    while (true) {
      const std::uint64_t i = next.fetch_add(1);
      if (i >= total) break;
      const auto p = point_parameters(s, order[i / nb]);
      const auto key = point_key(p);
      const std::uint64_t first = (i % nb) * s.block_size;
      const std::uint64_t last = std::min(s.realizations, first + s.block_size);
      for (std::uint64_t r = first; r < last; ++r)
        n += draw_realization(p.switch_rate, p.window, s.seed, key, r, sum);
    }
    counts[id] = n;
    sums[id] = sum;
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(worker, t);
  worker(0);
  for (auto& th : pool) th.join();
  floor_result out;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (unsigned t = 0; t < threads; ++t) {
    out.switch_times += counts[t];
    out.checksum += sums[t];
  }
  return out;
}

}  // namespace HWY_NAMESPACE
}  // namespace stickslip::bench
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace stickslip::bench {
HWY_EXPORT(DrawAllSwitchTimes);
floor_result draw_all_switch_times(const sweep_spec& s, unsigned threads) {
  return HWY_DYNAMIC_DISPATCH(DrawAllSwitchTimes)(s, threads);
}
}  // namespace stickslip::bench
#endif  // HWY_ONCE
