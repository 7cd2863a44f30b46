// Helpers shared by config.cpp and config_toml.cpp (not installed).
#pragma once
#include <cstdint>
#include <string>

namespace stickslip::io {

// The whole file as text. A missing file or one that is not a regular file is
// invalid input (exit code 2, "does not exist"); a read failure is io_error.
[[nodiscard]] std::string read_text_file(const std::string& path);

// An upper limit for messages: "100000", "2^40 = 1099511627776".
[[nodiscard]] std::string limit_text(std::uint64_t v);

}  // namespace stickslip::io
