// Closed forms of a damped slip, and the certified search for its first
// return to relative rest (derivations: docs/model.md, "Damped slip").
//
// During a slip with friction direction sigma, y = x - sigma a_k obeys
//   y'' + 2 gamma y' + omega_0^2 y = 0       (gamma = c / 2m > 0),
// and so do y' = x' and y'' = x''. Every solution u with u(0) = u0,
// u'(0) = u1 is u(t) = u0 f0(t) + u1 f1(t), u'(t) = u0 g0(t) + u1 g1(t) with
//   f1 = e^{-gamma t} S,  f0 = e^{-gamma t} (C + gamma S),
//   g1 = e^{-gamma t} (C - gamma S),  g0 = -omega_0^2 e^{-gamma t} S,
// where, by regime (omega_d^2 = omega_0^2 - gamma^2, beta^2 = -omega_d^2):
//   under-damped:       S = sin(omega_d t) / omega_d,  C = cos(omega_d t)
//   critically damped:  S = t,                         C = 1
//   over-damped:        S = sinh(beta t) / beta,        C = cosh(beta t)
// (over-damped products are formed from e^{r1 t}, e^{r2 t}, r = -gamma +- beta,
// and expm1, so nothing overflows or cancels).
//
// The relative velocity x' - v is monotone between consecutive zeros of x''
// (the extrema of x'), which have closed forms (extremum_after; the
// under-damped ones also first_under_extremum, whose cos/sin make each
// extremum cost one exp). The first root of sigma (v - x') = 0 is found piece
// by piece: a piece whose end has sigma (v - x') <= 0 holds exactly one root
// (monotone), which Halley's iteration safeguarded by the bracket solves to a
// few ulps. No root is missed, since every piece is checked at its end. A
// slip whose g starts >= 0 and grows (g' > 0) has no root on its first
// piece, where x'' keeps its sign: whatever sign the rounding gives its end,
// that piece is not searched (first_rest, `leaving`).
// Derivations: docs/model.md, "Slip" of "The model family".
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "stickslip/fast_math.hpp"

namespace stickslip::detail {

enum class damping_regime : unsigned char { under, critical, over };

struct damped_state {
  double y, velocity, acceleration;  // y = x - sigma a_k, x', x''
};

class damped_oscillator {
 public:
  // Preconditions: omega_0 > 0, gamma > 0, both finite.
  damped_oscillator(double omega0, double gamma) noexcept
      : w2_(omega0 * omega0), gamma_(gamma), growth_(omega0 + 2.0 * gamma) {
    const double d = (omega0 - gamma) * (omega0 + gamma);  // omega_d^2, factored
    if (d > 0.0) {
      regime_ = damping_regime::under;
      rate_ = std::sqrt(d);
    } else if (d < 0.0) {
      regime_ = damping_regime::over;
      rate_ = std::sqrt(-d);                    // beta
      r2_ = -gamma - rate_;
      r1_ = -w2_ / (gamma + rate_);             // -gamma + beta without cancellation (r1 r2 = w0^2)
    } else {
      regime_ = damping_regime::critical;
    }
  }

  [[nodiscard]] damping_regime regime() const noexcept { return regime_; }
  [[nodiscard]] double omega_squared() const noexcept { return w2_; }
  [[nodiscard]] double gamma() const noexcept { return gamma_; }

  // The slip state after time t from (y0, z0): y and x' from the basis, x''
  // from the equation of motion.
  [[nodiscard]] damped_state advance(double y0, double z0, double t) const noexcept {
    return state_of(y0, z0, at(t));
  }

  // The first zero t > after of x''(t), given x''(0) = w0 and
  // x'''(0) = w1 = -omega_0^2 x'(0) - 2 gamma w0, or +infinity. Zeros of
  //   under:  e^{-gamma t} R sin(omega_d t + phi), tan phi = w0 omega_d / (w1 + gamma w0),
  //           at omega_d t = n pi - phi (every pi / omega_d);
  //   critical: w0 + (w1 + gamma w0) t = 0, one zero;
  //   over:   A e^{r1 t} + B e^{r2 t} = 0, one zero at e^{2 beta t} = -B / A.
  [[nodiscard]] double extremum_after(double w0, double w1, double after) const noexcept {
    constexpr double inf = std::numeric_limits<double>::infinity();
    switch (regime_) {
      case damping_regime::under: {
        const double b = (w1 + gamma_ * w0) / rate_;
        if (w0 == 0.0 && b == 0.0) return inf;
        const double phi = fm::atan2(w0, b);  // R sin(theta + phi), R > 0
        // theta_n = n pi - phi; the first one beyond `after`.
        const double n = std::floor((rate_ * after + phi) / std::numbers::pi) + 1.0;
        double theta = n * std::numbers::pi - phi;
        if (theta <= rate_ * after) theta += std::numbers::pi;
        return theta / rate_;
      }
      case damping_regime::critical: {
        const double slope = w1 + gamma_ * w0;
        if (slope == 0.0) return inf;
        const double t = -w0 / slope;
        return t > after ? t : inf;
      }
      case damping_regime::over: {
        const double A = (w1 - r2_ * w0) / (r1_ - r2_), B = (r1_ * w0 - w1) / (r1_ - r2_);
        if (A == 0.0 || !(-B / A > 0.0)) return inf;
        const double t = std::log(-B / A) / (r1_ - r2_);
        return t > after ? t : inf;
      }
    }
    return inf;
  }

