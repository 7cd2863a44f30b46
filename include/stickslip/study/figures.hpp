// Figures of the reproduction, drawn by gnuplot. For every figure we write a
// data file (.dat, whitespace-separated columns with a commented header) and
// a gnuplot script (.gp) that reads it and renders PNG (pngcairo) and SVG, so
// users can edit and rerun `gnuplot NAME.gp` in the figure folder.
// gnuplot runs as a child process (std::system) from here, never from the core.
#pragma once
#include <string>
#include <vector>

#include "stickslip/study/paper_study.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::study {

struct figure {
  std::string key;      // "fig6b", "convergence", ...
  std::string title;    // short title
  std::string caption;  // self-contained caption: what, parameters, sample size
  std::string dir;      // folder holding the files
  std::string stem;     // file stem: dir/stem.{dat,gp,png,svg}
  bool rendered = false;
  [[nodiscard]] std::string png() const { return dir + "/" + stem + ".png"; }
  [[nodiscard]] std::string svg() const { return dir + "/" + stem + ".svg"; }
  [[nodiscard]] std::string script() const { return dir + "/" + stem + ".gp"; }
};

// True when `gnuplot` runs and has the pngcairo and svg terminals.
[[nodiscard]] bool gnuplot_available();

// Runs `gnuplot script` inside `dir` (so relative file names in the script
// resolve there). Returns false if gnuplot failed; its stderr goes to
// `dir/script.log`.
bool run_gnuplot(const std::string& dir, const std::string& script);

// One realization sampled from the closed-form segments (Fig. 2).
struct trace_point {
  double t, x, xdot, v;
  bool stick;
};
[[nodiscard]] std::vector<trace_point> sample_realization(const sweep_spec& spec,
                                                          const model_parameters& p,
                                                          std::uint64_t realization,
                                                          double dt, double t_end);

// All figures of one parameter set (Fig. 2, 4, 5, 6a, 6b, 7, convergence,
// refinement) into `dir`. Renders them when `render`.
[[nodiscard]] std::vector<figure> write_set_figures(const set_study& s, const std::string& dir,
                                                    bool render);

// Mean R against lambda at mu = 0.5, 5, 7 for every candidate parameter set,
// with the paper's claims marked.
[[nodiscard]] std::vector<figure> write_candidate_figures(const study_result& r,
                                                          const std::string& dir, bool render);

}  // namespace stickslip::study
