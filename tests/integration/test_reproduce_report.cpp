// `reproduce` on a small study, through the io layer and files on disk: the
// outputs exist, images are valid, and the report's tables hold the numbers
// of the result sets. gnuplot-dependent checks are skipped without gnuplot.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <unistd.h>

#include "stickslip/study/figures.hpp"
#include "stickslip/io/metadata.hpp"
#include "stickslip/study/report.hpp"

namespace fs = std::filesystem;
using namespace stickslip;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::uint32_t be32(const std::string& b, std::size_t at) {
  return (static_cast<std::uint32_t>(static_cast<unsigned char>(b[at])) << 24) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 1])) << 16) |
         (static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 2])) << 8) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 3]));
}

// Cells of the Markdown table that follows `heading` in `md`.
std::vector<std::vector<std::string>> table_after(const std::string& md,
                                                  const std::string& heading) {
  std::vector<std::vector<std::string>> rows;
  const auto at = md.find(heading);
  if (at == std::string::npos) return rows;
  std::istringstream in(md.substr(at));
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (line.rfind("|", 0) != 0) {
      if (inside) break;
      continue;
    }
    inside = true;
    if (line.rfind("|---", 0) == 0) continue;
    std::vector<std::string> cells;
    std::size_t p = 1;
    while (p < line.size()) {
      const auto q = line.find(" |", p);
      if (q == std::string::npos) break;
      auto cell = line.substr(p, q - p);
      while (!cell.empty() && cell.front() == ' ') cell.erase(0, 1);
      cells.push_back(cell);
      p = q + 2;
    }
    rows.push_back(cells);
  }
  return rows;
}

class ReproduceReport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    auto o = study::quick_options();
    o.realizations = 60;
    o.refine_realizations = 120;
    o.refine_points = 5;
    o.candidate_realizations = 30;
    o.candidate_refine_realizations = 40;
    o.lambda = {0.1, 1.0, 3.5, 3.8, 10.0};
    o.peak_halfwidth = o.candidate_peak_halfwidth = 0.4;
    o.peak_max_realizations = 2'000'000;
    o.threads = 2;
    study_ = new study::study_result(study::run_paper_study(o));
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("stickslip_reproduce_test_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    const char* argv[] = {"stickslip", "reproduce", "--quick"};
    const auto meta = io::make_metadata(3, argv, "");
    files_ = new study::report_files(study::write_reproduction(*study_, meta, dir_->string(), true));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete files_;
    delete dir_;
    delete study_;
  }
  static study::study_result* study_;
  static fs::path* dir_;
  static study::report_files* files_;
};
study::study_result* ReproduceReport::study_ = nullptr;
fs::path* ReproduceReport::dir_ = nullptr;
study::report_files* ReproduceReport::files_ = nullptr;

TEST_F(ReproduceReport, WritesTheReportTheSweepOutputsAndTheScripts) {
  EXPECT_TRUE(fs::exists(*dir_ / "report.md"));
  EXPECT_TRUE(fs::exists(*dir_ / "report.html"));
  for (const char* set : {"printed", "concluded"}) {
    for (const char* f : {"summary.json", "summary.csv", "results.nc", "refinement.csv",
                          "peaks.csv"})
      EXPECT_TRUE(fs::exists(*dir_ / set / f)) << set << "/" << f;
    for (const char* stem : {"fig2_realization", "fig4_first_stick_hist", "fig5_stick_duration",
                             "fig6a_sticks_per_time", "fig6b_stick_fraction",
                             "fig7_stick_fraction_all_mu", "convergence_R", "refinement_peak"}) {
      EXPECT_TRUE(fs::exists(*dir_ / "figures" / set / (std::string(stem) + ".gp"))) << stem;
      EXPECT_TRUE(fs::exists(*dir_ / "figures" / set / (std::string(stem) + ".dat"))) << stem;
    }
  }
  EXPECT_TRUE(fs::exists(*dir_ / "candidates" / "k40_g10" / "summary.json"));
  EXPECT_TRUE(fs::exists(*dir_ / "figures" / "candidates" / "candidates_R.gp"));
  // No temporary files left behind.
  for (const auto& e : fs::recursive_directory_iterator(*dir_))
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}

