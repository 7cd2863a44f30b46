// `stickslip reproduce`: placeholder until implemented.
#include "commands.hpp"
#include "stickslip/error.hpp"

namespace stickslip::app {
void add_reproduce_command(CLI::App& app, const invocation&) {
  auto* cmd = app.add_subcommand("reproduce", "(not implemented yet)");
  cmd->callback([] { throw error(exit_code::internal, "reproduce: not implemented yet"); });
}
}  // namespace stickslip::app
