// The writers' building blocks: the JSON emitter (escaping, round-trip exact
// numbers, layout) and atomic text files.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>

#include "stickslip/io/atomic_file.hpp"
#include "output/json_emitter.hpp"
#include "stickslip/error.hpp"
#include "writers_fixture.hpp"

namespace stickslip::testing {
namespace {

using io::detail::json_emitter;
using io::detail::json_number;
using io::detail::json_string;
using io::detail::layout;
using io::detail::text_sink;

TEST(json_emitter, EscapesQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(json_string("plain"), "\"plain\"");
  EXPECT_EQ(json_string("a\"b\\c"), "\"a\\\"b\\\\c\"");
  EXPECT_EQ(json_string("line\nnext\ttab\r\b\f"), "\"line\\nnext\\ttab\\r\\b\\f\"");
  EXPECT_EQ(json_string(std::string("nul\0x", 5)), "\"nul\\u0000x\"");
  EXPECT_EQ(json_string("\x01\x1f\x7f"), "\"\\u0001\\u001f\\u007f\"");
}

TEST(json_emitter, KeepsValidUtf8AndReplacesInvalidBytes) {
  EXPECT_EQ(json_string("\u03bb = 0.5, \u03bc \u2264 3 \U0001F600"),
            "\"\u03bb = 0.5, \u03bc \u2264 3 \U0001F600\"");
  EXPECT_EQ(json_string("bad \xff byte"), "\"bad \\ufffd byte\"");
  EXPECT_EQ(json_string("cut \xce"), "\"cut \\ufffd\"");          // truncated sequence
  EXPECT_EQ(json_string("\xc0\xaf"), "\"\\ufffd\\ufffd\"");       // overlong '/'
  EXPECT_EQ(json_string("\xed\xa0\x80"), "\"\\ufffd\\ufffd\\ufffd\"");  // surrogate
}

TEST(json_emitter, NumbersAreShortestRoundTripAndNonFiniteIsNull) {
  EXPECT_EQ(json_number(0.1), "0.1");
  EXPECT_EQ(json_number(1.0), "1");
  EXPECT_EQ(json_number(-2.5e-300), "-2.5e-300");
  EXPECT_EQ(json_number(std::numeric_limits<double>::quiet_NaN()), "null");
  EXPECT_EQ(json_number(std::numeric_limits<double>::infinity()), "null");
  EXPECT_EQ(json_number(-std::numeric_limits<double>::infinity()), "null");
  for (double x : {1.0 / 3.0, 0.1 + 0.2, 6.02214076e23, 4.9e-324, 1.7976931348623157e308,
                   0.5405315245690231}) {
    EXPECT_EQ(std::strtod(json_number(x).c_str(), nullptr), x) << json_number(x);
  }
}

TEST(json_emitter, LaysOutMultiLineAndInlineContainers) {
  text_sink out;
  json_emitter j(out);
  j.begin_object(layout::multi_line);
  j.member("name", "x");
  j.key("list");
  j.begin_array(layout::multi_line);
  j.begin_object();
  j.member("a", 1.5);
  j.member("b", std::uint64_t{2});
  j.key("c");
  j.begin_array();
  j.value(true);
  j.null();
  j.end_array();
  j.end_object();
  j.begin_object();
  j.end_object();
  j.end_array();
  j.key("empty");
  j.begin_array(layout::multi_line);
  j.end_array();
  j.end_object();
  EXPECT_EQ(out.str(),
            "{\n"
            "  \"name\": \"x\",\n"
            "  \"list\": [\n"
            "    {\"a\": 1.5, \"b\": 2, \"c\": [true, null]},\n"
            "    {}\n"
            "  ],\n"
            "  \"empty\": []\n"
            "}");
  EXPECT_EQ(j.depth(), 0u);
}

TEST(atomic_file, ReplacesTheFileOnlyWhenTheWriteSucceeded) {
  temp_dir dir;
  const auto path = dir / "out.txt";
  io::detail::write_text_atomically(path, [](text_sink& s) { s.write("first\n"); });
  EXPECT_EQ(read_text(path), "first\n");
  EXPECT_THROW(io::detail::write_text_atomically(path,
                                                 [](text_sink& s) {
                                                   s.write("half");
                                                   throw std::runtime_error("disk on fire");
                                                 }),
               stickslip::error);
  EXPECT_EQ(read_text(path), "first\n");
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST(atomic_file, LargeOutputsStreamThroughTheBuffer) {
  temp_dir dir;
  const auto path = dir / "big.txt";
  io::detail::write_text_atomically(path, [](text_sink& s) {
    for (int i = 0; i < 100000; ++i) s.print("{}\n", i);
  });
  const auto text = read_text(path);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 100000);
  EXPECT_EQ(text.substr(text.size() - 6), "99999\n");
}

TEST(atomic_file, ErrorNamesTheFinalPath) {
  temp_dir dir;
  const auto path = dir / "missing_dir/out.txt";
  try {
    io::detail::write_text_atomically(path, [](text_sink& s) { s.write("x"); });
    FAIL() << "expected an io_error";
  } catch (const stickslip::error& e) {
    EXPECT_EQ(e.code(), exit_code::io_failure);
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stickslip::testing
