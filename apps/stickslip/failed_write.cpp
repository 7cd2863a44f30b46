// After a failed NetCDF write (disk full, `ulimit -f`), HDF5 1.10 keeps a
// half-closed file and segfaults in its atexit teardown (H5_term_library ->
// H5F__close_cb). The error is already known and the outputs are already
// rolled back, so report it the way main() does and leave without running
// the library's exit handlers: a clear error, not a crash.

#include <cstdio>
#include <cstdlib>

#include "commands.hpp"
#include "stickslip/error.hpp"

namespace stickslip::app {

void print_error(const char* kind, const char* what) noexcept {
  std::fprintf(stderr, "stickslip: %s: %s\n", kind, what);  // errors ignored: nothing else to tell
  std::fflush(stderr);
}

void exit_after_failed_write(const std::exception& e) {
  std::fflush(stdout);
  print_error("error", e.what());
  const auto* se = dynamic_cast<const error*>(&e);
  std::_Exit(static_cast<int>(se ? se->code() : exit_code::io_failure));
}

}  // namespace stickslip::app
