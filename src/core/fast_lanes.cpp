// The lane engine behind simulate_block (sweep_engine::fast): several
// realizations of one work unit advance together, one event each per round,
// so that their serial dependency chains overlap and their transcendentals
// are evaluated as one SIMD vector (Highway, AVX2: 4 doubles).
//
// Each round, for every lane (= one realization in flight):
//   1. scalar: run a pending stick event (no transcendental), then prepare the
//      slip event: the argument of atan (mirror return), of atan2 (general
//      root) and the phase w * (min(t_switch, t_a) - t) whose sin and cos the
//      slip needs if it ends at a belt switch or at t_a (which it does exactly
//      when the root does not come first);
//   2. vector: atan, atan2, sin, cos of all lanes at once (the same kernels,
//      detail/fast_math_simd.hpp, that the scalar integrator calls one lane at
//      a time through detail/fast_math.hpp);
//   3. scalar: finish the slip event exactly as `simulate` does.
// The per-event arithmetic is a transcription of `simulate`
// (include/stickslip/integrator.hpp) with the same operations in the same
// order, sharing its helpers (root_angle_arguments / root_angle_from_raw,
// mirror_return_*), so every event time and state is bit-identical to the
// reference engine (tests/unit/test_fast_path*.cpp).
//
// Lanes take realizations in order; a finished realization waits in a small
// ring until all earlier ones are finished, and is then added to the block's
// statistics by point_statistics::add in realization order, exactly as the
// reference engine adds it: every Welford update happens in the same order.
// A realization that exceeds max_events makes the whole block rerun on the
// reference engine, which throws the same error the reference would.
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "stickslip/detail/fast_block.hpp"
#include "stickslip/detail/fast_math.hpp"
#include "stickslip/detail/fast_math_simd.hpp"
#include "stickslip/error.hpp"
#include "stickslip/initial_conditions.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/random_stream.hpp"
#include "stickslip/statistics.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::detail {
namespace {
namespace hn = hwy::HWY_NAMESPACE;
using simd::dtag;

constexpr int lanes = 4;        // realizations in flight per thread
constexpr std::size_t ring = 64;  // finished realizations waiting for their turn
constexpr double inf = std::numeric_limits<double>::infinity();

struct bound_exceeded {};

// The belt switch times of one realization, 32 at a time: the values of
// poisson_switches (same Philox blocks, u01fixedpt, log kernel, running sum).
class lane_switches {
 public:
  static constexpr int blocks = 8, chunk = 4 * blocks;
  void reset(double rate, std::uint64_t seed, std::uint64_t key, std::uint64_t r) noexcept {
    rs_ = random_stream(seed, key, r, substream::belt_switches);
    mean_wait_ = 1.0 / rate;
    time_ = 0.0;
    i_ = chunk;
  }
  [[nodiscard]] double next() noexcept {
    if (i_ == chunk) refill();
    return times_[i_++];
  }

 private:
  void refill() noexcept {
    const dtag d;
    HWY_ALIGN double w[chunk];
    for (int b = 0; b < blocks; ++b) {
      const auto blk = rs_.next_block();
      for (int j = 0; j < 4; ++j) w[4 * b + j] = random_stream::open_uniform(blk.v[j]);
    }
    for (int j = 0; j < chunk; j += static_cast<int>(hn::Lanes(d)))
      hn::Store(simd::log(d, hn::Load(d, w + j)), d, w + j);
    for (int j = 0; j < chunk; ++j) times_[j] = time_ += -w[j] * mean_wait_;
    i_ = 0;
  }
  random_stream rs_{0, 0, 0, substream::belt_switches};
  double mean_wait_ = 1.0, time_ = 0.0;
  int i_ = chunk;
  HWY_ALIGN double times_[chunk] = {};
};

enum class root_kind : unsigned char { none, mirror, general, after_reversal };

struct lane_state {
  bool active = false;
  std::uint64_t r = 0;
  realization_observer* obs = nullptr;
  double t = 0, x = 0, z = 0, v = 0, t_switch = 0, sigma = 1;
  mode m = mode::slip;
  bool grazing = false, after_reversal = false, mirror = false;
  event_counts counts;
  std::int64_t steps = 0;
  episode ep{};
  lane_switches sw;
  // The slip event being evaluated this round.
  bool pending = false;
  root_kind kind = root_kind::none;
  double c = 0, y = 0, wy = 0, disc = 0, sq = 0, dtheta = 0;
};

class lane_engine {
 public:
  lane_engine(const sweep_spec& s, const model_parameters& p, block_result& out,
              std::uint64_t first, std::uint64_t last)
      : s_(s), p_(p), out_(out), first_(first), last_(last), next_(first), flush_(first),
        a_(p.band_half_width()), w_(p.natural_frequency()), V_(p.belt_speed), ta_(p.window),
        key_(point_key(p)) {
    const std::size_t n = std::min<std::size_t>(ring, last - first);
    pool_.reserve(n);
    for (std::size_t i = 0; i < n; ++i) pool_.emplace_back(p.window);
    done_.assign(n, 0);
  }

