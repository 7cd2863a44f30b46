// `stickslip sweep`: placeholder until implemented.
#include "commands.hpp"
#include "stickslip/error.hpp"

namespace stickslip::app {
void add_sweep_command(CLI::App& app, const invocation&) {
  auto* cmd = app.add_subcommand("sweep", "(not implemented yet)");
  cmd->callback([] { throw error(exit_code::internal, "sweep: not implemented yet"); });
}
}  // namespace stickslip::app
