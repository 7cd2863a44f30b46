// `stickslip simulate`: placeholder until implemented.
#include "commands.hpp"
#include "stickslip/error.hpp"

namespace stickslip::app {
void add_simulate_command(CLI::App& app, const invocation&) {
  auto* cmd = app.add_subcommand("simulate", "(not implemented yet)");
  cmd->callback([] { throw error(exit_code::internal, "simulate: not implemented yet"); });
}
}  // namespace stickslip::app
