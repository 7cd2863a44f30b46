// One file per subcommand; each registers itself on the top-level app.
#pragma once
#include <CLI/CLI.hpp>

#include <exception>

namespace stickslip::app {

struct invocation {
  int argc;
  const char* const* argv;
};

void add_simulate_command(CLI::App& app, const invocation& inv);
void add_sweep_command(CLI::App& app, const invocation& inv);
void add_reproduce_command(CLI::App& app, const invocation& inv);
void add_merge_command(CLI::App& app, const invocation& inv);
void add_peak_command(CLI::App& app, const invocation& inv);
void add_sensitivity_command(CLI::App& app, const invocation& inv);
void add_plot_command(CLI::App& app, const invocation& inv);

// Reports a failed output write and leaves without the libraries' exit
// handlers (failed_write.cpp explains why).
[[noreturn]] void exit_after_failed_write(const std::exception& e);
// Prints "stickslip: <kind>: <what>" on stderr and never throws: when stderr
// itself is on the full disk that made the run fail, the exit code must
// still be the error's, not an abort from a second exception.
void print_error(const char* kind, const char* what) noexcept;

}  // namespace stickslip::app