  // The first t in (0, horizon] where sigma (v - x'(t)) returns to 0, or
  // +infinity, for a slip that starts strictly on its sigma side or exactly
  // at x' = v moving into it (g(0) >= 0, leaving). a0 = x''(0) is passed in so that a
  // start at a band edge can give its exact value (0 when mu_s = mu_k);
  // a0_rounding bounds the error of a computed a0 (0: exact).
  // On return `at_root` holds the state there; when there is no root, the
  // state at the horizon goes to `*horizon_state` (if given), so that the
  // engine does not compute it again.
  [[nodiscard]] double first_rest(double y0, double z0, double a0, double v, double sigma,
                                  double horizon, damped_state& at_root,
                                  damped_state* horizon_state = nullptr,
                                  double a0_rounding = 0.0) const noexcept {
    constexpr double inf = std::numeric_limits<double>::infinity();
    const double w1 = -w2_ * z0 - 2.0 * gamma_ * a0;
    double lo = 0.0;
    double g_lo = sigma * (v - z0);
    // Moving away from x' = v (g(0) >= 0, g'(0) = -sigma a0 > 0): on the first
    // piece x'' keeps the sign of a0, so g only grows there and holds no
    // return, even where g is within the resolution of x' and its computed
    // end value is 0 or negative by rounding (an edge departure with mu_s a
    // few ulps above mu_k: x' - v ~ omega_0^2 v t^2 / 2 for nanoseconds; or
    // x' within an ulp of a level just switched back to). A root there would
    // clamp the mass back into the band while the belt moves on.
    // A computed a0 carries the rounding of its terms (a0_rounding, from the
    // caller: 0 when a0 is exact): within it (a start a rounding away from
    // the band's edge, where a0 is 0 in exact arithmetic) its sign says
    // nothing, and the slip is leaving only if g'' = -sigma w1 > 0 as well
    // (w1 = x'''(0)). fuzz_model_family found starts at x' = v on that edge
    // with a0 = +9e-16 and +1.1e-15 by rounding and w1 < 0: x' falls away
    // from v at once, and taking such a slip for leaving lost its return.
    const bool a0_decided = std::abs(a0) > a0_rounding;
    const bool leaving =
        g_lo >= 0.0 && sigma * a0 < 0.0 && (a0_decided || sigma * w1 < 0.0);
    // The state at the horizon, computed at most once.
    damped_state s_horizon{};
    bool have_s_horizon = false;
    const auto state_at_horizon = [&] {
      if (!have_s_horizon) s_horizon = advance(y0, z0, horizon);
      have_s_horizon = true;
      return s_horizon;
    };
    if (regime_ == damping_regime::under && rate_ * horizon < std::numbers::pi && a0_decided) {
      // A horizon shorter than half a period holds at most one zero of
      // x'' = e^{-gamma t} R sin(omega_d t + phi); none when x'' has the
      // same strict sign at both ends. Then sigma (v - x') is monotone on
      // the whole piece, and the first extremum (an atan2) is not needed:
      // this is the piece [0, horizon] the loop below would solve.
      const damped_state s_hi = state_at_horizon();
      if ((a0 > 0.0 && s_hi.acceleration > 0.0) || (a0 < 0.0 && s_hi.acceleration < 0.0)) {
        if (!leaving && returned(g_lo, sigma * (v - s_hi.velocity)))
          return solve_monotone(y0, z0, v, sigma, lo, g_lo, horizon, s_hi, false, at_root);
        if (horizon_state) *horizon_state = s_hi;
        return inf;
      }
    }
    if (regime_ == damping_regime::under) {
      // Extrema every pi / omega_d from the first, theta_1 = omega_d t_1. At
      // theta_n cos and sin are known without a call: +-(cos theta_1,
      // sin theta_1), alternating; only e^{-gamma t} is computed there.
      const under_extremum first = first_under_extremum(a0, w1);
      if (!(first.theta < inf))
        return horizon_only(y0, z0, v, sigma, g_lo, horizon, at_root, horizon_state);
      double sign = 1.0;
      for (double n = 0.0;; n += 1.0) {
        const double t_n = (first.theta + n * std::numbers::pi) / rate_;
        const bool at_horizon = !(t_n < horizon);
        const double hi = at_horizon ? horizon : t_n;
        const damped_state s_hi =
            at_horizon ? state_at_horizon()
                       : state_from(y0, z0, std::exp(-gamma_ * hi), sign * first.cos,
                                    sign * first.sin / rate_);
        const bool first_leaving = leaving && n == 0.0;
        const double g_hi = sigma * (v - s_hi.velocity);
        if (!first_leaving && returned(g_lo, g_hi))
          return solve_monotone(y0, z0, v, sigma, lo, g_lo, hi, s_hi, !at_horizon, at_root);
        if (at_horizon) {
          if (horizon_state) *horizon_state = s_hi;
          return inf;
        }
        lo = hi;
        g_lo = first_leaving ? std::max(g_hi, 0.0) : g_hi;
        sign = -sign;
      }
    }
    // Critically and over-damped: at most one extremum.
    const double extremum = extremum_after(a0, w1, 0.0);
    if (extremum < horizon) {
      const damped_state s_hi = advance(y0, z0, extremum);
      const double g_hi = sigma * (v - s_hi.velocity);
      if (!leaving && returned(g_lo, g_hi))
        return solve_monotone(y0, z0, v, sigma, lo, g_lo, extremum, s_hi, true, at_root);
      lo = extremum;
      g_lo = leaving ? std::max(g_hi, 0.0) : g_hi;
    } else if (leaving) {  // [0, horizon] is the first piece
      if (horizon_state) *horizon_state = state_at_horizon();
      return inf;
    }
    return horizon_only(y0, z0, v, sigma, g_lo, horizon, at_root, horizon_state, lo);
  }