  void run() {
    const dtag d;
    constexpr std::size_t N = lanes;
    HWY_ALIGN double at_in[N], at_out[N], a2y[N], a2x[N], a2_out[N], ph[N], sn[N], cs[N];
    while (true) {
      bool any = false;
      for (int l = 0; l < lanes; ++l) {
        auto& L = lanes_[l];
        prepare(L);
        if (!L.pending) {
          at_in[l] = 0.0, a2y[l] = 0.0, a2x[l] = 1.0, ph[l] = 0.0;
          continue;
        }
        any = true;
        at_in[l] = L.kind == root_kind::mirror ? mirror_return_ratio(L.wy, L.z) : 0.0;
        if (L.kind == root_kind::general) {
          const auto q = root_angle_arguments(L.wy, L.z, L.v, L.sigma, L.sq);
          a2y[l] = q.y, a2x[l] = q.x;
        } else {
          a2y[l] = 0.0, a2x[l] = 1.0;
        }
        ph[l] = fm::reduce_phase(w_ * (std::min(L.t_switch, ta_) - L.t));
      }
      if (!any) break;
      for (std::size_t j = 0; j < N; j += hn::Lanes(d)) {
        hn::Store(simd::atan(d, hn::Load(d, at_in + j)), d, at_out + j);
        hn::Store(simd::atan2(d, hn::Load(d, a2y + j), hn::Load(d, a2x + j)), d, a2_out + j);
        const auto u = hn::Load(d, ph + j);
        hn::Store(simd::sin(d, u), d, sn + j);
        hn::Store(simd::cos(d, u), d, cs + j);
      }
      for (int l = 0; l < lanes; ++l) {
        auto& L = lanes_[l];
        if (L.pending) finish_slip(L, at_out[l], a2_out[l], sn[l], cs[l]);
      }
    }
  }

 private:
  // ---- realization start and end ----
  void start(lane_state& L, std::uint64_t r) {
    const auto ic = draw_initial_conditions(s_.initial, s_.seed, key_, r);
    L.sw.reset(p_.switch_rate, s_.seed, key_, r);
    L.r = r;
    L.obs = &pool_[(r - first_) % pool_.size()];
    L.obs->reset(r, ic.position, ic.velocity, ic.belt_direction);
    L.active = true;
    L.counts = event_counts{};
    L.steps = 0;
    // simulate(): initial state and mode.
    const double a = a_, V = V_;
    L.t = 0.0, L.x = ic.position, L.z = ic.velocity;
    L.v = ic.belt_direction >= 0 ? V : -V;
    L.t_switch = L.sw.next();
    L.sigma = 1.0;
    L.grazing = L.after_reversal = L.mirror = false;
    const double x = L.x, z = L.z, v = L.v;
    const bool on_outward_edge = a - (v > 0 ? x : -x) <= 0.0;
    if (z == v && std::abs(x) <= a && !on_outward_edge) {
      L.m = mode::stick;
    } else if (z == v && std::abs(x) <= a) {
      L.m = mode::slip;
      L.sigma = v > 0 ? 1.0 : -1.0;
      L.grazing = true;
    } else if (z == v) {
      L.m = mode::slip;
      L.sigma = x > 0 ? 1.0 : -1.0;
      L.after_reversal = true;
    } else {
      L.m = mode::slip;
      L.sigma = v > z ? 1.0 : -1.0;
    }
    L.ep = episode{L.m, 0.0, 0.0, L.x, L.v, false};
  }

