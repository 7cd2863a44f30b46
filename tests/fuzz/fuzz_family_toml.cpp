// The TOML sweep configuration (io::parse_sweep_toml) on configurations of
// the whole model family. fuzz_config_toml feeds raw bytes, which seldom get
// past the TOML syntax into the family's keys; this target writes the
// configuration from the input's bytes, key by key, and then damages the text.
//
// Input: byte 0 chooses the mode. With its top bit set the rest is raw TOML
// text. Otherwise the bytes choose, table by table:
//   [model]    a subset of m k g mu V lambda ta c mu_s mu_k, each a number
//              from a table (typical, 0, negative, 5e-324, 1e308, nan, inf,
//              an integer, raw 64-bit patterns written as %.17g), a law
//              string (valid, invalid, or with raw numbers as arguments), a
//              bool or an array; belt_levels (0-6 numbers), belt_rates
//              (0-3), belt_generator (an n x n matrix, sometimes ragged or
//              not square); laws of v1..v6, r1, r2
//   [initial]  x0, xdot0 ([lo, hi], sometimes reversed or of 1 or 3
//              numbers), belt_start ("stationary", "+1", "-1", 0..7, text)
//   [grid]     up to 3 axes of lambda mu mu_s mu_k c k m V v1 v2 r1 (an
//              array or a grid string), sometimes `order`
//   [sweep]    realizations, seed, block_size, max_events, keep_records,
//              engine, common_random_numbers, target_ci, min_realizations
//   [histograms] bins, stick_duration_max
// then, for a third of the inputs, up to 4 byte edits of the text (position
// u16, byte: mostly a character TOML gives a meaning, 0xff erases).
// The law strings (docs/uncertainty.md) are included since the TOML layer
// took them (commit ed49386).
//
// Properties: parse_sweep_toml either throws stickslip::error or returns a
// spec s, and then parse_sweep_toml(to_toml(s)) == s (every parsed spec, not
// only valid ones: to_toml is how the journal, the outputs and
// `--print-config` record a configuration); validate(s) either throws
// stickslip::error or accepts, and an accepted spec prints to the same TOML
// after the round trip. Nothing else is thrown; no sanitizer report.
// FUZZ_TRACE=1 prints the generated text.
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <exception>
#include <string_view>

#include "fuzz_common.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"