 private:
  // f0..g1 times scale. scale is 1 unless the decay factor is below
  // tiny_decay: then f0..g1 are formed without it and the state is scaled
  // last, so that its sign survives (at e^{-gamma t} ~ 1e-300 the products
  // e S, e C are subnormal, and their sums could come out of either sign:
  // fuzz_model_family found a return to x' = v on a resting level, v = 0,
  // missed that way at gamma t_a = 735).
  struct basis {
    double f0, f1, g0, g1, scale = 1.0;
  };
  static constexpr double tiny_decay = 1e-150;

  // Whether g = sigma (v - x') went from g_lo at the start of a piece to
  // g_hi <= 0 at its end: a return to x' = v within it. From a start exactly
  // at x' = v (g_lo == 0: leaving an edge or a reversal) g_hi == 0 is not a
  // return: x' has not yet left v by a representable amount (near the edge
  // with mu_s a few ulps above mu_k, x' - v ~ omega_0^2 v t^2 / 2 stays below
  // ulp(v) for nanoseconds), and a root there would put the mass back at
  // the edge while the belt moves on.
  [[nodiscard]] static bool returned(double g_lo, double g_hi) noexcept {
    return g_hi < 0.0 || (g_hi == 0.0 && g_lo > 0.0);
  }

  struct under_extremum {
    double theta, cos, sin;  // the first extremum's phase omega_d t_1 > 0
  };
  // Under-damped: x'' = e^{-gamma t} R sin(theta + phi), phi = atan2(w0, b),
  // b = (w1 + gamma w0) / omega_d; zeros at theta_n = n pi - phi, where
  // cos theta_n = (-1)^n cos phi, sin theta_n = -(-1)^n sin phi.
  [[nodiscard]] under_extremum first_under_extremum(double w0, double w1) const noexcept {
    constexpr double inf = std::numeric_limits<double>::infinity();
    const double b = (w1 + gamma_ * w0) / rate_;
    if (w0 == 0.0 && b == 0.0) return {inf, 0.0, 0.0};
    const double phi = fm::atan2(w0, b);
    const double r = std::sqrt(w0 * w0 + b * b);  // magnitudes are validated: no overflow
    double n = std::floor(phi / std::numbers::pi) + 1.0;
    double theta = n * std::numbers::pi - phi;
    if (theta <= 0.0) {
      theta += std::numbers::pi;
      n += 1.0;
    }
    const double parity = std::fmod(n, 2.0) == 0.0 ? 1.0 : -1.0;
    return {theta, parity * b / r, -parity * w0 / r};
  }