  void finish_realization(lane_state& L) {
    L.ep.end = ta_;
    L.ep.censored = true;
    L.obs->on_episode(L.ep);
    L.obs->finish();
    L.obs->record().events = L.counts;
    L.active = false;
    L.pending = false;
    done_[(L.r - first_) % pool_.size()] = 1;
    flush();
  }

  // Adds the finished realizations at the head of the order, in order.
  void flush() {
    while (flush_ < last_) {
      const std::size_t slot = (flush_ - first_) % pool_.size();
      if (!done_[slot]) return;
      auto& o = pool_[slot];
      out_.stats.add(o.record(), o.stick_durations(), o.slip_durations(), p_.window);
      if (s_.keep_records) out_.records.push_back(o.record());
      done_[slot] = 0;
      ++flush_;
    }
  }

  void close_episode(lane_state& L, double when, mode next_mode) {
    L.ep.end = when;
    if (L.ep.end > L.ep.start) L.obs->on_episode(L.ep);
    L.ep = episode{next_mode, when, 0.0, L.x, L.v, false};
  }

  void resolve_at_contact(lane_state& L, double from_sigma) {
    const double a = a_;
    const bool inside = from_sigma > 0 ? L.x >= -a : L.x <= a;
    if (inside) {
      L.x = std::clamp(L.x, -a, a);
      L.m = mode::stick;
    } else {
      L.m = mode::slip;
      L.sigma = -from_sigma;
      L.after_reversal = true;
    }
  }

  // ---- round, step 1: stick events, then the slip event's arguments ----
  void prepare(lane_state& L) {
    L.pending = false;
    while (true) {
      if (!L.active) {
        if (next_ >= last_ || next_ - flush_ >= pool_.size()) return;
        start(L, next_++);
      }
      if (++L.steps > s_.max_events) throw bound_exceeded{};
      if (L.m == mode::stick) {
        stick_event(L);
        continue;
      }
      prepare_slip(L);
      return;
    }
  }

  void stick_event(lane_state& L) {
    const double a = a_, V = V_, ta = ta_;
    const double s = L.v > 0 ? 1.0 : -1.0;
    const double t_edge = L.t + (a - s * L.x) / V;
    const double t_next = std::min(t_edge, L.t_switch);
    if (t_next >= ta) {
      L.x += L.v * (ta - L.t);
      L.t = ta;
      finish_realization(L);
      return;
    }
    if (L.t_switch <= t_edge) {  // belt switch ends the stick
      L.x = std::clamp(L.x + L.v * (L.t_switch - L.t), -a, a);
      L.z = L.v;
      L.t = L.t_switch;
      L.v = -L.v;
      L.sigma = -s;
      L.m = mode::slip;
      L.grazing = L.after_reversal = false;
      L.mirror = true;
      ++L.counts.belt_switches;
      close_episode(L, L.t, mode::slip);
      L.t_switch = L.sw.next();
    } else {  // stick breaks at the band edge; then the grazing orbit
      L.x = s * a;
      L.z = L.v;
      L.t = t_edge;
      L.sigma = s;
      L.m = mode::slip;
      L.grazing = true;
      L.after_reversal = L.mirror = false;
      ++L.counts.stick_breaks;
      close_episode(L, L.t, mode::slip);
    }
  }

  void prepare_slip(lane_state& L) {
    const double a = a_, w = w_;
    L.pending = true;
    L.c = L.sigma * a;
    L.y = L.x - L.c;
    L.wy = w * L.y;
    L.disc = L.wy * L.wy + (L.z - L.v) * (L.z + L.v);
    L.kind = root_kind::none;
    if (!L.grazing && L.disc > 0.0) {
      if (L.mirror) {
        L.kind = root_kind::mirror;
      } else if (L.after_reversal) {
        L.kind = root_kind::after_reversal;
        const double B = std::sqrt(L.wy * L.wy + L.z * L.z);
        const double alpha = std::acos(std::clamp(L.v / B, -1.0, 1.0));
        L.dtheta = L.sigma > 0 ? two_pi - 2.0 * alpha : 2.0 * alpha;
      } else {
        L.kind = root_kind::general;
        L.sq = std::sqrt(L.disc);
      }
    }
  }

