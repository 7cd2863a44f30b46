// Sobol' indices of a stochastic simulator by pick-freeze (docs/uncertainty.md).
//
// The output of one realization is Y = STAT(theta, omega): theta the
// uncertain parameters, omega the realization's own randomness (initial
// conditions, belt). g(theta) = E[Y | theta] is the mean response, and
//   Var Y = Var g(theta) + E Var(Y | theta)
// splits the spread into the parameters' share and the intrinsic share.
//
// One sample row j evaluates, each with its own independent omega:
//   y_A   at theta_A,   y_A2 at theta_A again (a replicate),
//   y_B   at theta_B,   y_E[i] at theta_A with input i taken from theta_B.
// This is OpenTURNS's SobolIndicesExperiment (1.20) row for row: its sample
// is the blocks A (rows 0..N-1), B (N..2N-1), then one block E_i per input
// (rows (2+i)N..(3+i)N-1) that is A with column i replaced by B's column i.
// Row j of our design is (A_j, A_j again, B_j, E_0j, ..., E_(d-1)j); a
// deterministic model has y_A2 = y_A.
//
// Estimators, over N rows, with c the mean of every y_A, y_B and y_E[i]
// (not y_A2) and C(u, v) = sum_j (u_j - mean u)(v_j - mean v):
//   V     = C(y_A, y_A) / (N - 1)                       -> Var Y
//   s2    = sum (y_A - y_A2)^2 / (2N)                   -> E Var(Y | theta)
//   V_i   = [C(y_B, y_E[i]) + N (mean y_E[i] - c)(mean y_B - c)] / (N - 1)
//           - (mean y_A - c)(mean y_B - c)              -> Var E[Y | theta_i]
//   VT_i  = [sum (y_A - y_E[i])^2 - sum (y_A - y_A2)^2] / (2N - 1)
//                                                       -> E Var(g | theta_~i)
//   first order of g      S_i   = V_i / (V - s2)
//   total order of g      T_i   = VT_i / (V - s2)
//   first order in Y      S_i^Y = V_i / V
//   shares                (V - s2) / V and s2 / V
// V_i is OpenTURNS's SaltelliSensitivityAlgorithm (Saltelli 2002: the
// product sum over N - 1 minus the product of the means, after OpenTURNS
// centres every output by c; the first-order normalization is its yA sample
// variance), and VT_i with s2 = 0 is its JansenSensitivityAlgorithm (Jansen
// 1999, with OpenTURNS's divisor 2N - 1 instead of 2N), as read in
// OpenTURNS 1.20's lib/src/Uncertainty/Algorithm/Sensitivity/
// {Saltelli,Jansen}SensitivityAlgorithm.cxx (computeIndices) and
// SobolIndicesAlgorithmImplementation.cxx (the centring by the mean of the
// whole output sample, referenceVariance_ = the variance of block A). For
// a deterministic model S_i and T_i are OpenTURNS's getFirstOrderIndices()
// and getTotalOrderIndices() to rounding
// (tests/python/test_sobol_openturns.py).
// Both stay consistent for a stochastic output: y_B and y_E[i] (and y_A and
// y_E[i]) share only theta_i (theta_~i) and have independent omega, so
// E[y_B y_E[i]] = Var E[g | theta_i] + (E Y)^2, and the intrinsic noise of
// the Jansen differences, 2 E Var(Y | theta) per row, is cancelled by the
// replicate pair's. The factors N/(N-1) and 2N/(2N-1) are OpenTURNS's
// finite-sample forms; they change nothing in the limit.
// This V_i is not Saltelli 2010's mean(y_B (y_E[i] - y_A)): agreement with
// OpenTURNS needs OpenTURNS's form, and it is also the better default for a
// stochastic simulator. saltelli_2010 below selects the other form, whose
// variance is smaller only for an input of small total index in a
// deterministic model (y_E[i] close to y_A): at N = 1e5 on the g-function
// (a_i = 99), half-width 0.0002 against 0.0062. It is larger for the large
// indices (0.016 against 0.008 for a_1 = 0), and for every input once the
// output is noisy, since y_E[i] - y_A then carries the intrinsic noise
// (noise sd 0.5: 0.012 to 0.022 against 0.0095 to 0.013).
// None of these depends on how random numbers are coupled across rows.
//
// Each estimate is a smooth function of the means of a row vector z_j
// (dimension 5 + 3d, layout in sobol.cpp):
//   y_A, y_B, y_E[i], y_A^2, y_A y_B, (y_A - y_A2)^2, y_B y_E[i], (y_A - y_E[i])^2.
// Its 95 % interval is the delta method's (CLT): the estimate
// +- 1.959963984540054 sqrt(grad' Cov(z) grad / N), with the sample
// covariance of z and the gradient of the estimate's limit as a function of
// E z at the sample means. Estimates are never clipped: a negative one is
// reported with its interval. The point estimates use only the centred
// co-moments, so they are as accurate for outputs far from zero; the
// interval's variance cancels terms of size (E Y)^2 Var Y and loses about
// 2 log10(|E Y| / sd Y) digits.
//
// The accumulator holds the means and co-moments of z: memory O(d^2), never
// O(rows); merging two is exact up to rounding and, done in a fixed order,
// gives the same bits for any threads or ranks.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace stickslip {