TEST_F(ReproduceReport, PngsAndSvgsAreValid) {
  if (!study::gnuplot_available()) GTEST_SKIP() << "gnuplot with pngcairo/svg not installed";
  ASSERT_TRUE(files_->rendered);
  ASSERT_FALSE(files_->figures.empty());
  for (const auto& rel : files_->figures) {
    const auto png = slurp(*dir_ / rel);
    ASSERT_GE(png.size(), 33u) << rel;
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << rel;
    EXPECT_EQ(png.substr(12, 4), "IHDR") << rel;
    EXPECT_GE(be32(png, 16), 800u) << rel;  // width: every canvas is >= 1000 px
    EXPECT_GE(be32(png, 20), 380u) << rel;  // height
    auto svg_path = *dir_ / rel;
    svg_path.replace_extension(".svg");
    const auto svg = slurp(svg_path);
    const auto start = svg.find('<');
    ASSERT_NE(start, std::string::npos) << svg_path;
    EXPECT_TRUE(svg.compare(start, 5, "<?xml") == 0 || svg.compare(start, 4, "<svg") == 0)
        << svg_path;
    EXPECT_NE(svg.find("<svg"), std::string::npos) << svg_path;
    EXPECT_NE(svg.find("</svg>"), std::string::npos) << svg_path;
  }
  // The Fig. 6b canvas is what its script asks for.
  const auto png = slurp(*dir_ / "figures/concluded/fig6b_stick_fraction.png");
  EXPECT_EQ(be32(png, 16), 1000u);
  EXPECT_EQ(be32(png, 20), 650u);
}

TEST_F(ReproduceReport, HtmlEmbedsEveryFigure) {
  const auto html = slurp(*dir_ / "report.html");
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("</html>"), std::string::npos);
  if (!study::gnuplot_available()) GTEST_SKIP() << "gnuplot not installed: nothing to embed";
  std::size_t images = 0;
  for (auto p = html.find("data:image/png;base64,"); p != std::string::npos;
       p = html.find("data:image/png;base64,", p + 1))
    ++images;
  EXPECT_EQ(images, files_->figures.size());
  EXPECT_EQ(html.find("figure not rendered"), std::string::npos);
}

TEST_F(ReproduceReport, GridTableHoldsTheComputedNumbers) {
  const auto md = slurp(*dir_ / "report.md");
  for (const auto& s : study_->sets) {
    const auto rows = table_after(md, "### Grid values at μ = 5 (" + s.set.id + ")");
    const auto pts = study::points_at_mu(s.sweep, 5.0);
    ASSERT_EQ(rows.size(), pts.size() + 1) << s.set.id;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const auto& row = rows[i + 1];
      ASSERT_GE(row.size(), 8u);
      const auto& st = pts[i]->stats;
      EXPECT_NEAR(std::stod(row[0]), pts[i]->parameters.switch_rate, 1e-3);
      EXPECT_NEAR(std::stod(row[1]), st.stick_fraction.mean(), 6e-6);
      EXPECT_NEAR(std::stod(row[2]), st.stick_fraction.mean() - st.stick_fraction.ci95_half_width(),
                  6e-6);
      EXPECT_NEAR(std::stod(row[3]), st.stick_fraction.mean() + st.stick_fraction.ci95_half_width(),
                  6e-6);
      EXPECT_NEAR(std::stod(row[4]), st.sticks_per_time.mean(), 6e-6);
      EXPECT_NEAR(std::stod(row[5]), st.stick_duration.mean(), 6e-6);
      EXPECT_EQ(std::stoull(row[7]), st.realizations);
    }
  }
}

TEST_F(ReproduceReport, ClaimsTableHoldsTheRefinedMaxima) {
  const auto md = slurp(*dir_ / "report.md");
  const auto rows = table_after(md, "## Every quantitative claim of the paper");
  ASSERT_GE(rows.size(), 11u);  // header + 10 claims
  const std::regex percent(R"(^([0-9.]+) %)");
  bool found = false;
  for (const auto& row : rows) {
    if (row[0] != "maximum of mean R for μ = 5") continue;
    found = true;
    EXPECT_EQ(row[1], "almost 80 %");
    for (std::size_t k = 0; k < study_->sets.size(); ++k) {
      std::smatch m;
      const auto& cell = row[2 + 3 * k];
      ASSERT_TRUE(std::regex_search(cell, m, percent)) << cell;
      for (const auto& r : study_->sets[k].refinements)
        if (r.mu == 5.0) {
          const double expected = study::best_maximum(r).R;
          EXPECT_NEAR(std::stod(m[1]) / 100, expected, 5.1e-5) << cell;
        }
      const auto& verdict = row[4 + 3 * k];
      EXPECT_TRUE(verdict == "**agrees**" || verdict == "**partly**" ||
                  verdict == "**disagrees**")
          << verdict;
    }
  }
  EXPECT_TRUE(found);
  // The d_max row holds the exact values of both sets.
  for (const auto& row : rows)
    if (row[0] == "maximum stick duration d_max for μ = 5") {
      EXPECT_EQ(row[2], "24.53 s");
      EXPECT_EQ(row[5], "2.453 s");
      EXPECT_EQ(row[4], "**disagrees**");
      EXPECT_EQ(row[7], "**agrees**");
    }
}

