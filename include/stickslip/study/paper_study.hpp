// Running the reproduction of the founding paper (design.hpp says what):
// the main sweep of each parameter set, the peak search and the 0.1.0
// quadratic fit for each mu, and what they give. Running simulations goes
// through the executors of study_options; this layer only decides what to
// run.
#pragma once
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "stickslip/study/design.hpp"
#include "stickslip/study/fit.hpp"

namespace stickslip::study {

// The peak search for one mu: its request and result, or why it has none
// (the first scan peaked at an end of the range).
struct located_peak {
  bool valid = false;
  std::string note;  // why not valid
  precision::sweep_peak_request request;
  precision::peak_result result;
};

// Refinement of the maximum of mean R for one mu.
struct mu_refinement {
  double mu = 0;
  std::size_t grid_argmax = 0;  // index into the lambda axis of the main sweep
  double grid_max = 0, grid_max_ci95 = 0, grid_max_lambda = 0;
  located_peak located;         // the estimate the report uses (peak)
  result_set fine;              // mu fixed, lambda on refinement_grid
  peak_estimate quadratic;      // 0.1.0's estimate, for comparison
};

// The maximum the report quotes for one mu: the peak search's when it has
// one, else the grid maximum with its normal interval (refined = false).
struct maximum_view {
  double R, R_lo, R_hi, lambda, lambda_lo, lambda_hi;
  bool refined;
};
[[nodiscard]] maximum_view best_maximum(const mu_refinement& r);

struct set_study {
  parameter_set set;
  result_set sweep;             // axes: mu (outer), lambda (inner)
  std::vector<mu_refinement> refinements;
  double seconds = 0;           // wall time of sweep + refinements
  double sweep_seconds = 0;     // wall time of the main sweep alone
};

// The refinement of `mu` in s: the one whose mu is nearest to `mu`, if
// within 1e-9 of it (so a literal 5 finds the grid's 5); else nullptr.
[[nodiscard]] const mu_refinement* find_refinement(const set_study& s, double mu);

struct study_result {
  study_options options;
  std::vector<set_study> sets;        // printed, concluded
  std::vector<set_study> candidates;  // reduced designs of the other sets
  double seconds = 0;                 // total wall time
  unsigned threads = 1;               // per process
  int ranks = 1;                      // MPI processes
};

// Progress is reported as a line of text per stage (the app prints it).
using study_log = std::function<void(const std::string&)>;

// Main sweep for the set, then the refinement for each mu of `refine_mu`.
[[nodiscard]] set_study run_set_study(const parameter_set& set, const study_options& o,
                                      const study_log& log = {});
// The whole reproduction: printed and concluded sets, then the candidates.
[[nodiscard]] study_result run_paper_study(const study_options& o, const study_log& log = {});
// The main sweep of every parameter set (id, spec), in the order the study
// runs them: what can run before any result is known (`reproduce --shard`).
// The refinements depend on the main sweeps' results.
[[nodiscard]] std::vector<std::pair<std::string, sweep_spec>> main_sweeps(const study_options& o);

// Access to a result_set with axes (mu, lambda).
[[nodiscard]] std::vector<const point_result*> points_at_mu(const result_set& rs, double mu);

}  // namespace stickslip::study
