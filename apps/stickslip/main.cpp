// stickslip: exact stochastic simulation of a dry-friction oscillator on a
// telegraph-driven belt. Exceptions are caught here and only here.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "commands.hpp"
#include "parse_errors.hpp"
#include "stickslip/error.hpp"
#include "stickslip/version.hpp"

int main(int argc, char** argv) {
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
    stickslip::app::print_error("error", e.what());
    return static_cast<int>(e.code());
  } catch (const std::exception& e) {
    stickslip::app::print_error("internal error", e.what());
    return static_cast<int>(stickslip::exit_code::internal);
  }
  return 0;
}