TEST_F(ReproduceReport, PeaksCsvMatchesTheRefinement) {
  const auto csv = slurp(*dir_ / "concluded" / "peaks.csv");
  const auto& s = study_->sets[1];
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  for (const auto& r : s.refinements) {
    ASSERT_TRUE(std::getline(in, line));
    std::istringstream cells(line);
    std::string mu, argmax, gmax, gci, valid, lstar;
    std::getline(cells, mu, ',');
    std::getline(cells, argmax, ',');
    std::getline(cells, gmax, ',');
    std::getline(cells, gci, ',');
    std::getline(cells, valid, ',');
    std::getline(cells, lstar, ',');
    EXPECT_DOUBLE_EQ(std::stod(mu), r.mu);
    EXPECT_DOUBLE_EQ(std::stod(gmax), r.grid_max);  // shortest round-trip text
    EXPECT_EQ(valid, r.located.valid ? "1" : "0");
    if (r.located.valid) {
      EXPECT_DOUBLE_EQ(std::stod(lstar), r.located.result.argmax);
    }
  }
}

TEST_F(ReproduceReport, WithoutRenderingWritesScriptsAndNoStaleImages) {
  // Render into a folder, then rewrite it without gnuplot: the old images
  // must go, the scripts stay, and the report says how to draw them.
  const auto other = *dir_ / "unrendered";
  const char* argv[] = {"stickslip", "reproduce", "--no-figures"};
  const auto meta = io::make_metadata(3, argv, "");
  if (study::gnuplot_available()) (void)study::write_reproduction(*study_, meta, other.string(), true);
  const auto files = study::write_reproduction(*study_, meta, other.string(), false);
  EXPECT_FALSE(files.rendered);
  EXPECT_TRUE(fs::exists(other / "figures/concluded/fig6b_stick_fraction.gp"));
  EXPECT_TRUE(fs::exists(other / "figures/concluded/fig6b_stick_fraction.dat"));
  EXPECT_FALSE(fs::exists(other / "figures/concluded/fig6b_stick_fraction.png"));
  EXPECT_FALSE(fs::exists(other / "figures/concluded/fig6b_stick_fraction.svg"));
  const auto md = slurp(other / "report.md");
  EXPECT_NE(md.find("not rendered"), std::string::npos);
  EXPECT_EQ(slurp(other / "report.html").find("data:image/png"), std::string::npos);
}

TEST(ReproduceFigures, SampledRealizationFollowsTheSegments) {
  sweep_spec spec;
  model_parameters p = spec.base;
  p.stiffness = 40;
  p.switch_rate = 1;
  const auto trace = study::sample_realization(spec, p, 0, 0.01, 10.0);
  ASSERT_FALSE(trace.empty());
  EXPECT_EQ(trace.front().t, 0.0);
  EXPECT_LE(trace.back().t, 10.0);
  const double a = p.band_half_width();
  for (const auto& q : trace) {
    if (!q.stick) continue;
    EXPECT_DOUBLE_EQ(q.xdot, q.v);             // sticking: mass moves with the belt
    EXPECT_LE(std::abs(q.x), a * (1 + 1e-12));  // inside the stick band
  }
  for (std::size_t i = 1; i < trace.size(); ++i) EXPECT_GE(trace[i].t, trace[i - 1].t);
}

}  // namespace

// ---- what a new user hit in the report ----

TEST_F(ReproduceReport, QuickReportIsMarkedAsADemoAndNamesItsGridSize) {
  const auto md = slurp(files_->markdown);
  EXPECT_NE(md.find("(DEMO, --quick)"), std::string::npos);
  EXPECT_NE(md.find("**DEMO (`reproduce --quick`): not a reproduction.**"), std::string::npos);
  EXPECT_NE(md.find("5-point λ grid"), std::string::npos);  // o.lambda has 5 values
  EXPECT_EQ(md.find("the 40-point grid"), std::string::npos);
  EXPECT_NE(slurp(files_->html).find("DEMO"), std::string::npos);
  // The same study, not marked quick: no banner.
  auto full = *study_;
  full.options.quick = false;
  const char* argv[] = {"stickslip", "reproduce"};
  const auto plain = study::report_markdown(full, io::make_metadata(2, argv, ""), {}, dir_->string());
  EXPECT_EQ(plain.find("DEMO"), std::string::npos);
}

