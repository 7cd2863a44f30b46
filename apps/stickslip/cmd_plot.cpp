// `stickslip plot DIR`: figures of a finished sweep or sensitivity study,
// drawn by gnuplot (study/plot.hpp, docs/plot.md). DIR is read under its
// writer lock, so a running writer's partial outputs are never read; the
// figures go to OUT (default DIR/plots) under OUT's lock. Every request error
// exits 2 before anything is written.
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/output_files.hpp"
#include "stickslip/io/output_lock.hpp"
#include "stickslip/io/result_file.hpp"
#include "stickslip/study/plot.hpp"

namespace stickslip::app {
namespace {

struct plot_options {
  std::string dir, out_dir, format = "text";
  study::plot_request request;
  bool overwrite = false, scripts_only = false;
};

// Reads DIR under its lock when it has one (a directory some stickslip
// command wrote): refused, like a second writer, while a writer holds it.
// Without a lock file (results copied elsewhere) nothing is locked, and an
// unwritable DIR is read as it is: no writer can be at work in it.
study::plot_figure read_and_plan(const plot_options& o) {
  std::optional<io::output_lock> lock;
  if (std::filesystem::exists(io::output_lock::path_of(o.dir))) {
    try {
      lock.emplace(o.dir, "stickslip plot (reading " + o.dir + ")");
    } catch (const error& e) {
      if (e.code() != exit_code::io_failure) throw;
    }
  }
  const io::result_file file(study::find_result_file(o.dir));
  return study::plan_plot(file, o.request);
}

std::vector<std::string> files_of(const study::figure& f, bool rendered) {
  std::vector<std::string> out{f.dir + "/" + f.stem + ".dat", f.script()};
  if (rendered) {
    out.push_back(f.png());
    out.push_back(f.svg());
  }
  return out;
}

std::string json_string(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') q += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      q += fmt::format("\\u{:04x}", c);
      continue;
    }
    q += c;
  }
  return q + "\"";
}

void print_written(const study::figure& f, const std::vector<std::string>& files,
                   const std::string& format) {
  if (format != "json") {
    for (const auto& p : files) fmt::print("{}\n", p);
    return;
  }
  std::string list;
  for (const auto& p : files) list += (list.empty() ? "" : ", ") + json_string(p);
  fmt::print("{{\"title\": {}, \"caption\": {}, \"files\": [{}]}}\n", json_string(f.title),
             json_string(f.caption), list);
}

void run_plot(const plot_options& o) {
  const bool render = !o.scripts_only;
  if (render && !study::gnuplot_available())
    throw error(exit_code::invalid_input,
                "gnuplot (with pngcairo and svg) not found: install it (Debian: apt-get install "
                "gnuplot-nox), or add --scripts-only to write the data and scripts without images");
  const auto plan = read_and_plan(o);
  const std::string out = o.out_dir.empty() ? (std::filesystem::path(o.dir) / "plots").string()
                                            : o.out_dir;
  std::error_code ec;
  if (std::filesystem::exists(out, ec) && !std::filesystem::is_directory(out, ec))
    throw invalid_value("-o (output directory)", out, "a directory or a path that does not exist");
  const bool existed = std::filesystem::exists(out, ec);
  const io::output_lock lock(out, "stickslip plot");
  const std::string stem = (std::filesystem::path(out) / study::text_of(plan).stem).string();
  if (!o.overwrite) {
    try {
      io::refuse_to_replace({stem + ".dat", stem + ".gp", stem + ".png", stem + ".svg"},
                            "a figure of an earlier plot",
                            "add --overwrite to replace it, or choose another -o OUT");
    } catch (const error&) {
      if (!existed) std::filesystem::remove_all(out, ec);
      throw;
    }
  }
  const auto f = study::write_plot_figure(plan, out, render);
  if (render && !f.rendered)
    throw error(exit_code::io_failure,
                fmt::format("gnuplot failed on '{}': its messages are in '{}.log'", f.script(),
                            f.script()));
  print_written(f, files_of(f, render), o.format);
}

}  // namespace

void add_plot_command(CLI::App& app, const invocation&) {
  auto o = std::make_shared<plot_options>();
  auto& r = o->request;
  auto* cmd = app.add_subcommand(
      "plot",
      "Draw a finished sweep (DIR/results.nc) or sensitivity study (DIR/sensitivity.nc) with "
      "gnuplot: a statistic against an axis with 95 % bands, a heat map, histograms at "
      "chosen points, time-resolved and survival curves, Sobol' indices; PNG, SVG, .dat and "
      ".gp into OUT (docs/plot.md).");
  cmd->add_option("dir", o->dir, "output directory of a sweep or sensitivity study")
      ->type_name("DIR")
      ->required();
  cmd->add_option("--y", r.y,
                  "the statistic (name or symbol: R, stick_duration, ...) whose mean is drawn, "
                  "or another variable over the grid (default R; sensitivity: a list of "
                  "indices, default first_order,total_order)")
      ->type_name("STAT");
  cmd->add_option("--x", r.x, "the axis along x (default: the first with several values)")
      ->type_name("AXIS");
  cmd->add_option("--by", r.by, "one curve per value of this axis (the map's y axis)")
      ->type_name("AXIS");
  cmd->add_option("--at", r.at,
                  "a grid point, NAME=VALUE[,NAME=VALUE...] (the nearest grid value is used); "
                  "fixes axes not drawn; repeat for one curve per point")
      ->type_name("POINT")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_flag("--map", r.map, "a heat map of --y over --x and --by");
  cmd->add_option("--histogram", r.histogram,
                               "the histogram of STAT (name or symbol: D, H, X, ...) at each --at")
                   ->type_name("STAT");
  cmd->add_flag("--time", r.time,
                             "--y (default stick_probability) against time at each --at "
                             "(results of sweep --observe-times)");
  cmd->add_option("--survival", r.survival,
                               "the Kaplan-Meier curve NAME_survival at each --at (stick or "
                               "slip; results with survival statistics)")
                   ->type_name("stick|slip");
  cmd->add_flag("--logx", r.logx,
                "log-scale x (default: on when the x axis is log-spaced, as log:a:b:n grids are)");
  cmd->add_option("-o,--output", o->out_dir, "directory for the figures (default DIR/plots)")
      ->type_name("OUT");
  cmd->add_flag("--overwrite", o->overwrite, "replace a figure of the same name in OUT");
  cmd->add_flag("--scripts-only", o->scripts_only,
                "write the .dat and .gp files without running gnuplot");
  cmd->add_option("--format", o->format, "the list of written files: text or json (default text)")
      ->type_name("text|json")
      ->check(CLI::IsMember({"text", "json"}));
  cmd->callback([o] { run_plot(*o); });
}

}  // namespace stickslip::app
