// `stickslip reproduce`: the founding paper's study end to end, under the
// printed parameters and under the set its figures were computed with, with
// figures (gnuplot) and a claim-by-claim report. See docs/reproduction.md.
//
//   (a) options -> study::study_options (validated before anything runs)
//   (b) study::run_paper_study: main sweeps, refinements of the maximum,
//       candidates; every sweep is a journaled run of the run layer in
//       OUT/.runs/<sweep>, so a killed reproduce continues with --resume,
//       `--shard i/n` runs one slice of the main sweeps, and under mpirun the
//       work is spread over the ranks
//   (c) study::write_reproduction: sweep outputs, figures, report.md,
//       report.html; then OUT/.runs is removed
#include <fmt/format.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "commands.hpp"
#include "execution.hpp"
#include "reproduce_peaks.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/study/figures.hpp"
#include "stickslip/io/metadata.hpp"
#include "stickslip/io/output_files.hpp"
#include "stickslip/io/output_lock.hpp"
#include "stickslip/study/report.hpp"
#include "stickslip/run/journaled_run.hpp"

namespace stickslip::app {
namespace {

// Numbers are kept as text and parsed with io::parse_unsigned, so that "-5"
// is refused with the flag, the value and the range (CLI11 would wrap it).
// OUT/.runs/<sweep>: the journal of each of the study's sweeps until the
// report is written.
std::string runs_dir(const std::string& out_dir) { return out_dir + "/.runs"; }

struct reproduce_flags {
  std::string out_dir = "reproduction";
  std::string realizations;         // empty: 2000 (200 with --quick)
  std::string refine_realizations;  // empty: 10000 (400 with --quick)
  std::string peak_halfwidth;       // empty: 0.05 (0.25 with --quick)
  std::string seed;                 // empty: the study's documented seed
  std::string threads = "0";
  bool quick = false, no_candidates = false, no_figures = false;
  bool resume = false, keep_journal = false, overwrite = false;
  std::string shard;  // "i/n"
  double checkpoint_interval = 2.0;  // seconds between journal segments
};

study::study_options resolve(const reproduce_flags& f) {
  study::study_options o = f.quick ? study::quick_options() : study::study_options{};
  if (!f.realizations.empty())
    o.realizations = io::parse_unsigned("--realizations", f.realizations, 2, max_realizations);
  if (!f.refine_realizations.empty())
    o.refine_realizations =
        io::parse_unsigned("--refine-realizations", f.refine_realizations, 2, max_realizations);
  if (!f.peak_halfwidth.empty()) {
    o.peak_halfwidth = io::parse_number("--peak-halfwidth", f.peak_halfwidth);
    if (!(o.peak_halfwidth >= 1e-4 && o.peak_halfwidth <= 10))
      throw invalid_parameter("--peak-halfwidth", o.peak_halfwidth, "1e-4 .. 10 (1/s)");
  }
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

// OUT/reproduce.toml: the settings that define a reproduction (everything
// resolve() decides that changes its results), one `key = value` line each,
// written next to the report so that a later --resume can tell this
// reproduction's finished outputs from another's.
constexpr const char* settings_file = "reproduce.toml";

std::string settings_text(const study::study_options& o) {
  std::string t = "# stickslip reproduce: the settings of the reproduction in this folder\n";
  t += fmt::format("quick = {}\ncandidates = {}\nseed = {}\n", o.quick, o.candidates, o.seed);
  t += fmt::format("realizations = {}\nrefine_realizations = {}\nrefine_points = {}\n",
                   o.realizations, o.refine_realizations, o.refine_points);
  t += fmt::format("refine_log_half_width = {}\ncandidate_realizations = {}\n",
                   o.refine_log_half_width, o.candidate_realizations);
  t += fmt::format("candidate_refine_realizations = {}\npeak_halfwidth = {}\n",
                   o.candidate_refine_realizations, o.peak_halfwidth);
  t += fmt::format("candidate_peak_halfwidth = {}\npeak_max_realizations = {}\n",
                   o.candidate_peak_halfwidth, o.peak_max_realizations);
  return t;
}

// The first line in which two settings texts differ, as "KEY: A vs B".
std::string first_setting_difference(const std::string& theirs, const std::string& ours) {
  auto lines = [](const std::string& text) {
    std::vector<std::string> out;
    std::size_t at = 0;
    while (at < text.size()) {
      const auto end = std::min(text.find('\n', at), text.size());
      out.push_back(text.substr(at, end - at));
      at = end + 1;
    }
    return out;
  };
  const auto a = lines(theirs), b = lines(ours);
  for (std::size_t i = 0; i < std::max(a.size(), b.size()); ++i) {
    const std::string x = i < a.size() ? a[i] : "(nothing)", y = i < b.size() ? b[i] : "(nothing)";
    if (x != y) return fmt::format("{} vs {}", x, y);
  }
  return "";
}

// --resume onto OUT without journals (OUT/.runs): when OUT holds a finished
// reproduction, it must be this one (OUT/reproduce.toml equal to these
// settings): then true (nothing to do). Another one's, or one whose settings
// cannot be read, is refused (exit 2). False: nothing finished there.
bool finished_reproduction(const std::string& out, const study::study_options& options) {
  std::string found;
  for (const char* name : {"report.md", "report.html", settings_file}) {
    std::error_code ec;
    if (std::filesystem::exists(out + "/" + name, ec)) {
      found = out + "/" + name;
      break;
    }
  }
  if (found.empty()) return false;
  const std::string what_to_do =
      "; there are no journals (" + runs_dir(out) + "), so --resume has nothing to continue: "
      "choose another -o DIR for these settings, or add --overwrite to replace that reproduction";
  const std::string path = out + "/" + settings_file;
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw error(exit_code::invalid_input,
                fmt::format("-o '{}' holds a finished reproduction ('{}') whose settings cannot "
                            "be read ('{}' is missing){}",
                            out, found, path, what_to_do));
  const std::string theirs((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string ours = settings_text(options);
  if (theirs != ours)
    throw error(exit_code::invalid_input,
                fmt::format("-o '{}' holds the finished reproduction of other settings ({}; "
                            "that reproduction vs this command){}",
                            out, first_setting_difference(theirs, ours), what_to_do));
  for (const char* name : {"report.md", "report.html"}) {
    std::error_code ec;
    if (!std::filesystem::exists(out + "/" + name, ec))
      throw error(exit_code::invalid_input,
                  fmt::format("-o '{}' holds an incomplete reproduction with these settings "
                              "('{}/{}' is missing){}",
                              out, out, name, what_to_do));
  }
  return true;
}

void print_journal_note(const std::string& line) {
  fmt::print(stderr, "stickslip: journal: {}\n", line);
}

run::run_plan plan_for(const std::string& dir, const run::stop_token& stop, double interval) {
  run::run_plan p;
  p.dir = dir;
  p.checkpoint_interval = std::chrono::duration<double>(interval);
  p.resume = io::journal_exists(dir);  // the command checked --resume for all of OUT/.runs
  p.stop = &stop;
  p.report = print_journal_note;
  return p;
}

// --shard i/n: this process runs its slice of every main sweep (the
// refinements need their results) and journals it.
void run_shard(const study::study_options& options, const run::shard& slice, const std::string& out,
               const run::run_plan& base, run::runner& r, const invocation& inv) {
  for (const auto& [id, spec] : study::main_sweeps(options)) {
    auto plan = base;
    plan.dir = runs_dir(out) + "/" + id;
    plan.resume = io::journal_exists(plan.dir);
    plan.slice = slice;
    const auto done = run::run_journaled(
        spec, plan, io::make_metadata(inv.argc, inv.argv, io::to_toml(spec)), r);
    fmt::print(stderr, "reproduce: shard {}/{} of {}: {} units journaled\n", slice.index,
               slice.count, id, done.computed_units + done.resumed_units);
  }
  fmt::print(stderr, "reproduce: when every shard is done, finish with the same command "
                     "without --shard and with --resume -o {}\n", out);
}

void run(const reproduce_flags& f, const invocation& inv) {
  std::signal(SIGXFSZ, SIG_IGN);  // past `ulimit -f`: EFBIG, reported
  run::stop_token stop;
  run::stop_on_signals signals(stop);
  execution exec(static_cast<unsigned>(io::parse_unsigned("--threads", f.threads, 0, 1u << 16)));
  if (exec.is_worker()) return exec.serve();  // rank 0 runs the study

  auto options = resolve(f);
  const auto slice = run::parse_shard(f.shard);
  const std::string runs = runs_dir(f.out_dir);
  if (!(f.checkpoint_interval >= 0) || f.checkpoint_interval > 86400)
    throw invalid_parameter("--checkpoint-interval", f.checkpoint_interval, "0 .. 86400 seconds");
  // One writer of OUT from here until the report is written (shards: one
  // each), so that the checks below see what no other writer is changing.
  const io::output_lock lock(f.out_dir, slice ? "stickslip reproduce --shard " + f.shard
                                              : std::string("stickslip reproduce"),
                             slice ? slice->tag() : "");
  if (std::filesystem::exists(runs) && !f.resume && !slice)
    throw invalid_value("-o (output folder)", f.out_dir,
                        "a folder without the journals of an unfinished reproduce (found " + runs +
                            "): add --resume to continue it, or remove " + runs);
  if (f.resume && !f.overwrite && !slice && !std::filesystem::exists(runs) &&
      finished_reproduction(f.out_dir, options)) {
    fmt::print(stderr, "reproduce: {} already holds the finished reproduction with these "
                       "settings ({}): nothing to do, it is left as it is\n",
               f.out_dir, f.out_dir + "/" + settings_file);
    return;
  }
  if (!f.overwrite && !f.resume && !slice)
    io::refuse_to_replace({f.out_dir + "/report.md", f.out_dir + "/report.html"},
                          "the report of an earlier reproduce",
                          "add --overwrite to replace it, or choose another -o DIR");
  auto log = [](const std::string& line) {
    fmt::print(stderr, "reproduce: {}\n", line);
  };
  if (f.quick)
    log("--quick: a DEMO on a small design, not the study; the report is marked as a demo");
  if (slice)
    return run_shard(options, *slice, f.out_dir, plan_for("", stop, f.checkpoint_interval),
                     exec.runner(), inv);

  options.execute = [&](const sweep_spec& spec, const std::string& id) {
    auto out = run::run_journaled(spec, plan_for(runs + "/" + id, stop, f.checkpoint_interval),
                                  io::make_metadata(inv.argc, inv.argv, io::to_toml(spec)),
                                  exec.runner());
    if (out.resumed_units)
      log(fmt::format("{}: {} units from the journal, {} computed", id, out.resumed_units,
                      out.computed_units));
    return std::move(*out.results);
  };
  options.locate = kept_peak_locator(runs, exec.runner(), stop, log);
  const bool render = !f.no_figures && study::gnuplot_available();
  if (!f.no_figures && !render)
    log("gnuplot (with pngcairo and svg) not found: writing data and scripts only");
  auto study = study::run_paper_study(options, log);
  study.threads = exec.runner().threads();
  study.ranks = exec.runner().ranks();
  const auto meta = io::make_metadata(inv.argc, inv.argv, "");
  log(fmt::format("study done in {:.1f} s; writing {}", study.seconds, f.out_dir));
  const auto files = study::write_reproduction(study, meta, f.out_dir, render);
  io::write_text_files({{"-o", f.out_dir + "/" + settings_file,
                         [&options] { return settings_text(options); }}},
                       true, "");
  if (!f.keep_journal) {
    std::error_code ec;
    std::filesystem::remove_all(runs, ec);
  }
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
  cmd->add_option("--peak-halfwidth", flags->peak_halfwidth,
                  "target 95 % half-width in lambda [1/s] of the located maximum of mean R "
                  "for the printed and concluded sets (default 0.05; 0.25 with --quick; "
                  "the other candidates use 0.1); see docs/precision.md for the cost")
      ->type_name("H");
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
  cmd->add_flag("--resume", flags->resume,
                "continue a reproduce that was killed or stopped (its sweeps are journaled in "
                "OUT/.runs); refused if the settings changed. Without journals: nothing to do "
                "if OUT holds the finished reproduction with these settings (OUT/reproduce.toml), "
                "refused if it holds another (unless --overwrite), else starts afresh");
  cmd->add_option("--shard", flags->shard,
                  "run only units with index % n == i of every main sweep and journal them in "
                  "OUT/.runs; then finish with --resume (docs/scaling.md)")
      ->type_name("i/n");
  cmd->add_option("--checkpoint-interval", flags->checkpoint_interval,
                  "minimum seconds between journal segments (each is fsynced; more while a "
                  "checkpoint would cost over 5 %, up to 15 times this); 0 = after every unit")
      ->type_name("SECONDS")
      ->capture_default_str();
  cmd->add_flag("--overwrite", flags->overwrite,
                "replace the report and outputs of an earlier reproduce in DIR");
  cmd->add_flag("--keep-journal", flags->keep_journal,
                "keep OUT/.runs (the journals of the study's sweeps) after the report");
  cmd->callback([flags, inv] { run(*flags, inv); });
}

}  // namespace stickslip::app
