#include "stickslip/io/metadata.hpp"

#include <chrono>
#include <ctime>

#include "stickslip/version.hpp"

namespace stickslip::io {

run_metadata make_metadata(int argc, const char* const* argv, std::string resolved_config) {
  run_metadata m;
  for (int i = 0; i < argc; ++i) {
    if (i) m.command_line += ' ';
    m.command_line += argv[i];
  }
  m.resolved_config = std::move(resolved_config);
  m.version = stickslip::version;
  m.git_revision = stickslip::git_revision;
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  m.created_utc = buf;
  return m;
}

}  // namespace stickslip::io
