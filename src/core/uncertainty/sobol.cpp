// The pick-freeze accumulator and the Sobol' estimators
// (uncertainty/sobol.hpp; the formulas and their OpenTURNS forms are there).
#include "stickslip/uncertainty/sobol.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "stickslip/error.hpp"

namespace stickslip {
namespace {

// The layout of z for d inputs (dimension 5 + 3d).
struct z_layout {
  std::size_t d;
  [[nodiscard]] static constexpr std::size_t a() noexcept { return 0; }  // y_A
  [[nodiscard]] static constexpr std::size_t b() noexcept { return 1; }  // y_B
  [[nodiscard]] static constexpr std::size_t e(std::size_t i) noexcept { return 2 + i; }  // y_E[i]
  [[nodiscard]] std::size_t aa() const noexcept { return 2 + d; }          // y_A^2
  [[nodiscard]] std::size_t ab() const noexcept { return 3 + d; }          // y_A y_B
  [[nodiscard]] std::size_t replicate() const noexcept { return 4 + d; }   // (y_A - y_A2)^2
  [[nodiscard]] std::size_t be(std::size_t i) const noexcept { return 5 + d + i; }      // y_B y_E[i]
  [[nodiscard]] std::size_t jansen(std::size_t i) const noexcept { return 5 + 2 * d + i; }  // (y_A - y_E[i])^2
  [[nodiscard]] std::size_t size() const noexcept { return sobol_moments::dimension(d); }
};

// Index of (k, l), k <= l, in a row-major upper triangle of dimension n.
constexpr std::size_t upper(std::size_t n, std::size_t k, std::size_t l) noexcept {
  return k * n - k * (k - 1) / 2 + (l - k);
}

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

}  // namespace

sobol_moments::sobol_moments(std::size_t inputs)
    : inputs_(inputs),
      mean_(dimension(inputs), 0.0),
      comoment_(dimension(inputs) * (dimension(inputs) + 1) / 2, 0.0) {}

// Welford, for the vector z: with delta = z - mean_(n-1) and
// mean_n = mean_(n-1) + delta / n, the co-moment grows by
// delta_k (z_l - mean_n,l) = (n-1)/n delta_k delta_l.
void sobol_moments::add(double y_a, double y_a2, double y_b, std::span<const double> y_e) {
  const z_layout L{inputs_};
  const std::size_t n = L.size();
  // The row's z and delta, on the stack for up to 8 inputs.
  constexpr std::size_t on_stack = sobol_moments::dimension(8);
  std::array<double, 2 * on_stack> buffer;
  std::vector<double> heap;
  double* z = buffer.data();
  if (n > on_stack) {
    heap.resize(2 * n);
    z = heap.data();
  }
  double* delta = z + n;
  z[L.a()] = y_a;
  z[L.b()] = y_b;
  z[L.aa()] = y_a * y_a;
  z[L.ab()] = y_a * y_b;
  z[L.replicate()] = (y_a - y_a2) * (y_a - y_a2);
  for (std::size_t i = 0; i < inputs_; ++i) {
    z[L.e(i)] = y_e[i];
    z[L.be(i)] = y_b * y_e[i];
    z[L.jansen(i)] = (y_a - y_e[i]) * (y_a - y_e[i]);
  }
  ++rows_;
  const double inv_n = 1.0 / static_cast<double>(rows_);
  for (std::size_t k = 0; k < n; ++k) {
    delta[k] = z[k] - mean_[k];
    mean_[k] += delta[k] * inv_n;
  }
  std::size_t at = 0;
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t l = k; l < n; ++l) comoment_[at++] += delta[k] * (z[l] - mean_[l]);
}