  // The state from e = e^{-gamma t}, C and S of the basis (under-damped:
  // C = cos omega_d t, S = sin(omega_d t) / omega_d).
  [[nodiscard]] damped_state state_from(double y0, double z0, double e, double c,
                                        double s) const noexcept {
    return state_of(y0, z0, e < tiny_decay ? scaled(e, c, s) : decayed(e * c, e * s));
  }
  // The state from (y0, z0) through a basis: y and x' from it, x'' from the
  // equation of motion, all times the basis's scale last.
  [[nodiscard]] damped_state state_of(double y0, double z0, const basis& b) const noexcept {
    const double y = y0 * b.f0 + z0 * b.f1;
    const double z = y0 * b.g0 + z0 * b.g1;
    const double a = -w2_ * y - 2.0 * gamma_ * z;
    if (b.scale == 1.0) return {y, z, a};
    return {b.scale * y, b.scale * z, b.scale * a};
  }

  // The last piece, from lo to the horizon, has no extremum inside.
  [[nodiscard]] double horizon_only(double y0, double z0, double v, double sigma, double g_lo,
                                    double horizon, damped_state& at_root,
                                    damped_state* horizon_state, double lo = 0.0) const noexcept {
    if (!(lo < horizon)) return std::numeric_limits<double>::infinity();
    const damped_state s_hi = advance(y0, z0, horizon);
    if (returned(g_lo, sigma * (v - s_hi.velocity)))
      return solve_monotone(y0, z0, v, sigma, lo, g_lo, horizon, s_hi, false, at_root);
    if (horizon_state) *horizon_state = s_hi;
    return std::numeric_limits<double>::infinity();
  }

  [[nodiscard]] basis at(double t) const noexcept {
    double e_s, e_c;  // e^{-gamma t} S and e^{-gamma t} C
    switch (regime_) {
      case damping_regime::under: {
        // libm, like exp: the damped model runs on the scalar engine only, so
        // it needs no kernel shared with the lane engine, and glibc's sincos
        // (one range reduction for both, any phase) is faster than two
        // one-lane Highway calls (bench/family_vs_paper.sh).
        const double e = std::exp(-gamma_ * t);
        double sn, cs;
        ::sincos(rate_ * t, &sn, &cs);
        if (e < tiny_decay) return scaled(e, cs, sn / rate_);
        e_s = e * sn / rate_;
        e_c = e * cs;
        break;
      }
      case damping_regime::critical: {
        const double e = std::exp(-gamma_ * t);
        if (e < tiny_decay) return scaled(e, 1.0, t);
        e_s = e * t;
        e_c = e;
        break;
      }
      case damping_regime::over:
      default: {
        // (e1 - e2) / (2 beta) and (e1 + e2) / 2 with e1 = e^{r1 t},
        // e2 = e^{r2 t}: for 2 beta t < 1 as e2 expm1(2 beta t) (no
        // cancellation, one exp and one expm1, e1 = e2 (1 + expm1)); beyond,
        // from e1 and e2 themselves (e2 may underflow where e^{2 beta t}
        // would overflow: never 0 * inf).
        const double spread = 2.0 * rate_ * t;
        if (spread < 1.0) {
          const double e2 = std::exp(r2_ * t), em = std::expm1(spread);
          if (e2 < tiny_decay) return scaled(e2, 1.0 + 0.5 * em, em / (2.0 * rate_));
          e_s = e2 * em / (2.0 * rate_);
          e_c = e2 + 0.5 * (e2 * em);
        } else {
          const double e1 = std::exp(r1_ * t), e2 = std::exp(r2_ * t);
          if (e1 < tiny_decay) {  // e2 / e1 = e^{-spread} < 1
            const double ratio = std::exp(-spread);
            return scaled(e1, 0.5 * (1.0 + ratio), (1.0 - ratio) / (2.0 * rate_));
          }
          e_s = (e1 - e2) / (2.0 * rate_);
          e_c = 0.5 * (e1 + e2);
        }
        break;
      }
    }
    return decayed(e_c, e_s);
  }
  // The basis from e C and e S (the decay factor inside), or from C and S
  // with the decay factor e kept apart.
  [[nodiscard]] basis decayed(double e_c, double e_s) const noexcept {
    return {e_c + gamma_ * e_s, e_s, -w2_ * e_s, e_c - gamma_ * e_s};
  }
  [[nodiscard]] basis scaled(double e, double c, double s) const noexcept {
    basis b = decayed(c, s);
    b.scale = e;
    return b;
  }

