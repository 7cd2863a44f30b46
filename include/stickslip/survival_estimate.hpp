// The Kaplan-Meier estimate of a duration law from binned, right-censored
// counts (accumulators/survival_counts.hpp), evaluated at the bin edges
// e_0 = 0, e_1, ..., e_B = upper: the one place the writers (NetCDF, JSON)
// and Python get survival curves from. docs/outputs.md, "Survival".
//
// With n_j the episodes at risk at e_j (durations >= e_j, ended or
// censored, the overflow included) and d_j the episodes that ended in bin
// [e_j, e_j+1):
//   S(e_0) = 1,  S(e_j+1) = S(e_j) (1 - d_j / n_j)            (Kaplan-Meier)
//   V(e_j+1) = sum_{i <= j} d_i / (n_i (n_i - d_i))            (Greenwood)
//   Var S(e) = S(e)^2 V(e).
// Ties follow the usual rule: at the same time, events come before
// censorings; within a bin the censorings count after the bin's events, and
// then the grouped product equals the exact Kaplan-Meier estimate at e_j+1
// (1 - 1/n)(1 - 1/(n-1))...(1 - 1/(n-d+1)) = (n - d)/n, and the exact
// Greenwood sum telescopes the same way: sum 1/(k(k-1)), k = n-d+1..n, is
// 1/(n-d) - 1/n = d / (n (n-d)).
// The 95 % interval is the exponential Greenwood (log(-log)) interval of R's
// survival (conf.type = "log-log") and lifelines' KaplanMeierFitter: with
// theta = log(-log S), Var theta = V / (log S)^2 (delta method), so
//   S^exp(+z sigma) <= S <= S^exp(-z sigma),  sigma = sqrt(V) / |log S|,
// z = 1.959964; it stays inside [0, 1]. [1, 1] where S = 1 (no event yet),
// [0, 0] where S = 0.
// The restricted mean duration is the integral of S from 0 to upper, with S
// linear between edges (the events of a bin spread evenly over it); the
// step function's integral differs by at most half a bin width.
// Beyond the last episode at risk (n_j = 0) S keeps its last value. Without
// any episode every value is NaN and every count 0.
#pragma once
#include <cstdint>
#include <vector>

#include "stickslip/accumulators/survival_counts.hpp"

namespace stickslip {

struct survival_curve {
  std::vector<double> duration;      // the edges e_0 = 0 .. e_B = upper [s]
  std::vector<double> survival;      // S(e_j)
  std::vector<double> greenwood;     // V(e_j): Var S = S^2 V
  std::vector<double> ci95_low, ci95_high;
  std::vector<std::uint64_t> at_risk;  // n_j
  double restricted_mean = 0.0;        // integral of S over [0, upper] [s]
};

// The curves every writer outputs, as "<law name><suffix>" (stick_survival,
// stick_survival_ci95_low, ...) over the law's duration coordinate.
struct survival_curve_column {
  const char* suffix;
  const char* long_name;    // after the law's name: "stick survival probability"
  const char* description;
  std::vector<double> survival_curve::*values;
};
inline constexpr survival_curve_column survival_curve_columns[] = {
    {"_survival", "survival probability",
     "Kaplan-Meier estimate of P(duration >= e) at each edge e of the duration coordinate, "
     "episodes cut by t_a right-censored",
     &survival_curve::survival},
    {"_survival_ci95_low", "survival, lower 95% CI",
     "lower end of the 95% exponential Greenwood (log(-log)) interval of the survival "
     "probability",
     &survival_curve::ci95_low},
    {"_survival_ci95_high", "survival, upper 95% CI",
     "upper end of the 95% exponential Greenwood (log(-log)) interval of the survival "
     "probability",
     &survival_curve::ci95_high},
};

// z of a two-sided 95 % normal interval.
inline constexpr double survival_z95 = 1.959963984540054;

// Precondition: c.selected().
[[nodiscard]] survival_curve kaplan_meier(const survival_counts& c);

// The bin edges of counts over [0, upper] in `bins` bins (the duration
// coordinate): e_j = upper j / bins, exactly upper at j = bins.
[[nodiscard]] std::vector<double> survival_edges(double upper, std::size_t bins);

}  // namespace stickslip