TEST_F(ReproduceReport, VerdictNotesAreNotRepeatedWordForWord) {
  const auto md = slurp(files_->markdown);
  const auto at = md.find("Notes on the verdicts:");
  ASSERT_NE(at, std::string::npos);
  std::istringstream in(md.substr(at));
  std::string line;
  std::set<std::pair<std::string, std::string>> seen;  // (claim id, note text)
  int notes = 0;
  std::getline(in, line);
  while (std::getline(in, line)) {
    if (line.empty()) {
      if (notes) break;
      continue;
    }
    if (line.rfind("- `", 0) != 0) break;
    ++notes;
    const auto id_end = line.find('`', 3);
    const auto text_at = line.find("): ");
    ASSERT_NE(text_at, std::string::npos) << line;
    const auto key = std::make_pair(line.substr(3, id_end - 3), line.substr(text_at + 3));
    EXPECT_TRUE(seen.insert(key).second) << "repeated: " << line;
  }
  EXPECT_GT(notes, 0);
  // A note that holds for both sets names both.
  EXPECT_NE(md.find("(printed, concluded): "), std::string::npos);
}

TEST_F(ReproduceReport, ConvergenceAndRefinementFiguresAreNumbered) {
  const auto md = slurp(files_->markdown);
  EXPECT_NE(md.find("Fig. S1: convergence of mean R"), std::string::npos);
  EXPECT_NE(md.find("Fig. S2: refinement of the maximum of mean R"), std::string::npos);
}

TEST_F(ReproduceReport, Fig4YRangeHoldsBothHistograms) {
  for (const char* set : {"printed", "concluded"}) {
    const auto gp = slurp(*dir_ / "figures" / set / "fig4_first_stick_hist.gp");
    const auto dat = slurp(*dir_ / "figures" / set / "fig4_first_stick_hist.dat");
    // The y range of each panel, in order.
    std::vector<double> ymax;
    const std::regex yr(R"(set yrange \[0:([0-9.eE+-]+)\])");
    for (auto it = std::sregex_iterator(gp.begin(), gp.end(), yr); it != std::sregex_iterator();
         ++it)
      ymax.push_back(std::stod((*it)[1]));
    // The highest density (D_1: column 2, D: column 4) of each data block.
    std::vector<double> top;
    std::istringstream in(dat);
    std::string line;
    bool in_block = false;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') {
        in_block = false;
        continue;
      }
      if (!in_block) top.push_back(0);
      in_block = true;
      std::istringstream cols(line);
      double c, d1, n, d;
      cols >> c >> d1 >> n >> d;
      top.back() = std::max({top.back(), d1, std::isnan(d) ? 0.0 : d});
    }
    ASSERT_EQ(ymax.size(), top.size()) << set;
    ASSERT_FALSE(top.empty());
    for (std::size_t i = 0; i < top.size(); ++i)
      EXPECT_GE(ymax[i], top[i]) << set << " panel " << i;
  }
}

TEST(Chi2PoorFit, NinetyFivePercentPointsMatchTheTable) {
  // chi^2 table (Abramowitz & Stegun 26.8 / any statistics text), 95 % points.
  EXPECT_NEAR(study::chi2_95(5), 11.070, 0.01 * 11.070);
  EXPECT_NEAR(study::chi2_95(14), 23.685, 0.01 * 23.685);
  EXPECT_NEAR(study::chi2_95(30), 43.773, 0.01 * 43.773);
  study::peak_estimate p;
  p.chi2 = 24.9;  // the fit the issue found unflagged
  p.dof = 14;
  EXPECT_TRUE(study::poor_fit(p));
  p.chi2 = 14.0;
  EXPECT_FALSE(study::poor_fit(p));
}

