// The switch-times file reader and the --switch-times list on arbitrary text:
// stickslip::error, or times that are finite, >= 0 and strictly increasing.
#include <cmath>
#include <cstdint>
#include <string_view>

#include "fuzz_common.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"

static void check_times(const std::vector<double>& t) {
  for (std::size_t i = 0; i < t.size(); ++i) {
    FUZZ_CHECK(std::isfinite(t[i]) && t[i] >= 0, "time %g accepted", t[i]);
    if (i) FUZZ_CHECK(t[i] > t[i - 1], "times not increasing");
  }
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    check_times(stickslip::io::parse_switch_times(text, "fuzz.txt"));
  } catch (const stickslip::error&) {
  }
  try {
    check_times(stickslip::io::parse_switch_time_list("--switch-times", text));
  } catch (const stickslip::error&) {
  }
  return 0;
}
