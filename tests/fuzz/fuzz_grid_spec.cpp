// Grid specifications ("a,b,c", "lin:a:b:n", "log:a:b:n") and single numbers
// on arbitrary text: stickslip::error or values that are all finite and > 0.
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_common.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto values = stickslip::io::parse_grid("--lambda", text);
    FUZZ_CHECK(!values.empty(), "empty grid accepted");
    for (double v : values) FUZZ_CHECK(std::isfinite(v) && v > 0, "grid value %g accepted", v);
    if (stickslip::io::is_single_value(text)) FUZZ_CHECK(values.size() == 1, "single value gave a list");
  } catch (const stickslip::error&) {
  }
  try {
    const double x = stickslip::io::parse_number("--mu", text);
    FUZZ_CHECK(std::isfinite(x), "non-finite number %g accepted", x);
  } catch (const stickslip::error&) {
  }
  try {
    (void)stickslip::io::parse_unsigned("--realizations", text, 1);
  } catch (const stickslip::error&) {
  }
  return 0;
}