// reproduce quotes `peak` for every lambda* and R*. The study's
// located maximum must be what find_peak_by_sweeps (the code behind `stickslip
// peak`) returns for the same request, bit for bit, and the report must quote
// it.
TEST_F(ReproduceReport, EveryMaximumIsThePeakFindersResult) {
  const auto md = slurp(files_->markdown);
  std::size_t located = 0;
  for (const auto& s : study_->sets)
    for (const auto& r : s.refinements) {
      if (!r.located.valid) {
        EXPECT_FALSE(r.located.note.empty()) << s.set.id << " mu " << r.mu;
        continue;
      }
      ++located;
      const auto& q = r.located.request;
      EXPECT_EQ(q.over, "lambda");
      EXPECT_EQ(q.statistic->summary_name, "R");
      EXPECT_EQ(q.method, precision::peak_method::common);
      EXPECT_EQ(q.spec.base.friction_coefficient, r.mu);
      EXPECT_EQ(q.options.target_halfwidth, study_->options.peak_halfwidth);
      const auto p = precision::find_peak_by_sweeps(q);
      EXPECT_EQ(p.argmax, r.located.result.argmax) << s.set.id << " mu " << r.mu;
      EXPECT_EQ(p.max, r.located.result.max) << s.set.id << " mu " << r.mu;
      EXPECT_EQ(p.argmax_lo, r.located.result.argmax_lo);
      const auto v = study::best_maximum(r);
      EXPECT_TRUE(v.refined);
      EXPECT_EQ(v.lambda, p.argmax);
      EXPECT_EQ(v.R_hi, p.max_hi);
      const auto cell = fmt::format("{:.3f} [{:.3f}, {:.3f}]", p.argmax, p.argmax_lo, p.argmax_hi);
      EXPECT_NE(md.find(cell), std::string::npos) << cell;
    }
  EXPECT_GE(located, 3u);  // the quick design locates most maxima
}

// The report says what changed: each mu's 0.1.0 quadratic estimate beside the
// located one, the shift, and whether the old interval holds the new lambda*.
TEST_F(ReproduceReport, ComparisonWithTheQuadraticFitOfVersion010) {
  const auto md = slurp(files_->markdown);
  EXPECT_NE(md.find("What changed from stickslip 0.1.0, and why"), std::string::npos);
  EXPECT_NE(md.find("**Why λ* changed.**"), std::string::npos);
  std::size_t checked = 0;
  for (const auto& s : study_->sets)
    for (const auto& r : s.refinements) {
      const auto rows = table_after(md, "0.1.0 against now (" + s.set.id + ")");
      if (!r.quadratic.valid || !r.located.valid) continue;
      const auto& q = r.quadratic;
      const auto& p = r.located.result;
      const auto old_cell =
          fmt::format("{:.3f} [{:.3f}, {:.3f}]", q.lambda_star, q.lambda_lo, q.lambda_hi);
      const auto new_cell = fmt::format("{:.3f} [{:.3f}, {:.3f}]", p.argmax, p.argmax_lo, p.argmax_hi);
      bool found = false;
      for (const auto& row : rows)
        if (row.size() >= 6 && row[1] == old_cell && row[3] == new_cell) {
          found = true;
          EXPECT_EQ(row[4], fmt::format("{:+.3f}", p.argmax - q.lambda_star));
          const bool holds = q.lambda_lo <= p.argmax && p.argmax <= q.lambda_hi;
          EXPECT_EQ(row[5], holds ? "yes" : "**no**");
        }
      EXPECT_TRUE(found) << s.set.id << " mu " << r.mu << ": " << old_cell << " / " << new_cell;
      ++checked;
    }
  EXPECT_GE(checked, 2u);
}

TEST_F(ReproduceReport, PoorFitsAreFlaggedInTheRefinementTable) {
  const auto md = slurp(files_->markdown);
  for (const auto& s : study_->sets)
    for (const auto& r : s.refinements) {
      const auto cell = fmt::format("{:.2f} / {}", r.quadratic.chi2, r.quadratic.dof);
      const auto at = md.find(cell);
      ASSERT_NE(at, std::string::npos) << cell;
      const std::string flag = " **poor fit**";
      const bool flagged = md.compare(at + cell.size(), flag.size(), flag) == 0;
      EXPECT_EQ(flagged, study::poor_fit(r.quadratic)) << s.set.id << " mu " << r.mu;
    }
}

TEST_F(ReproduceReport, QuickFiguresAreStampedAsADemo) {
  int scripts = 0;
  for (const auto& e : fs::recursive_directory_iterator(*dir_ / "figures"))
    if (e.path().extension() == ".gp") {
      ++scripts;
      EXPECT_NE(slurp(e.path()).find("DEMO (reproduce --quick): not a reproduction"),
                std::string::npos)
          << e.path();
    }
  EXPECT_GT(scripts, 10);
  EXPECT_NE(slurp(files_->markdown).find("DEMO, Fig. 4"), std::string::npos);
}