class sobol_moments {
 public:
  sobol_moments() = default;
  explicit sobol_moments(std::size_t inputs);
  // The length of z for `inputs` uncertain inputs: 5 + 3 inputs. means()
  // has this many entries, comoments() dimension (dimension + 1) / 2.
  [[nodiscard]] static constexpr std::size_t dimension(std::size_t inputs) noexcept {
    return 5 + 3 * inputs;
  }
  // One row (Welford). Precondition: y_e.size() == inputs().
  void add(double y_a, double y_a2, double y_b, std::span<const double> y_e);
  // Chan-Golub-LeVeque merge. Precondition: same inputs() (an empty
  // default-constructed accumulator merges with any).
  sobol_moments& operator+=(const sobol_moments& o);

  [[nodiscard]] std::size_t inputs() const noexcept { return inputs_; }
  [[nodiscard]] std::uint64_t rows() const noexcept { return rows_; }
  // The state, for serialization: the means of z and its co-moments
  // sum (z - mean)(z - mean)^T (upper triangle, row-major).
  [[nodiscard]] const std::vector<double>& means() const noexcept { return mean_; }
  [[nodiscard]] const std::vector<double>& comoments() const noexcept { return comoment_; }
  // Throws stickslip::error when the sizes are not those of dimension(inputs).
  [[nodiscard]] static sobol_moments from_state(std::size_t inputs, std::uint64_t rows,
                                                std::vector<double> means,
                                                std::vector<double> comoments);
  friend bool operator==(const sobol_moments&, const sobol_moments&) = default;

 private:
  std::size_t inputs_ = 0;
  std::uint64_t rows_ = 0;
  std::vector<double> mean_, comoment_;
};

struct interval_estimate {
  double value = 0.0;
  double low = 0.0, high = 0.0;  // the 95 % interval
  [[nodiscard]] double half_width() const noexcept { return 0.5 * (high - low); }
  friend bool operator==(const interval_estimate&, const interval_estimate&) = default;
};

struct sobol_estimates {
  std::uint64_t rows = 0;
  double mean = 0.0;                 // E Y (c above)
  double variance = 0.0;             // Var Y (V above)
  double intrinsic_variance = 0.0;   // E Var(Y | theta) (s2 above)
  std::vector<interval_estimate> first_order;           // S_i of g
  std::vector<interval_estimate> total_order;           // T_i of g
  std::vector<interval_estimate> response_first_order;  // Var E[Y|theta_i] / Var Y
  interval_estimate parameter_share, intrinsic_share;
  // With variance 0: whether every output of every row (y_A, y_A2, y_B,
  // y_E) was the same value, i.e. the statistic is constant over the design.
  bool constant_statistic = false;
  // The largest half-width of every index and share (the stop rule of
  // --target-halfwidth); NaN when any is NaN.
  [[nodiscard]] double max_half_width() const noexcept;
};

// The first-order numerator V_i: OpenTURNS's Saltelli form (above, the
// default), or Saltelli 2010's mean(y_B (y_E[i] - y_A)).
enum class first_order_form { openturns_saltelli, saltelli_2010 };

// The 95 % normal quantile of the intervals.
inline constexpr double sobol_z95 = 1.959963984540054;

// The estimates and their 95 % intervals. With fewer than 2 rows every value
// is NaN; with a zero variance (a statistic constant over the design, e.g.
// damping_power with c = 0) the mean, the variance 0 and the intrinsic
// variance, and every index and share NaN (the indices of g also when
// V - s2 = 0).
[[nodiscard]] sobol_estimates sobol_indices(
    const sobol_moments& m, first_order_form form = first_order_form::openturns_saltelli);

// For a zero variance, why the indices are NaN (one line, for a warning and
// summary.json's "warning"); empty otherwise.
[[nodiscard]] std::string undefined_indices_note(const sobol_estimates& e,
                                                 std::string_view statistic);

// When a 95 % interval is wider than [0, 1], the range of an index (a
// finite half-width > 1/2; NaN ones are left out), one line on why:
// - an index of the response or a share (over Var Y), or one of the mean
//   response unless the parameter share's interval is below 1/4: too few
//   rows, and the delta method's intervals, asymptotic, may not hold (a new
//   user's --samples 2 reported a parameter share of -5.8 without a word);
// - else an index of the mean response (over Var g) with a share whose
//   interval is below 1/4: those indices divide by the share, which
//   magnifies their intervals by about 1 / share.
// Empty otherwise, and for a zero variance (undefined_indices_note).
[[nodiscard]] std::string uninformative_indices_note(const sobol_estimates& e,
                                                     std::string_view statistic);

// What a study's outputs record as its "warning": undefined_indices_note,
// else uninformative_indices_note; empty when neither applies.
[[nodiscard]] std::string sensitivity_warning(const sobol_estimates& e, std::string_view statistic);

}  // namespace stickslip