// Chan, Golub and LeVeque (1979): with delta = mean_b - mean_a and
// n = n_a + n_b, mean = mean_a + delta n_b / n and
// C = C_a + C_b + delta delta^T n_a n_b / n.
sobol_moments& sobol_moments::operator+=(const sobol_moments& o) {
  if (o.rows_ == 0) {
    if (rows_ == 0 && inputs_ == 0) *this = o;
    return *this;
  }
  if (rows_ == 0) {
    *this = o;
    return *this;
  }
  const std::size_t n = mean_.size();
  const double na = static_cast<double>(rows_), nb = static_cast<double>(o.rows_);
  const double total = na + nb;
  std::vector<double> delta(n);
  for (std::size_t k = 0; k < n; ++k) delta[k] = o.mean_[k] - mean_[k];
  const double w = na * nb / total;
  std::size_t at = 0;
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t l = k; l < n; ++l, ++at)
      comoment_[at] += o.comoment_[at] + delta[k] * delta[l] * w;
  for (std::size_t k = 0; k < n; ++k) mean_[k] += delta[k] * (nb / total);
  rows_ += o.rows_;
  return *this;
}

sobol_moments sobol_moments::from_state(std::size_t inputs, std::uint64_t rows,
                                        std::vector<double> means,
                                        std::vector<double> comoments) {
  const std::size_t n = dimension(inputs);
  if (means.size() != n || comoments.size() != n * (n + 1) / 2)
    throw error(exit_code::invalid_input,
                fmt::format("pick-freeze moments of {} inputs: {} means and {} co-moments, "
                            "expected {} and {}",
                            inputs, means.size(), comoments.size(), n, n * (n + 1) / 2));
  sobol_moments m;
  m.inputs_ = inputs;
  m.rows_ = rows;
  m.mean_ = std::move(means);
  m.comoment_ = std::move(comoments);
  return m;
}

double sobol_estimates::max_half_width() const noexcept {
  double worst = 0.0;
  auto take = [&](const interval_estimate& e) {
    const double h = e.half_width();
    worst = std::isnan(h) || std::isnan(worst) ? nan : std::max(worst, h);
  };
  for (const auto& e : first_order) take(e);
  for (const auto& e : total_order) take(e);
  for (const auto& e : response_first_order) take(e);
  take(parameter_share);
  take(intrinsic_share);
  return worst;
}

namespace {

// The delta method: an estimate that is a smooth function F of E z has the
// asymptotic variance grad F' Cov(z) grad F / N; Cov(z) = C / (N - 1).
class delta_method {
 public:
  explicit delta_method(const sobol_moments& m)
      : n_(m.means().size()), rows_(static_cast<double>(m.rows())), c_(m.comoments()) {}

  [[nodiscard]] interval_estimate interval(double value, const std::vector<double>& grad) const {
    double q = 0.0;
    for (std::size_t k = 0; k < n_; ++k) {
      if (grad[k] == 0.0) continue;
      for (std::size_t l = 0; l < n_; ++l)
        if (grad[l] != 0.0)
          q += grad[k] * grad[l] * c_[k <= l ? upper(n_, k, l) : upper(n_, l, k)];
    }
    // A quadratic form of a covariance is >= 0; rounding can make it -0.
    const double variance = std::max(q, 0.0) / (rows_ - 1.0) / rows_;
    const double h = sobol_z95 * std::sqrt(variance);
    if (std::isnan(value) || std::isnan(h)) return {nan, nan, nan};
    return {value, value - h, value + h};
  }

 private:
  std::size_t n_;
  double rows_;
  const std::vector<double>& c_;
};

// grad (x / y) = (grad x - (x / y) grad y) / y.
std::vector<double> ratio_gradient(double x, const std::vector<double>& gx, double y,
                                   const std::vector<double>& gy) {
  std::vector<double> g(gx.size());
  const double r = x / y;
  for (std::size_t k = 0; k < g.size(); ++k) g[k] = (gx[k] - r * gy[k]) / y;
  return g;
}

sobol_estimates all_nan(const sobol_moments& m) {
  sobol_estimates s;
  s.rows = m.rows();
  s.mean = s.variance = s.intrinsic_variance = nan;
  const interval_estimate none{nan, nan, nan};
  s.first_order.assign(m.inputs(), none);
  s.total_order.assign(m.inputs(), none);
  s.response_first_order.assign(m.inputs(), none);
  s.parameter_share = s.intrinsic_share = none;
  return s;
}

}  // namespace

