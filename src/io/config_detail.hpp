// Helpers shared by config.cpp and config_toml.cpp (not installed).
#pragma once
#include <string>

namespace stickslip::io {

// The whole file as text; throws io_error naming the path.
[[nodiscard]] std::string read_text_file(const std::string& path);

}  // namespace stickslip::io