  // One root of g(t) = sigma (v - x'(t)) in (lo, hi], g(lo) > 0 >= g(hi), g
  // monotone: Halley steps (g' = -sigma x'', g'' = -sigma x''') from the
  // secant point, kept inside the bracket (else bisection). Stops when a
  // correction is within a few ulps of t (t is then the root to a few ulps:
  // the iteration has reached the rounding noise of g) or the bracket is that
  // narrow.
  [[nodiscard]] double solve_monotone(double y0, double z0, double v, double sigma, double lo,
                                      double g_lo, double hi, damped_state s_hi,
                                      bool vertex_at_hi, damped_state& at_root) const noexcept {
    constexpr double eps = std::numeric_limits<double>::epsilon();
    const double g_hi = sigma * (v - s_hi.velocity);
    // Start: where g vanishes on the parabola with its vertex at an extremum
    // end (g' = 0 there) through the other end, else the secant point.
    double t = 0.5 * (lo + hi);
    if (g_lo - g_hi > 0.0)
      t = vertex_at_hi ? hi - (hi - lo) * std::sqrt(-g_hi / (g_lo - g_hi))
                       : lo + (hi - lo) * (g_lo / (g_lo - g_hi));
    // Halley creeps where g is flat: in an over-damped tail (x'' ~ 1e-200 far
    // beyond the root) each step moves t by about 2 / |r1| while g does not
    // change, so 200 steps from a secant point deep in a long horizon never
    // reached the root, and the bracket's far end was returned instead (a
    // missed stick that depended on t_a). A step that does not halve |g|
    // on the same side of the root is followed by a bisection instead; a
    // Halley step converging normally shrinks |g| far more.
    double g_prev = 0.0;
    bool bisect_next = false;
    for (int i = 0; i < 400; ++i) {
      if (bisect_next || !(t > lo && t < hi)) t = 0.5 * (lo + hi);
      if (t <= lo || t >= hi) break;  // the bracket is two adjacent doubles
      const damped_state s = advance(y0, z0, t);
      const double g = sigma * (v - s.velocity);
      bisect_next = i > 0 && (g <= 0.0) == (g_prev <= 0.0) && std::abs(g) > 0.5 * std::abs(g_prev);
      g_prev = g;
      if (g <= 0.0) {
        hi = t;
        s_hi = s;
      } else {
        lo = t;
      }
      const double slope = -sigma * s.acceleration;
      const double curvature = sigma * (w2_ * s.velocity + 2.0 * gamma_ * s.acceleration);
      const double denominator = 2.0 * slope * slope - g * curvature;
      const double step = denominator != 0.0 ? 2.0 * g * slope / denominator : 0.0;
      // A small step means a root only if g is as small as the step says
      // (g ~ slope step near a simple root). In a tail where x'' has
      // underflowed the step is tiny while g is far from 0: fuzz_model_family
      // found such a t (18.19 s, the root at 2.9e-9 s) taken for the root on
      // a 72.8-s bracket whose far end had underflowed to a zero state.
      const bool g_is_small =
          std::abs(g) <= 2.0 * std::abs(slope * step) +
                             64.0 * eps * (std::abs(v) + std::abs(s.velocity));
      if (slope != 0.0 && g_is_small && std::abs(step) <= 4.0 * eps * t) {
        at_root = s;
        return t;
      }
      // A last step this small leaves a Halley error ~ (growth step)^3 below
      // the rounding of t: take it without another closed-form evaluation,
      // moving the state along its own Taylor series (third order, the next
      // term is smaller still).
      if (slope != 0.0 && g_is_small && std::abs(step) * growth_ <= 2e-6 && t - step > lo &&
          t - step <= hi) {
        const double h = -step;
        const double jerk = -w2_ * s.velocity - 2.0 * gamma_ * s.acceleration;
        at_root = {s.y + h * (s.velocity + h * (0.5 * s.acceleration + h * jerk / 6.0)), v,
                   s.acceleration + h * jerk};
        return t + h;
      }
      if (hi - lo <= 4.0 * eps * hi) break;
      t = t - step;
    }
    at_root = s_hi;
    return hi;
  }

  double w2_, gamma_, growth_;  // growth_ = omega_0 + 2 gamma bounds every rate of the slip
  damping_regime regime_ = damping_regime::critical;
  double rate_ = 0.0;  // omega_d (under) or beta (over)
  double r1_ = 0.0, r2_ = 0.0;
};

}  // namespace stickslip::detail