sobol_estimates sobol_indices(const sobol_moments& m, first_order_form form) {
  const std::size_t d = m.inputs();
  const z_layout L{d};
  const std::size_t n = L.size();
  if (m.rows() < 2 || m.means().size() != n) return all_nan(m);
  const auto& mu = m.means();
  const auto& C = m.comoments();
  auto cov = [&](std::size_t k, std::size_t l) { return C[k <= l ? upper(n, k, l) : upper(n, l, k)]; };
  const double N = static_cast<double>(m.rows());
  const double a = mu[L.a()], b = mu[L.b()];
  double sum_e = 0.0;
  for (std::size_t i = 0; i < d; ++i) sum_e += mu[L.e(i)];
  const double k_c = 1.0 / static_cast<double>(2 + d);
  const double c = (a + b + sum_e) * k_c;  // the mean of every y_A, y_B, y_E[i]

  // Point estimates (the header's finite-sample forms, from centred co-moments).
  const double V = cov(L.a(), L.a()) / (N - 1.0);
  const double s2 = mu[L.replicate()] / 2.0;
  const double G = V - s2;
  if (!std::isfinite(V)) return all_nan(m);
  if (V == 0.0) {  // no indices (0 / 0); the mean and the variance are estimates
    sobol_estimates s = all_nan(m);
    s.mean = c;
    s.variance = 0.0;
    s.intrinsic_variance = s2;
    // Constant over the design only if every output column is (y_A alone
    // can be, by chance, for a discrete statistic on few rows: a review).
    bool constant = s2 == 0.0 && cov(L.b(), L.b()) == 0.0 && b == a;
    for (std::size_t i = 0; i < d; ++i)
      constant = constant && cov(L.e(i), L.e(i)) == 0.0 && mu[L.e(i)] == a;
    s.constant_statistic = constant;
    return s;
  }

  // Limits' gradients with respect to E z, at the sample means.
  auto zero = [&] { return std::vector<double>(n, 0.0); };
  std::vector<double> gV = zero(), gs2 = zero();
  gV[L.aa()] = 1.0;  // V = E y_A^2 - (E y_A)^2
  gV[L.a()] = -2.0 * a;
  gs2[L.replicate()] = 0.5;  // s2 = E (y_A - y_A2)^2 / 2
  std::vector<double> gG(n);
  for (std::size_t k = 0; k < n; ++k) gG[k] = gV[k] - gs2[k];

  sobol_estimates s;
  s.rows = m.rows();
  s.mean = c;
  s.variance = V;
  s.intrinsic_variance = s2;
  const delta_method dm(m);
  const interval_estimate none{nan, nan, nan};
  for (std::size_t i = 0; i < d; ++i) {
    const double e = mu[L.e(i)];
    double Vi = 0.0;
    std::vector<double> gVi = zero();
    if (form == first_order_form::openturns_saltelli) {
      // V_i -> E[y_B y_E] - a b + c (a - e): OpenTURNS's form with its
      // centring by c, whose sample value moves with a, b and every e.
      Vi = (cov(L.b(), L.e(i)) + N * (e - c) * (b - c)) / (N - 1.0) - (a - c) * (b - c);
      gVi[L.be(i)] = 1.0;
      const double dc = k_c * (a - e);  // d/dc of c (a - e), times dc/dz
      for (std::size_t j = 0; j < d; ++j) gVi[L.e(j)] = dc;
      gVi[L.e(i)] += -c;
      gVi[L.a()] = -b + c + dc;
      gVi[L.b()] = -a + dc;
    } else {
      // V_i = mean(y_B (y_E - y_A)) -> E[y_B y_E] - E[y_A y_B].
      Vi = (cov(L.b(), L.e(i)) - cov(L.a(), L.b())) / N + b * (e - a);
      gVi[L.be(i)] = 1.0;
      gVi[L.ab()] = -1.0;
    }
    // VT_i = (sum (y_A - y_E)^2 - sum (y_A - y_A2)^2) / (2N - 1)
    //     -> (E (y_A - y_E)^2 - E (y_A - y_A2)^2) / 2.
    const double VTi = N * (mu[L.jansen(i)] - mu[L.replicate()]) / (2.0 * N - 1.0);
    std::vector<double> gVTi = zero();
    gVTi[L.jansen(i)] = 0.5;
    gVTi[L.replicate()] = -0.5;
    s.first_order.push_back(G != 0.0 ? dm.interval(Vi / G, ratio_gradient(Vi, gVi, G, gG)) : none);
    s.total_order.push_back(G != 0.0 ? dm.interval(VTi / G, ratio_gradient(VTi, gVTi, G, gG))
                                     : none);
    s.response_first_order.push_back(dm.interval(Vi / V, ratio_gradient(Vi, gVi, V, gV)));
  }
  s.intrinsic_share = dm.interval(s2 / V, ratio_gradient(s2, gs2, V, gV));
  s.parameter_share = dm.interval(G / V, ratio_gradient(G, gG, V, gV));
  return s;
}

