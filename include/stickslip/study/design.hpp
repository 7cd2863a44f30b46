// The design of the reproduction of the founding paper
// (docs/reproduction.md): the grids, the candidate parameter sets and the
// options of a study run. What to run, not how.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "stickslip/precision/peak_sweep.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::study {

// ---------------------------------------------------------------- grids ----

// The 40 lambda values [1/s] of the full study, increasing, in [0.1, 30]:
// 20 log-spaced values on [0.1, 2.6), a uniform 0.3 step on [2.6, 4.7]
// (2.6, 2.9, ..., 4.7: the paper's claimed maximum locations 3.5 and 3.8 are
// nodes and the flat peak is sampled densely), and 12 log-spaced values on
// (4.7, 30]. Log spacing because every lambda effect is relative: the mean
// wait 1/lambda sets the stick-duration scale over two and a half decades.
[[nodiscard]] std::vector<double> paper_lambda_grid();
// The 8 mu values: 0.5, 1, 2, 3, 4, 5, 6, 7 (contains the paper's 0.5, 5, 7).
[[nodiscard]] std::vector<double> paper_mu_grid();
// The --quick design: 8 lambda values x mu in {0.5, 5, 7}.
[[nodiscard]] std::vector<double> quick_lambda_grid();
[[nodiscard]] std::vector<double> quick_mu_grid();

// n values geometrically spaced on [center e^-h, center e^+h] (n >= 2).
[[nodiscard]] std::vector<double> refinement_grid(double center, double log_half_width,
                                                  std::size_t n);

// -------------------------------------------------------- parameter sets ---

struct parameter_set {
  std::string id;     // folder name: "printed", "concluded", "k40_g10", ...
  std::string label;  // for legends: "k = 4 N/m, g = 9.81 m/s^2"
  std::string why;    // one sentence: where this set comes from
  model_parameters base;  // mu and lambda are overwritten by the grid
};

// m = 1, k = 4, g = 9.81, V = 1, t_a = 50: the values printed in Sec. 5.
[[nodiscard]] parameter_set printed_parameters();
// k = 40, g = 9.81 (m = 1, V = 1, t_a = 50): the set the figures used
// (evidence: docs/reproduction.md and the candidates table of the report).
[[nodiscard]] parameter_set concluded_parameters();
// Every candidate compared in the report, printed and concluded first.
[[nodiscard]] std::vector<parameter_set> candidate_parameter_sets();

// --------------------------------------------------------------- options ---

// How the study runs one of its sweeps; `id` names it uniquely within the
// study and can name a file ("printed-sweep", "concluded-refine-mu-5").
// Default (empty): run_sweep on `threads` threads. The command line passes a
// journaled run from the run layer (resume, MPI).
using sweep_executor = std::function<result_set(const sweep_spec&, const std::string& id)>;
// How the study runs one peak search; `id` names it uniquely within the
// study ("concluded-peak-mu-5"). Default (empty): find_peak_by_sweeps. The
// command line passes one that runs the sweeps on its runner (MPI) and keeps
// each finished search in OUT/.runs, so a resumed reproduce does not redo it.
using peak_locator = std::function<precision::peak_result(const precision::sweep_peak_request&,
                                                          const std::string& id)>;

struct study_options {
  std::uint64_t realizations = 2000;         // per grid point of the main sweep
  std::uint64_t refine_realizations = 10000; // per lambda of the refinement
  std::size_t refine_points = 17;            // lambda values of the refinement
  double refine_log_half_width = 0.4;        // window: lambda_c e^(+-0.4)
  std::uint64_t candidate_realizations = 1000;
  std::uint64_t candidate_refine_realizations = 4000;
  // The peak search's target 95 % half-width in lambda [1/s], for the
  // printed and concluded sets and for the other candidates, and its budget
  // of realizations per search (over all stages).
  double peak_halfwidth = 0.05;
  double candidate_peak_halfwidth = 0.1;
  std::uint64_t peak_max_realizations = 200'000'000;
  std::uint64_t seed = 20200101;
  unsigned threads = 0;  // 0 = all cores
  bool quick = false;
  bool candidates = true;  // compare the other candidate parameter sets too
  std::vector<double> lambda, mu;  // empty: paper (or quick) grids
  std::vector<double> refine_mu;   // empty: every mu of the grid
  sweep_executor execute;          // empty: run_sweep
  peak_locator locate;             // empty: precision::find_peak_by_sweeps
};

// The --quick settings: 8 lambda x 3 mu x 200 realizations, refinement with
// 7 lambda values x 400, candidates at 100/200 realizations, peak searches
// to a half-width of 0.25.
[[nodiscard]] study_options quick_options();

}  // namespace stickslip::study
