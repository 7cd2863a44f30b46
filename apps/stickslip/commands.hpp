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

// Reports a failed output write and leaves without the libraries' exit
// handlers (failed_write.cpp explains why).
[[noreturn]] void exit_after_failed_write(const std::exception& e);

}  // namespace stickslip::app
