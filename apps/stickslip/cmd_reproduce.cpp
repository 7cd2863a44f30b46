// `stickslip reproduce`: the founding paper's study end to end, under the
// printed parameters and under the set its figures were computed with, with
// figures (gnuplot) and a claim-by-claim report. See docs/reproduction.md.
//
//   (a) options -> io::study_options (validated before anything runs)
//   (b) io::run_paper_study: main sweeps, refinements of the maximum, candidates
//   (c) io::write_reproduction: sweep outputs, figures, report.md, report.html
#include <fmt/format.h>

#include <cstdio>
#include <string>

#include "commands.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/io/figures.hpp"
#include "stickslip/io/metadata.hpp"
#include "stickslip/io/report.hpp"

namespace stickslip::app {
namespace {

// Numbers are kept as text and parsed with io::parse_unsigned, so that "-5"
// is refused with the flag, the value and the range (CLI11 would wrap it).
struct reproduce_flags {
  std::string out_dir = "reproduction";
  std::string realizations;         // empty: 2000 (200 with --quick)
  std::string refine_realizations;  // empty: 10000 (400 with --quick)
  std::string seed;                 // empty: the study's documented seed
  std::string threads = "0";
  bool quick = false, no_candidates = false, no_figures = false;
};

io::study_options resolve(const reproduce_flags& f) {
  io::study_options o = f.quick ? io::quick_options() : io::study_options{};
  if (!f.realizations.empty())
    o.realizations = io::parse_unsigned("--realizations", f.realizations, 2, max_realizations);
  if (!f.refine_realizations.empty())
    o.refine_realizations =
        io::parse_unsigned("--refine-realizations", f.refine_realizations, 2, max_realizations);
  if (!f.seed.empty()) o.seed = io::parse_unsigned("--seed", f.seed);
  o.threads = static_cast<unsigned>(io::parse_unsigned("--threads", f.threads, 0, 1u << 16));
  o.candidates = !f.no_candidates;
  if (o.realizations < 2)
    throw invalid_parameter("--realizations", static_cast<double>(o.realizations),
                            ">= 2 (a confidence interval needs two realizations)");
  if (o.refine_realizations < 2)
    throw invalid_parameter("--refine-realizations",
                            static_cast<double>(o.refine_realizations), ">= 2");
  return o;
}

void run(const reproduce_flags& f, const invocation& inv) {
  const auto options = resolve(f);
  auto log = [](const std::string& line) {
    fmt::print(stderr, "reproduce: {}\n", line);
  };
  if (f.quick)
    log("--quick: a DEMO on a small design, not the study; the report is marked as a demo");
  const bool render = !f.no_figures && io::gnuplot_available();
  if (!f.no_figures && !render)
    log("gnuplot (with pngcairo and svg) not found: writing data and scripts only");
  const auto study = io::run_paper_study(options, log);
  const auto meta = io::make_metadata(inv.argc, inv.argv, "");
  log(fmt::format("study done in {:.1f} s; writing {}", study.seconds, f.out_dir));
  const auto files = io::write_reproduction(study, meta, f.out_dir, render);
  log(fmt::format("report: {} and {} ({} figures{})", files.markdown, files.html,
                  files.figures.size(), files.rendered ? "" : ", not rendered"));
}

}  // namespace

void add_reproduce_command(CLI::App& app, const invocation& inv) {
  auto flags = std::make_shared<reproduce_flags>();
  auto* cmd = app.add_subcommand(
      "reproduce",
      "Rerun the paper's study (40 lambda x 8 mu x 2000 realizations, t_a = 50 s) under the "
      "printed and the concluded parameters; write sweep outputs, gnuplot figures and a "
      "claim-by-claim report (report.md, report.html)");
  cmd->add_option("-o,--output", flags->out_dir, "output folder (default reproduction)")
      ->type_name("DIR");
  cmd->add_option("--realizations", flags->realizations,
                  "realizations per grid point (default 2000; 200 with --quick)")
      ->type_name("N");
  cmd->add_option("--refine-realizations", flags->refine_realizations,
                  "realizations per lambda when refining the maximum of mean R (default "
                  "10000; 400 with --quick)")
      ->type_name("N");
  cmd->add_option("--seed", flags->seed, "master seed (default 20200101)")->type_name("S");
  cmd->add_option("--threads", flags->threads, "threads, 0 = all cores (default 0)")
      ->type_name("T");
  cmd->add_flag("--quick", flags->quick,
                "DEMO only: a small design (8 lambda x 3 mu x 200 realizations) for tests and "
                "demos; its report is marked as a demo, not a reproduction");
  cmd->add_flag("--no-candidates", flags->no_candidates,
                "skip the other candidate parameter sets (k=40/g=10, k=4/g=1, k=4/V=10)");
  cmd->add_flag("--no-figures", flags->no_figures,
                "write figure data and gnuplot scripts but do not run gnuplot");
  cmd->callback([flags, inv] { run(*flags, inv); });
}

}  // namespace stickslip::app
