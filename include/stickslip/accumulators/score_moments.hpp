// Moments of a per-realization value X against the centred number of belt
// switches K = N - lambda t_a of its realization, for two estimators that
// use the Poisson switching (docs/precision.md):
//
//   likelihood-ratio (score) derivative: the path density of the switch
//   times on [0, t_a] is lambda^N exp(-lambda t_a), so its score is
//   S = d/dlambda log(...) = N / lambda - t_a = K / lambda, and
//       d E[X] / dlambda = E[X S] = Cov(X, K) / lambda      (E[K] = 0).
//   Estimate: D = (mean(X K) - mean(X) mean(K)) / lambda, the mean of
//   (X_i - mean X) S_i; delta method: Var(D) ~ Var((X - mu_X) K) / (n lambda^2).
//
//   control variate: K has the known mean 0, so
//       X_cv = mean(X) - beta mean(K),  beta = Cov(X, K) / Var(K),
//   is unbiased up to O(1/n) with the residual variance
//   Var(X) (1 - rho^2) per realization; the reduction factor is 1/(1 - rho^2).
//
// Accumulated as plain sums of K, K^2, X K, X K^2, X^2 K^2: merging is
// addition (exact up to rounding; merged in block order, so reproducible),
// and K is centred by its known mean, so the sums do not cancel. X's own
// mean and variance come from its mean_variance.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "stickslip/accumulators/mean_variance.hpp"

namespace stickslip {

// A count and five running sums, merged by addition (in block order, so
// the bits are reproducible): the storage of score_moments and
// causal_score_moments, which differ in what they sum.
template <class Derived>
class five_sums {
 public:
  Derived& operator+=(const Derived& o) noexcept {
    n_ += o.n_;
    for (int i = 0; i < 5; ++i) s_[i] += o.s_[i];
    return static_cast<Derived&>(*this);
  }
  [[nodiscard]] std::uint64_t count() const noexcept { return n_; }
  // The sums in their fixed order (serialization).
  [[nodiscard]] double sum(int i) const noexcept { return s_[i]; }
  static Derived from_raw(std::uint64_t n, const double (&s)[5]) noexcept {
    Derived m;
    m.n_ = n;
    for (int i = 0; i < 5; ++i) m.s_[i] = s[i];
    return m;
  }
  friend bool operator==(const five_sums&, const five_sums&) = default;

 protected:
  void add_sums(double a, double b, double c, double d, double e) noexcept {
    ++n_;
    s_[0] += a;
    s_[1] += b;
    s_[2] += c;
    s_[3] += d;
    s_[4] += e;
  }