  // ---- round, step 3: the rest of simulate()'s slip branch ----
  void finish_slip(lane_state& L, double atan_ratio, double raw, double sn, double cs) {
    const double a = a_, w = w_, ta = ta_;
    const double c = L.c, y = L.y, wy = L.wy, disc = L.disc;
    double t_root = inf;
    if (L.kind != root_kind::none) {
      double dtheta;
      if (L.kind == root_kind::mirror) {
        dtheta = mirror_return_from_atan(atan_ratio);
      } else if (L.kind == root_kind::after_reversal) {
        dtheta = L.dtheta;
      } else {
        dtheta = root_angle_from_raw(raw, wy, L.v, L.sigma, L.sq);
      }
      t_root = L.t + dtheta / w;
    }
    const double t_next = std::min(t_root, L.t_switch);
    if (t_next >= ta) {
      const double z = L.z;
      L.x = c + y * cs + z / w * sn;
      L.z = z * cs - wy * sn;
      L.t = ta;
      finish_realization(L);
      return;
    }
    L.pending = false;
    if (L.t_switch <= t_root) {  // belt switch during a slip
      const double z = L.z;
      L.x = c + y * cs + z / w * sn;
      L.z = z * cs - wy * sn;
      L.t = L.t_switch;
      L.v = -L.v;
      L.grazing = L.after_reversal = L.mirror = false;
      ++L.counts.belt_switches;
      L.t_switch = L.sw.next();
      if (L.z == L.v) {  // measure zero: landed exactly on relative rest
        resolve_at_contact(L, L.x > 0 ? -1.0 : 1.0);
        if (L.m == mode::stick && a - (L.v > 0 ? L.x : -L.x) <= 0.0) {
          L.m = mode::slip;
          L.sigma = L.v > 0 ? 1.0 : -1.0;
          L.grazing = true;
        } else if (L.m == mode::stick) {
          ++L.counts.stick_onsets;
          close_episode(L, L.t, mode::stick);
        }
      } else {
        L.sigma = L.v > L.z ? 1.0 : -1.0;
      }
      return;
    }
    if (!L.mirror) L.x = c - L.sigma * std::sqrt(disc) / w;
    L.z = L.v;
    L.t = t_root;
    const double from_sigma = L.sigma;
    L.after_reversal = L.mirror = false;
    resolve_at_contact(L, from_sigma);
    if (L.m == mode::stick) {
      const double s = L.v > 0 ? 1.0 : -1.0;
      if (a - s * L.x <= 0.0) {  // onset exactly on the outward edge: zero-length stick
        L.m = mode::slip;
        L.sigma = s;
        L.grazing = true;
        return;
      }
      ++L.counts.stick_onsets;
      close_episode(L, L.t, mode::stick);
    } else {
      ++L.counts.slip_reversals;
    }
  }

  const sweep_spec& s_;
  const model_parameters& p_;
  block_result& out_;
  std::uint64_t first_, last_, next_, flush_;
  double a_, w_, V_, ta_;
  std::uint64_t key_;
  std::vector<realization_observer> pool_;
  std::vector<unsigned char> done_;
  std::array<lane_state, lanes> lanes_{};
};

}  // namespace

block_result simulate_block_lanes(const sweep_spec& s, const work_unit& u) {
  const auto p = point_parameters(s, u.point);
  block_result out;
  out.stats = point_statistics(p, s.histograms);
  const std::uint64_t first = u.block * s.block_size;
  const std::uint64_t last = std::min(s.realizations, first + s.block_size);
  if (first >= last) return out;
  if (s.keep_records) out.records.reserve(last - first);
  try {
    lane_engine(s, p, out, first, last).run();
  } catch (const bound_exceeded&) {
    return simulate_block_reference(s, u);  // throws what the reference throws
  }
  return out;
}

}  // namespace stickslip::detail
