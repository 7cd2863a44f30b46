// One error hierarchy for the whole project (the CLI11/fmt pattern): every
// error carries the process exit code, messages are built by named factories,
// and exceptions are caught only in main().
#pragma once
#include <stdexcept>
#include <string>

namespace stickslip {

enum class exit_code : int {
  ok = 0,
  invalid_input = 2,    // a parameter, flag, file or grid specification is wrong
  io_failure = 3,       // an output could not be written / an input could not be read
  work_bound = 4,       // a realization hit the bound on the number of events
  resume_mismatch = 5,  // --resume found a journal made with another configuration
  internal = 70,
};

// A run stopped by signal n exits 128 + n (the shell's convention): the
// user's or the batch system's stop, not a failure.
[[nodiscard]] constexpr exit_code interrupted_by(int signal) noexcept {
  return static_cast<exit_code>(128 + signal);
}
[[nodiscard]] constexpr bool is_interruption(exit_code c) noexcept {
  return static_cast<int>(c) > 128;
}

class error : public std::runtime_error {
 public:
  error(exit_code code, const std::string& what) : std::runtime_error(what), code_(code) {}
  [[nodiscard]] exit_code code() const noexcept { return code_; }

 private:
  exit_code code_;
};

// Named factories. Each message names the parameter, the offending value and
// what would have been allowed.
[[nodiscard]] error invalid_parameter(const std::string& name, double value,
                                      const std::string& allowed);
[[nodiscard]] error invalid_value(const std::string& name, const std::string& value,
                                  const std::string& allowed);
[[nodiscard]] error io_error(const std::string& path, const std::string& what);
[[nodiscard]] error work_bound_exceeded(long long events, double time, double window);

}  // namespace stickslip
