// `stickslip merge`: placeholder until implemented.
#include "commands.hpp"
#include "stickslip/error.hpp"

namespace stickslip::app {
void add_merge_command(CLI::App& app, const invocation&) {
  auto* cmd = app.add_subcommand("merge", "(not implemented yet)");
  cmd->callback([] { throw error(exit_code::internal, "merge: not implemented yet"); });
}
}  // namespace stickslip::app
