// The reproduction of the founding paper (docs/reproduction.md): the study
// design (grids, parameter sets), the refinement of the maximum of mean R in
// lambda with confidence intervals, the claim-by-claim comparison, and the
// report (report.md, report.html). Running simulations goes through
// run_sweep; this layer only decides what to run and how to present it.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "stickslip/io/metadata.hpp"
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

// ------------------------------------------------- refinement of the peak ---

// The maximum of mean R over lambda for one mu is located by `stickslip
// peak` (precision/peak_sweep.hpp: common random numbers, local cubic and
// quartic fits in a shrinking window, an interval that counts sampling error
// and local-model bias; docs/precision.md). The quadratic fit below is the
// method of stickslip 0.1.0; the study still runs it, on its own sweep, so
// that the report can show what changed and why.
//
// Weighted least-squares fit of R = b0 + b1 u + b2 u^2, u = ln(lambda/center),
// weights 1/se_i^2, to the mean R of independent points. With b2 < 0:
//   u* = -b1/(2 b2),  lambda* = center e^u*,  R* = b0 - b1^2/(4 b2).
// Delta-method standard errors come from cov(b) = (X^T W X)^-1; the 95 %
// intervals come from a parametric bootstrap: each point's mean is redrawn
// from N(mean_i, se_i^2) (independent, since each lambda has its own Philox
// key; normal by the CLT) and refitted, and the 2.5 and 97.5 percentiles of
// lambda* and R* are taken. Draws without a maximum (b2 >= 0) are counted
// and left out. The bootstrap streams are Philox with key {seed, tag}, so
// the intervals are reproducible.
struct peak_estimate {
  bool valid = false;         // b2 < 0 and enough points
  double center = 0;          // lambda the fit is expanded around
  double b0 = 0, b1 = 0, b2 = 0;
  double lambda_star = 0, lambda_lo = 0, lambda_hi = 0;  // bootstrap 95 %
  double R_star = 0, R_lo = 0, R_hi = 0;                 // bootstrap 95 %
  double lambda_se_delta = 0, R_se_delta = 0;            // delta method
  double chi2 = 0;            // weighted residual sum of squares
  std::size_t dof = 0;        // points - 3
  bool interior = false;      // lambda* inside the fitted lambda range
  std::size_t bootstrap = 0, bootstrap_degenerate = 0;
};

// The 95 % point of the chi^2 distribution with `dof` degrees of freedom.
[[nodiscard]] double chi2_95(std::size_t dof);
// A refinement fit whose chi^2 is above its 95 % point: the quadratic in
// ln lambda does not describe mean R over the window; the report flags it.
[[nodiscard]] bool poor_fit(const peak_estimate& p);

[[nodiscard]] peak_estimate fit_peak(const std::vector<double>& lambda,
                                     const std::vector<double>& mean,
                                     const std::vector<double>& std_error, double center,
                                     std::uint64_t seed, std::uint64_t stream_tag,
                                     std::size_t bootstrap = 2000);

// ------------------------------------------------------------- the study ---

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

// ---------------------------------------------------------------- claims ---

enum class verdict { agrees, partly, disagrees, not_evaluated };
[[nodiscard]] const char* to_string(verdict v) noexcept;

// One quantitative claim of the paper, evaluated for one parameter set.
struct claim_value {
  std::string value;  // our number(s), formatted
  std::string ci95;   // our 95 % interval, formatted (may be empty)
  verdict result = verdict::not_evaluated;
  std::string note;   // how the verdict was reached
};

struct claim {
  std::string id;           // short key: "dmax", "Rmax_mu5", ...
  std::string statement;    // what the paper says
  std::string paper_value;  // as printed
  std::vector<claim_value> per_set;  // in the order of the sets evaluated
};

// Evaluates every claim for each set study (in order).
[[nodiscard]] std::vector<claim> evaluate_claims(const std::vector<const set_study*>& sets);

// Number of claims with verdict `agrees` (partly counts one half).
[[nodiscard]] double claim_score(const std::vector<claim>& claims, std::size_t set_index);

// ---------------------------------------------------------------- report ---

struct figure;  // figures.hpp

struct report_files {
  std::string markdown, html;        // paths
  std::vector<std::string> figures;  // PNG paths, relative to the report folder
  bool rendered = false;             // gnuplot ran
};

// Writes everything into `dir`: the sweep outputs of each set (io::write_all
// into DIR/<set id>/ plus refinement.csv and peaks.csv; candidates under
// DIR/candidates/<id>/), the figures (DIR/figures/<set id>/), report.md and
// report.html. With `render` false (or no gnuplot) the scripts and data are
// written but nothing is rendered.
report_files write_reproduction(const study_result& study, const io::run_metadata& meta,
                                const std::string& dir, bool render = true);

// The report as Markdown; `figures` carry paths relative to `report_dir`'s
// parent layout (write_reproduction passes what it rendered).
[[nodiscard]] std::string report_markdown(const study_result& study, const io::run_metadata& meta,
                                          const std::vector<figure>& figures,
                                          const std::string& report_dir);

// Text of DIR/<set id>/peaks.csv: one row per refined mu.
[[nodiscard]] std::string peaks_csv(const set_study& s);
// Text of DIR/<set id>/refinement.csv: one row per (mu, lambda) of the refinement.
[[nodiscard]] std::string refinement_csv(const set_study& s);

}  // namespace stickslip::study
