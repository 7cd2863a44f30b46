// stickslip: exact stochastic simulation of a dry-friction oscillator on a
// telegraph-driven belt. Exceptions are caught here and only here.
#if __has_include(<malloc.h>)
#include <malloc.h>
#endif
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "commands.hpp"
#include "parse_errors.hpp"
#include "stickslip/error.hpp"
#include "stickslip/version.hpp"

// glibc gives freed memory back to the kernel once 128 KiB sit free at the
// top of the heap, and the next allocation faults the pages in again. A
// sweep frees and allocates each work unit's accumulators over and over:
// page faults and zero-filling of fresh pages were ~5 % of the paper grid's
// CPU time. Up to 64 MiB free is kept for reuse instead (the peak resident
// memory of the paper grid's sweep did not change: the memory freed is the
// memory allocated next).
namespace {
void keep_freed_memory() {
#ifdef M_TRIM_THRESHOLD  // glibc
  mallopt(M_TRIM_THRESHOLD, 64 << 20);
  // Setting the trim threshold freezes glibc's mmap threshold at 128 KiB
  // (it otherwise rises after the first large free): blocks up to 32 MiB
  // come from the heap, so that they too are reused, not mapped afresh.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
#endif
}
}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  CLI::App app{"stickslip: exact event-driven simulation and parametric statistics of a "
               "stick-slip oscillator on a randomly switching belt"};
  app.require_subcommand(1);
  app.set_version_flag("--version", fmt::format("stickslip {} ({})", stickslip::version,
                                                 stickslip::git_revision));
  const stickslip::app::invocation inv{argc, argv};
  stickslip::app::add_simulate_command(app, inv);
  stickslip::app::add_sweep_command(app, inv);
  stickslip::app::add_reproduce_command(app, inv);
  stickslip::app::add_merge_command(app, inv);
  stickslip::app::add_peak_command(app, inv);
  stickslip::app::add_sensitivity_command(app, inv);
  stickslip::app::add_plot_command(app, inv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return stickslip::app::report_parse_error(app, e, std::vector<std::string>(argv + 1, argv + argc));
  } catch (const stickslip::error& e) {
    // An interruption's message says what was kept and how to go on.
    stickslip::app::print_error(stickslip::is_interruption(e.code()) ? "stopped" : "error",
                                e.what());
    return static_cast<int>(e.code());
  } catch (const std::exception& e) {
    stickslip::app::print_error("internal error", e.what());
    return static_cast<int>(stickslip::exit_code::internal);
  }
  return 0;
}
