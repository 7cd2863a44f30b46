// What every output file carries so that it explains itself (CmdStan style):
// the full resolved configuration, the program version and git revision, the
// seed and the command line.
#pragma once
#include <string>

namespace stickslip::io {

struct run_metadata {
  std::string command_line;     // argv joined with spaces
  std::string resolved_config;  // the full resolved configuration, as TOML text
  std::string version;          // stickslip::version
  std::string git_revision;     // stickslip::git_revision
  std::string created_utc;      // ISO 8601
};

[[nodiscard]] run_metadata make_metadata(int argc, const char* const* argv,
                                         std::string resolved_config);

}  // namespace stickslip::io
