// `stickslip peak`: the maximizer of a mean statistic over one parameter, to
// a target 95 % half-width, with an interval that accounts for both the
// sampling error and the bias of the local model (precision/peak_finder.hpp,
// docs/precision.md). Every evaluation is an exact sweep (run_sweep) whose
// seed is a hash of (--seed, stage), so the result is the same for any
// number of threads.
#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <memory>
#include <string>
#include <utility>
#include <vector>
#include <unistd.h>

#include "commands.hpp"
#include "model_flags.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/precision/peak_sweep.hpp"
#include "stickslip/statistics_schema.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::app {
namespace {

struct peak_flags {
  model_flags model;
  std::string statistic = "R", over = "lambda", range, target = "0.01";
  std::string initial = "1000", budget = "400000000", threads = "0", format = "text";
  std::string method = "auto";
  bool progress = false;  // one line per stage on stderr (default: when it is a terminal)
};

// One line per stage on stderr: the window, the realizations, the estimate
// and, once there is one, about how many more realizations the target needs
// if the window holds (the half-width's sampling part falls like 1/sqrt(n)),
// at the throughput so far.
void print_stage(const precision::peak_stage& p, const std::string& over, double target,
                 double seconds) {
  std::string line = fmt::format("peak: stage {}: {} in [{:.5g}, {:.5g}] at {} points, +{:.3g} "
                                 "realizations ({:.3g} in all, {:.1f} s)",
                                 p.stage, over, p.window_lo, p.window_hi, p.points,
                                 static_cast<double>(p.realizations_added),
                                 static_cast<double>(p.realizations), seconds);
  if (!p.estimate) {
    line += "; no interior maximum yet: the window moves";
  } else {
    line += fmt::format(": {}* = {:.6g} +- {:.3g} (sampling {:.3g}, bias {:.3g}), target {}",
                        over, p.argmax, p.sampling_halfwidth + p.model_bias,
                        p.sampling_halfwidth, p.model_bias, target);
    const double room = target - p.model_bias;
    if (p.sampling_halfwidth + p.model_bias > target && room > 0 && seconds > 0) {
      const double more = static_cast<double>(p.realizations_added) *
                          ((p.sampling_halfwidth / room) * (p.sampling_halfwidth / room) - 1.0);
      line += fmt::format("; about {:.2g} more realizations (~{:.0f} s) if the window holds", more,
                          more * seconds / static_cast<double>(p.realizations));
    }
  }
  fmt::print(stderr, "{}\n", line);
}

const quantity_info& find_statistic(const std::string& name) {
  return precision::peak_statistic("--statistic", name);
}

std::string find_parameter(const std::string& name) {
  std::string names;
  for (const char* p : parameter_names) {
    if (name == p) return name;
    names += fmt::format("{}{}", names.empty() ? "" : ", ", p);
  }
  throw invalid_value("--over", name, "a parameter symbol: " + names);
}

// "LO:HI" with 0 < LO < HI (every model parameter is positive).
std::pair<double, double> parse_range(const std::string& text) {
  const auto colon = text.find(':');
  if (colon == std::string::npos)
    throw invalid_value("--range", text, "LO:HI with 0 < LO < HI");
  const double lo = io::parse_number("--range (lower end)", text.substr(0, colon));
  const double hi = io::parse_number("--range (upper end)", text.substr(colon + 1));
  if (!(lo > 0)) throw invalid_parameter("--range (lower end)", lo, "> 0");
  if (!(hi > lo)) throw invalid_parameter("--range (upper end)", hi, fmt::format("> the lower end {}", lo));
  return {lo, hi};
}

std::string json_number(double v) { return fmt::format("{:.17g}", v); }

void run_peak(const CLI::App& cmd, const peak_flags& f) {
  const auto& stat = find_statistic(f.statistic);
  const std::string over = find_parameter(f.over);
  for (const auto* flag : given_model_flags(cmd, f.model))
    if (flag->symbol == over)
      throw invalid_value(flag_label(over), flag->text,
                          "not given: --over " + over + " sweeps it over --range");

  refuse_laws(cmd, f.model, "peak",
              "it locates the maximum for one model (give a value), while `stickslip sweep` "
              "takes laws and grids together");
  sweep_spec spec;
  spec.base = apply_scalar_flags(cmd, f.model, apply_preset(f.model, model_parameters{}));
  spec.seed = resolve_seed(f.model, spec.seed);
  spec.max_events = resolve_max_events(f.model, spec.max_events);
  if (f.range.empty() && over != "lambda")
    throw invalid_value("--range", "(not given)", "LO:HI, required unless --over lambda");
  const auto [lo, hi] = parse_range(f.range.empty() ? "0.1:100" : f.range);

  precision::peak_options o;
  o.lo = lo;
  o.hi = hi;
  o.log_scan = hi / lo >= 4;
  o.target_halfwidth = io::parse_number("--target-halfwidth", f.target);
  if (!(o.target_halfwidth > 0))
    throw invalid_parameter("--target-halfwidth", o.target_halfwidth, "> 0");
  o.initial_realizations = io::parse_unsigned("--initial-realizations", f.initial, 2, 1u << 24);
  o.max_total_realizations =
      io::parse_unsigned("--max-realizations", f.budget, 2, max_realizations);
  const auto start = std::chrono::steady_clock::now();
  if (f.progress || ::isatty(STDERR_FILENO) == 1)
    o.on_stage = [&](const precision::peak_stage& p) {
      print_stage(p, over, o.target_halfwidth,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    };
  precision::sweep_peak_request q;
  q.spec = spec;
  q.over = over;
  q.statistic = &stat;
  q.options = o;
  q.method = precision::peak_method_named("--method", f.method, q);
  q.threads = static_cast<unsigned>(io::parse_unsigned("--threads", f.threads, 0, 1u << 16));
  const std::clock_t cpu_start = std::clock();
  const auto r = precision::find_peak_by_sweeps(q);
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;

  if (f.format == "json") {
    fmt::print(
        "{{\n  \"statistic\": \"{}\",\n  \"method\": \"{}\",\n  \"over\": \"{}\",\n  \"range\": [{}, {}],\n"
        "  \"target_halfwidth\": {},\n  \"target_met\": {},\n  \"argmax\": {},\n"
        "  \"argmax_ci95\": [{}, {}],\n  \"argmax_sampling_halfwidth\": {},\n"
        "  \"argmax_model_bias\": {},\n  \"max\": {},\n  \"max_ci95\": [{}, {}],\n"
        "  \"realizations\": {},\n  \"stages\": {},\n  \"window\": [{}, {}],\n  \"seed\": {},\n"
        "  \"elapsed_seconds\": {},\n  \"cpu_seconds\": {}\n}}\n",
        stat.summary_name, precision::to_string(q.method), over, json_number(lo), json_number(hi),
        json_number(o.target_halfwidth), r.target_met ? "true" : "false", json_number(r.argmax),
        json_number(r.argmax_lo), json_number(r.argmax_hi), json_number(r.sampling_halfwidth),
        json_number(r.model_bias), json_number(r.max), json_number(r.max_lo),
        json_number(r.max_hi), r.realizations, r.stages, json_number(r.window_lo),
        json_number(r.window_hi), spec.seed, json_number(elapsed), json_number(cpu));
  } else {
    fmt::print("{} = {:.6g}  95 % [{:.6g}, {:.6g}]  (sampling +-{:.3g}, local-model bias {:.3g})\n",
               over + "*", r.argmax, r.argmax_lo, r.argmax_hi, r.sampling_halfwidth, r.model_bias);
    fmt::print("max {} = {:.6g}  95 % [{:.6g}, {:.6g}]\n", stat.symbol, r.max, r.max_lo, r.max_hi);
    fmt::print("{} realizations in {} stages, {:.2f} s ({:.2f} s CPU)\n", r.realizations,
               r.stages, elapsed, cpu);
  }
  if (!r.target_met)
    fmt::print(stderr,
               "stickslip: peak: the target half-width {} was not reached within {} stages "
               "and --max-realizations {} (a maximizer at an end of --range is never "
               "reached); the interval printed is honest but wider\n",
               o.target_halfwidth, o.max_stages, o.max_total_realizations);
}

}  // namespace

void add_peak_command(CLI::App& app, const invocation&) {
  auto f = std::make_shared<peak_flags>();
  auto* cmd = app.add_subcommand(
      "peak",
      "Locate the maximizer of a mean statistic over one parameter to a target 95 % "
      "half-width; the interval counts both the sampling error and the bias of the local "
      "model (docs/precision.md).");
  cmd->add_option("--statistic", f->statistic,
                  fmt::format("the statistic whose mean is maximized: {} (default R)",
                              mean_statistic_names()));
  cmd->add_option("--over", f->over, "the parameter to maximize over (default lambda)");
  cmd->add_option("--range", f->range,
                  "LO:HI, the search range (default 0.1:100 for lambda; scanned geometrically "
                  "when HI/LO >= 4)");
  cmd->add_option("--target-halfwidth", f->target,
                  "the 95 % half-width of the maximizer to reach (default 0.01)")
      ->type_name("H");
  cmd->add_option("--initial-realizations", f->initial,
                  "realizations per point of the first scan and stage (default 1000)")
      ->type_name("N");
  cmd->add_option("--max-realizations", f->budget,
                  "budget of realizations over all stages (default 400000000)")
      ->type_name("N");
  cmd->add_option("--method", f->method,
                  "score: the root of dE[R]/dlambda, from the causal score derivative and the "
                  "values at 3 points, in 20 independent groups with common random numbers "
                  "across the points (over lambda, statistic R, Poisson switching); common: "
                  "the same groups at 5 points, a cubic fitted to the values; independent: "
                  "every point its own streams; auto: score where it applies, else common "
                  "(default auto)")
      ->type_name("auto|score|common|independent")
      ->check(CLI::IsMember({"auto", "score", "common", "independent"}));
  cmd->add_option("--threads", f->threads, "worker threads, 0 = all cores (default 0)");
  cmd->add_flag("--progress", f->progress,
                "print one line per stage on stderr (window, realizations, estimate, about how "
                "many more realizations the target needs); on by default when stderr is a "
                "terminal");
  cmd->add_option("--format", f->format, "output: text or json (default text)")
      ->type_name("text|json")
      ->check(CLI::IsMember({"text", "json"}));
  add_model_flags(*cmd, f->model, flag_values::scalar, model_parameters{});
  cmd->callback([cmd, f] { run_peak(*cmd, *f); });
}

}  // namespace stickslip::app
