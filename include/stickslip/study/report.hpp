// The report of the reproduction (report.md, report.html) and the files
// beside it: each set's sweep outputs, peaks.csv, refinement.csv and the
// figures. Layout of the output folder: docs/reproduction.md.
#pragma once
#include <string>
#include <vector>

#include "stickslip/io/metadata.hpp"
#include "stickslip/study/paper_study.hpp"

namespace stickslip::study {

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