std::string undefined_indices_note(const sobol_estimates& e, std::string_view statistic) {
  if (e.variance != 0.0) return {};
  if (!e.constant_statistic)
    return fmt::format(
        "{} is the same in every row's first output (variance 0) though not in the others: "
        "too few rows ({}) for Sobol' indices, which are written as NaN; run more --samples",
        statistic, e.rows);
  return fmt::format(
      "{} is constant over the design's {} rows (mean {}, variance 0): its Sobol' indices and "
      "shares are 0 / 0, undefined, and written as NaN",
      statistic, e.rows, e.mean);
}

namespace {

// The largest finite half-width of some intervals (0 when none is finite):
// a NaN index (V - s2 = 0) does not hide the others' width.
struct widest_finite {
  double width = 0.0;
  void operator()(const interval_estimate& e) {
    if (const double h = e.half_width(); std::isfinite(h)) width = std::max(width, h);
  }
  void operator()(const std::vector<interval_estimate>& es) {
    for (const auto& e : es) (*this)(e);
  }
};

}  // namespace

std::string uninformative_indices_note(const sobol_estimates& e, std::string_view statistic) {
  if (!(e.variance > 0.0)) return {};  // undefined_indices_note's case
  // Over Var Y, which the rows estimate well: the response's first-order
  // indices and the shares. Wide here means too few rows.
  widest_finite response;
  response(e.response_first_order), response(e.parameter_share), response(e.intrinsic_share);
  // The mean response's indices divide by Var g = Var Y - s2, the
  // parameters' share of Var Y: their intervals are those over Var Y
  // magnified by about 1 / share. When the share's whole interval is below
  // 1/4 (a magnification over 4) the share is why they are wide (a review:
  // "so few rows" was said at 4,000); otherwise the rows are (a share of
  // 0.06 [-0.23, 0.35] at 64 rows is the rows' doing: a new user).
  widest_finite mean;
  mean(e.first_order), mean(e.total_order);
  const bool small_share = e.parameter_share.high < 0.25;
  if (response.width > 0.5 || (mean.width > 0.5 && !small_share))
    return fmt::format(
        "the Sobol' estimates of {} from {} rows say little: a 95 % interval is wider than "
        "[0, 1], the range of an index (largest half-width {:.3g}), and these intervals, "
        "asymptotic (delta method), may not hold at so few rows; run more rows (--samples, or "
        "a larger --max-samples with --target-halfwidth)",
        statistic, e.rows, std::max(response.width, mean.width));
  if (mean.width > 0.5)
    return fmt::format(
        "the Sobol' indices of E[{0} | theta] have 95 % intervals wider than [0, 1] (largest "
        "half-width {1:.3g}): they divide by the parameters' share of Var {0}, here {2:.3g} "
        "[{3:.3g}, {4:.3g}], which is small (below 1/4) and magnifies their intervals by about "
        "1 / share, so that more rows narrow them only slowly; the first order in {0} and the "
        "shares are this study's better-determined estimates",
        statistic, mean.width, e.parameter_share.value, e.parameter_share.low, e.parameter_share.high);
  return {};
}

std::string sensitivity_warning(const sobol_estimates& e, std::string_view statistic) {
  auto note = undefined_indices_note(e, statistic);
  return note.empty() ? uninformative_indices_note(e, statistic) : note;
}

}  // namespace stickslip
