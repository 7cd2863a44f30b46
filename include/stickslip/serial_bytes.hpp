// The bytes every serialized message and journal record is made of: the
// little-endian writer and the bounds-checked reader, the message header
// (tag, format version, layout id) and the CRC-32 the journal adds per
// record. serialize.hpp encodes the sweep's types with them.
//
// Doubles travel as their IEEE-754 bit patterns, so a round trip is
// bit-exact (NaN payloads and -0 included). The reader never trusts its
// input: every access is checked against the bytes that remain, and any
// problem throws stickslip::error (exit_code::io_failure) naming what was
// wrong; it never reads out of bounds.
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <fmt/format.h>
#include <string>
#include <string_view>
#include <utility>

#include "stickslip/error.hpp"

namespace stickslip {

// Bumped whenever the layout of any message (serialize.hpp) or journal
// record changes in a way the tables do not say (CHANGELOG.md notes the
// recent bumps); a change of the statistics schema, the parameter table or
// the record table changes layout_id instead. Readers refuse both: a journal
// from another version or layout is recomputed, never misread.
inline constexpr std::uint32_t serial_format_version = 11;

// FNV-1a over statistics_schema_id(), the parameter names and
// record_layout_id(record_table), in order: the lists serialize.hpp lays out
// by iterating them.
[[nodiscard]] std::uint64_t layout_id() noexcept;

// A byte string holds the encoded bytes (std::string: contiguous, cheap to move).
using bytes = std::string;

namespace detail {
[[nodiscard]] error corrupt(std::string_view what);  // io_failure "corrupt serialized data: ..."

// Little-endian encoder.
class byte_writer {
 public:
  void raw(std::string_view s) { out_.append(s); }
  void u8(std::uint8_t v) { out_.push_back(static_cast<char>(v)); }
  void u32(std::uint32_t v) { little_endian<4>(v); }
  void u64(std::uint64_t v) { little_endian<8>(v); }
  void i64(std::int64_t v) { u64(static_cast<std::uint64_t>(v)); }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  void str(std::string_view s) {
    u64(s.size());
    raw(s);
  }
  void header(std::string_view tag) {
    raw(tag);
    u32(serial_format_version);
    u64(layout_id());
  }
  [[nodiscard]] bytes take() { return std::move(out_); }

 private:
  // One append per word rather than one push_back per byte: journals and
  // merges encode millions of words.
  template <int N>
  void little_endian(std::uint64_t v) {
    char b[N];
    for (int i = 0; i < N; ++i) b[i] = static_cast<char>(static_cast<std::uint8_t>(v >> (8 * i)));
    out_.append(b, N);
  }
  bytes out_;
};

// Decoder: every access is bounds-checked and throws corrupt(...) when short.
class byte_reader {
 public:
  explicit byte_reader(std::string_view in) : in_(in) {}
  std::string_view raw(std::size_t n, std::string_view what) {
    if (n > in_.size() - pos_) throw corrupt(fmt::format("truncated while reading {}", what));
    auto s = in_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  std::uint8_t u8(std::string_view what) { return static_cast<std::uint8_t>(raw(1, what)[0]); }
  std::uint32_t u32(std::string_view what) {
    const auto s = raw(4, what);
    std::uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<std::uint8_t>(s[i]);
    return v;
  }
  std::uint64_t u64(std::string_view what) {
    const auto s = raw(8, what);
    std::uint64_t v = 0;
    for (int i = 7; i >= 0; --i) v = (v << 8) | static_cast<std::uint8_t>(s[i]);
    return v;
  }
  std::int64_t i64(std::string_view what) { return static_cast<std::int64_t>(u64(what)); }
  double f64(std::string_view what) { return std::bit_cast<double>(u64(what)); }
  bool boolean(std::string_view what) {
    const auto v = u8(what);
    if (v > 1) throw corrupt(fmt::format("{}: {} is not a boolean", what, v));
    return v == 1;
  }
  // A count of elements of at least `min_size` bytes each: cannot exceed what remains.
  std::size_t count(std::string_view what, std::size_t min_size) {
    const auto n = u64(what);
    if (n > (in_.size() - pos_) / std::max<std::size_t>(1, min_size))
      throw corrupt(fmt::format("{}: length {} exceeds the {} bytes left", what, n,
                                in_.size() - pos_));
    return static_cast<std::size_t>(n);
  }
  std::string str(std::string_view what) {
    const auto n = count(what, 1);
    return std::string(raw(n, what));
  }
  void header(std::string_view tag) {
    const auto t = raw(tag.size(), "message tag");
    if (t != tag) throw corrupt(fmt::format("expected a '{}' message", tag));
    const auto v = u32("format version");
    if (v != serial_format_version)
      throw corrupt(fmt::format("format version {} (this program reads version {}): written "
                                "by another version of stickslip",
                                v, serial_format_version));
    const auto layout = u64("layout id");
    if (layout != layout_id())
      throw corrupt(fmt::format("layout {:016x} (this program's is {:016x}): written by a "
                                "build with another list of statistics, model parameters or "
                                "record fields",
                                layout, layout_id()));
  }
  [[nodiscard]] std::size_t remaining() const noexcept { return in_.size() - pos_; }
  void finish(std::string_view what) const {
    if (pos_ != in_.size())
      throw corrupt(fmt::format("{} trailing bytes after the {}", in_.size() - pos_, what));
  }

 private:
  std::string_view in_;
  std::size_t pos_ = 0;
};

}  // namespace detail

// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320), as in zlib and PNG.
[[nodiscard]] std::uint32_t crc32(std::string_view data, std::uint32_t crc = 0) noexcept;

}  // namespace stickslip
