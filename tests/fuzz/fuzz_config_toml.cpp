// The TOML sweep configuration parser on arbitrary bytes: it must either
// throw stickslip::error or return a spec; a spec that validates must survive
// the documented round trip parse_sweep_toml(to_toml(s)) == s.
#include <cstdint>
#include <string_view>

#include "fuzz_common.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  stickslip::sweep_spec spec;
  try {
    spec = stickslip::io::parse_sweep_toml(text, "fuzz.toml");
    stickslip::validate(spec);
  } catch (const stickslip::error&) {
    return 0;
  }
  const auto again = stickslip::io::parse_sweep_toml(stickslip::io::to_toml(spec), "round-trip");
  FUZZ_CHECK(again == spec, "to_toml round trip changed the spec");
  return 0;
}