 private:
  std::uint64_t n_ = 0;
  double s_[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
};

// The sums K, K^2, X K, X K^2, X^2 K^2.
class score_moments : public five_sums<score_moments> {
 public:
  // One realization: its value x and K = N - lambda t_a.
  void add(double x, double k) noexcept {
    const double xk = x * k;
    add_sums(k, k * k, xk, xk * k, xk * xk);
  }
};

// An estimate with its standard error; NaN below 3 realizations.
struct estimate {
  double value = NAN;
  double std_error = NAN;
  [[nodiscard]] double ci95_half_width() const noexcept { return z95 * std_error; }
};

// d E[X] / dlambda by the likelihood ratio (score) of the Poisson switching.
// Preconditions: m and x hold the same realizations, rate = lambda > 0.
[[nodiscard]] inline estimate score_derivative(const score_moments& m, const mean_variance& x,
                                               double rate) noexcept {
  const auto n = static_cast<double>(m.count());
  if (m.count() < 3 || x.count() != m.count()) return {};
  const double xm = x.mean();
  const double k = m.sum(0) / n, kk = m.sum(1) / n, xk = m.sum(2) / n;
  const double xkk = m.sum(3) / n, xxkk = m.sum(4) / n;
  const double d = xk - xm * k;  // mean((X_i - mean X) K_i)
  // Var((X - mu) K) = E[X^2 K^2] - 2 mu E[X K^2] + mu^2 E[K^2] - (E[(X - mu) K])^2
  const double var = std::max(0.0, xxkk - 2.0 * xm * xkk + xm * xm * kk - d * d);
  return {d / rate, std::sqrt(var / (n - 1.0)) / rate};
}

// The control-variate mean of X with control K (known mean 0) and the
// variance reduction factor Var(X) / residual variance.
struct controlled_mean {
  estimate mean;
  double variance_reduction = NAN;
};
[[nodiscard]] inline controlled_mean control_variate_mean(const score_moments& m,
                                                          const mean_variance& x) noexcept {
  const auto n = static_cast<double>(m.count());
  if (m.count() < 3 || x.count() != m.count()) return {};
  const double xm = x.mean();
  const double k = m.sum(0) / n, kk = m.sum(1) / n, xk = m.sum(2) / n;
  const double cov = (xk - xm * k) * n / (n - 1.0);  // sample Cov(X, K)
  const double vk = (kk - k * k) * n / (n - 1.0);    // sample Var(K)
  const double vx = x.variance();
  if (!(vk > 0.0)) return {{xm, x.std_error()}, 1.0};
  const double beta = cov / vk;
  const double resid = std::max(0.0, (vx - cov * beta) * (n - 1.0) / (n - 2.0));
  return {{xm - beta * k, std::sqrt(resid / n)}, resid > 0.0 ? vx / resid : INFINITY};
}

// The causal likelihood-ratio derivative of the stick fraction R over the
// switch rate lambda (docs/precision.md, "The causal score"). With
// M(t) = N(t)/lambda - t, the score of the switching observed up to t (a
// martingale: its later increments have mean 0 whatever happened before),
//   d E[R]/dlambda = E[R M(t_a)] = E[Z],  Z = (1/t_a) int_0^t_a stick(t) M(t) dt,
// because whether the mass sticks at t is decided by the path up to t, so
// the increments of M after t drop out of stick(t) M(t_a) in the mean. They
// carry about half of the variance of (R - E R) M(t_a), and with
// Y = (1/t_a) int_0^t_a M(t) dt (mean 0) as a control,
//   D = mean(Z) - beta mean(Y),  beta = Cov(Z, Y) / Var(Y) (about E[R]),
// removes the part of Z that is the mean stick fraction times M (without
// it Z alone is far noisier than the full score). Per realization at mu =
// 0.5, lambda = 3.5: sd 0.044 against 0.061 for the full score
// (docs/precision.md).
// The sums Z, Y, Z^2, Y^2, Z Y.
class causal_score_moments : public five_sums<causal_score_moments> {
 public:
  void add(double z, double y) noexcept { add_sums(z, y, z * z, y * y, z * y); }
  // mean(Z) - baseline x mean(Y) with a fixed baseline: exactly unbiased
  // (the peak finder's groups use the stick fraction of its scan).
  [[nodiscard]] double derivative_with_baseline(double baseline) const noexcept {
    const auto n = static_cast<double>(count());
    return count() == 0 ? NAN : sum(0) / n - baseline * (sum(1) / n);
  }
};

// D with the fitted beta (unbiased up to O(1/n), like control_variate_mean)
// and the standard error of the residual; NaN below 3 realizations.
[[nodiscard]] inline estimate causal_score_derivative(const causal_score_moments& m) noexcept {
  const auto n = static_cast<double>(m.count());
  if (m.count() < 3) return {};
  const double z = m.sum(0) / n, y = m.sum(1) / n;
  const double vz = (m.sum(2) / n - z * z) * n / (n - 1.0);
  const double vy = (m.sum(3) / n - y * y) * n / (n - 1.0);
  const double cov = (m.sum(4) / n - z * y) * n / (n - 1.0);
  if (!(vy > 0.0)) return {z, std::sqrt(std::max(0.0, vz) / n)};
  const double beta = cov / vy;
  const double resid = std::max(0.0, (vz - cov * beta) * (n - 1.0) / (n - 2.0));
  return {z - beta * y, std::sqrt(resid / n)};
}

}  // namespace stickslip