namespace {

struct byte_source {
  const std::uint8_t* p;
  std::size_t n;
  std::uint8_t u8() {
    if (n == 0) return 0;
    --n;
    return *p++;
  }
  std::uint16_t u16() { return static_cast<std::uint16_t>(u8() | (u8() << 8)); }
  std::uint64_t u64() {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(u8()) << (8 * i);
    return v;
  }
};

// TOML number literals: typical model values, edges and non-numbers.
constexpr const char* numbers[] = {
    "1.0",  "0.5",   "2",      "0",      "-1.0",  "1e-3",  "10.0",   "0.3",
    "9.81", "5.0",   "4.0",    "0.75",   "1e300", "1e-300", "5e-324", "1.7976931348623157e308",
    "nan",  "inf",   "-inf",   "-0.0",   "3",     "100",   "0.1",    "1e61",
    "1e-61", "0.2",  "-0.5",   "1.5",    "7",     "6.0",   "0x10",   "1_000.0"};

constexpr const char* law_texts[] = {
    "gamma(mean=5,cv=0.2)",
    "uniform(min=0.1,max=0.5)",
    "uniform(0.1,0.5)",
    "loguniform(min=1e-3,max=1)",
    "normal(mean=0,sd=1)",
    "truncnormal(mean=1,sd=0.5,min=0,max=2)",
    "lognormal(mean=1,cv=0.3)",
    "beta(mean=0.5,sd=0.1,min=0,max=1)",
    "gamma(mean=5)",
    "gamma(mean=-1,cv=0.2)",
    "uniform(min=1,max=1)",
    "gamma(mean=nan,cv=1)",
    "foo(1)",
    "gamma(mean=5,cv=0.2,cv=0.3)",
    "normal(0,1)",
    "uniform(min=0.5,max=0.1)",
    "beta(mean=2,sd=0.1,min=0,max=1)",
    "gamma(",
    "lognormal(mean=1e300,cv=1e300)",
    "uniform(min=-1e308,max=1e308)",
};
constexpr const char* law_families[] = {"uniform", "loguniform", "normal", "truncnormal",
                                        "lognormal", "gamma", "beta"};
constexpr const char* law_argument_names[] = {"min", "max", "mean", "sd", "cv"};

std::string raw_double(byte_source& in) {
  double d;
  const std::uint64_t bits = in.u64();
  std::memcpy(&d, &bits, sizeof d);
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", d);
  std::string s = buf;
  if (s == "inf" || s == "-inf" || s == "nan" || s == "-nan") return s == "-nan" ? "nan" : s;
  if (s.find_first_of(".en") == std::string::npos) s += ".0";
  return s;
}

std::string number(byte_source& in) {
  const std::uint8_t b = in.u8();
  if (b >= 240) return raw_double(in);
  return numbers[b % std::size(numbers)];
}

std::string law(byte_source& in) {
  const std::uint8_t b = in.u8();
  if (b < 160) return law_texts[b % std::size(law_texts)];
  // A family with 1-4 named or positional arguments of table or raw values.
  std::string s = law_families[b % std::size(law_families)];
  s += "(";
  const int args = 1 + in.u8() % 4;
  for (int i = 0; i < args; ++i) {
    const std::uint8_t a = in.u8();
    if (i) s += ",";
    if (a & 0x80) s += std::string(law_argument_names[a % std::size(law_argument_names)]) + "=";
    s += number(in);
  }
  return s + ")";
}

std::string array(byte_source& in, std::size_t count) {
  std::string s = "[";
  for (std::size_t i = 0; i < count; ++i) s += (i ? ", " : "") + number(in);
  return s + "]";
}

// A value for a [model] scalar: mostly a number, sometimes a law or a wrong type.
std::string model_value(byte_source& in) {
  const std::uint8_t b = in.u8();
  if (b < 170) return number(in);
  if (b < 235) return "\"" + law(in) + "\"";
  if (b < 245) return "true";
  return array(in, in.u8() % 3);
}

void model_table(byte_source& in, std::string& t) {
  constexpr const char* scalars[] = {"m", "k", "g", "mu", "V", "lambda", "ta", "c", "mu_s", "mu_k"};
  const std::uint16_t present = in.u16();
  t += "[model]\n";
  for (std::size_t i = 0; i < std::size(scalars); ++i)
    if ((present >> i) & 1) t += std::string(scalars[i]) + " = " + model_value(in) + "\n";
  const std::uint8_t belt = in.u8();
  std::size_t levels = 0;
  if (belt & 1) {
    levels = in.u8() % 7;
    t += "belt_levels = " + array(in, levels) + "\n";
  }
  if (belt & 2) t += "belt_rates = " + array(in, in.u8() % 4) + "\n";
  if (belt & 4) {
    const std::size_t n = (belt & 8) ? levels : 1 + in.u8() % 5;
    t += "belt_generator = [";
    for (std::size_t i = 0; i < n; ++i) {
      const bool ragged = (belt & 0x10) && i == n - 1;
      t += (i ? ", " : "") + array(in, ragged ? n + 1 : n);
    }
    t += "]\n";
  }
  if (belt & 0x20) {  // laws of belt levels and rates
    constexpr const char* indexed[] = {"v1", "v2", "v3", "v4", "v5", "v6", "r1", "r2", "v0", "r3"};
    const std::uint8_t which = in.u8();
    for (int i = 0; i < 3; ++i)
      if ((which >> i) & 1)
        t += std::string(indexed[(which >> (3 + i)) % std::size(indexed)]) + " = " +
             (in.u8() < 230 ? "\"" + law(in) + "\"" : number(in)) + "\n";
  }
  if ((belt & 0xc0) == 0xc0) t += "friction = 1.0\n";  // an unknown key
}

void initial_table(byte_source& in, std::string& t) {
  const std::uint8_t b = in.u8();
  if (!(b & 0x80)) return;
  t += "\n[initial]\n";
  auto range = [&](const char* key) {
    const std::uint8_t shape = in.u8() % 8;
    t += std::string(key) + " = ";
    t += shape == 0 ? array(in, 1) : shape == 1 ? array(in, 3) : array(in, 2);
    t += "\n";
  };
  if (b & 1) range("x0");
  if (b & 2) range("xdot0");
  if (b & 4) {
    constexpr const char* starts[] = {"\"stationary\"", "\"+1\"", "\"-1\"", "\"random\"", "0",
                                      "1", "2", "3", "5", "-1", "\"4\"", "\"up\"", "1000001"};
    t += std::string("belt_start = ") + starts[in.u8() % std::size(starts)] + "\n";
  }
}

void grid_table(byte_source& in, std::string& t) {
  constexpr const char* axes[] = {"lambda", "mu", "mu_s", "mu_k", "c", "k", "m", "V", "v1", "v2",
                                  "r1", "ta", "g", "v7"};
  constexpr const char* grids[] = {"lin:0.1:1:3", "log:0.01:1:4", "0.5,1,2", "lin:0:1:2",
                                   "lin:1:0.1:3", "log:0:1:3", "1,1", "lin:-1:1:3", "", "x"};
  const std::uint8_t b = in.u8();
  const std::size_t count = b % 4;
  if (count == 0 && !(b & 0x80)) return;
  t += "\n[grid]\n";
  std::string names[3];
  for (std::size_t i = 0; i < count; ++i) {
    names[i] = axes[in.u8() % std::size(axes)];
    const std::uint8_t v = in.u8();
    t += names[i] + " = " +
         ((v & 1) ? "\"" + std::string(grids[(v >> 1) % std::size(grids)]) + "\""
                  : array(in, 1 + (v >> 1) % 3)) +
         "\n";
  }
  if ((b & 0x40) && count > 0) {
    t += "order = [";
    for (std::size_t i = count; i-- > 0;) t += "\"" + names[i] + "\"" + (i ? ", " : "");
    t += "]\n";
  }
}

void sweep_tables(byte_source& in, std::string& t) {
  const std::uint16_t b = in.u16();
  if (!(b & 0x8000)) return;
  constexpr const char* counts[] = {"1", "2", "4", "10", "0", "-3", "1.5", "1099511627777",
                                    "100", "\"5\""};
  t += "\n[sweep]\n";
  if (b & 1) t += std::string("realizations = ") + counts[in.u8() % std::size(counts)] + "\n";
  if (b & 2) t += std::string("seed = ") + counts[in.u8() % std::size(counts)] + "\n";
  if (b & 4) t += std::string("block_size = ") + counts[in.u8() % std::size(counts)] + "\n";
  if (b & 8) t += std::string("max_events = ") + counts[in.u8() % std::size(counts)] + "\n";
  if (b & 16) t += "keep_records = true\n";
  if (b & 32) t += (in.u8() & 1) ? "engine = \"reference\"\n" : "engine = \"fast\"\n";
  if (b & 64) t += "common_random_numbers = true\n";
  if (b & 128) {
    constexpr const char* targets[] = {"R:0.01", "R:0", "nope:1", "R", "R:nan", "stick_fraction:0.1"};
    t += std::string("target_ci = \"") + targets[in.u8() % std::size(targets)] + "\"\n";
  }
  if (b & 256) t += std::string("min_realizations = ") + counts[in.u8() % std::size(counts)] + "\n";
  if (b & 512) {
    t += "\n[histograms]\n";
    t += std::string("bins = ") + counts[in.u8() % std::size(counts)] + "\n";
    if (b & 1024) t += "stick_duration_max = " + number(in) + "\n";
  }
}

std::string generate(byte_source& in) {
  std::string t;
  model_table(in, t);
  initial_table(in, t);
  grid_table(in, t);
  sweep_tables(in, t);
  // Raw damage to the text, mostly with characters that TOML gives a meaning.
  constexpr std::string_view toml_chars = "[]{}=\",.\n#'-+_0123456789eE:abcinf \t";
  const std::uint8_t damage = in.u8();
  const int edits = damage < 160 ? 0 : damage % 5;
  for (int i = 0; i < edits && !t.empty(); ++i) {
    const std::size_t at = in.u16() % t.size();
    const std::uint8_t c = in.u8();
    if (c == 0xff) t.erase(at, 1);
    else if (c & 0x80) t[at] = static_cast<char>(c);
    else t[at] = toml_chars[c % toml_chars.size()];
  }
  return t;
}

// validate(s): true if it accepts, false if it throws stickslip::error.
bool accepted(const stickslip::sweep_spec& s, bool trace) {
  try {
    validate(s);
    return true;
  } catch (const stickslip::error& e) {
    if (trace) std::fprintf(stderr, "invalid: %s\n", e.what());
  } catch (const std::exception& e) {
    FUZZ_CHECK(false, "validate threw a foreign exception: %s", e.what());
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace stickslip;
  static const bool trace = std::getenv("FUZZ_TRACE") != nullptr;
  if (size == 0) return 0;
  byte_source in{data + 1, size - 1};
  const std::string text = (data[0] & 0x80) ? std::string(reinterpret_cast<const char*>(data + 1), size - 1)
                                            : generate(in);
  if (trace) std::fprintf(stderr, "----\n%s----\n", text.c_str());
  sweep_spec spec;
  try {
    spec = io::parse_sweep_toml(text, "fuzz.toml");
  } catch (const error& e) {
    if (trace) std::fprintf(stderr, "refused: %s\n", e.what());
    return 0;
  } catch (const std::exception& e) {
    FUZZ_CHECK(false, "the parser threw a foreign exception: %s", e.what());
  }
  const std::string printed = io::to_toml(spec);
  sweep_spec again;
  try {
    again = io::parse_sweep_toml(printed, "round-trip");
  } catch (const error& e) {
    FUZZ_CHECK(false, "to_toml of a parsed spec does not parse: %s\n%s", e.what(), printed.c_str());
  }
  FUZZ_CHECK(again == spec, "to_toml round trip changed the spec:\n%s\nread back and printed:\n%s",
             printed.c_str(), io::to_toml(again).c_str());
  if (!accepted(spec, trace)) return 0;
  FUZZ_CHECK(io::to_toml(again) == printed, "an accepted spec prints differently after a round trip");
  if (trace) std::fprintf(stderr, "accepted\n");
  return 0;
}
