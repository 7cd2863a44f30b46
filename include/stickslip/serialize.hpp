// Exact binary (de)serialization of sweep specs, work units and block results,
// for MPI messages and the checkpoint journal (src/io/store/journal*.cpp).
//
// Format: little-endian; doubles travel as their IEEE-754 bit patterns, so a
// round trip is bit-exact (NaN payloads and -0 included). Every message starts
// with a 4-byte tag, the format version and the layout id (layout_id(): the
// list of statistics a block result holds and of model parameters a spec
// holds); vectors carry their length. Both lists are laid out by iterating
// them (statistics_schema.hpp, recorded_parameter_names in parameters.hpp),
// so adding a statistic or a parameter changes the layout id, and data
// written without it is refused, never misread.
// Deserialization never trusts its input: every length is checked against
// the bytes that remain, every count against a sane bound, and histogram
// binnings against their invariants. Any problem throws stickslip::error
// (exit_code::io_failure) naming what was wrong; it never reads out of bounds.
// The journal adds a CRC-32 per record on top, to tell corruption from a bug.
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <fmt/format.h>
#include <string>
#include <string_view>
#include <utility>

#include "stickslip/error.hpp"
#include "stickslip/statistics_schema.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip {

// Bumped whenever the layout of anything below changes (CHANGELOG.md notes
// the recent bumps). Readers refuse other versions: a journal from another
// version is recomputed, never misread.
inline constexpr std::uint32_t serial_format_version = 11;

// FNV-1a over statistics_schema_id() and the parameter names, in order.
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
                                "build with another list of statistics or model parameters",
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


[[nodiscard]] bytes serialize(const sweep_spec& s);
[[nodiscard]] sweep_spec deserialize_sweep_spec(std::string_view in);

[[nodiscard]] bytes serialize(const work_unit& u);
[[nodiscard]] work_unit deserialize_work_unit(std::string_view in);

// One finished unit: the unit and its block result.
[[nodiscard]] bytes serialize(const work_unit& u, const block_result& r);
[[nodiscard]] std::pair<work_unit, block_result> deserialize_unit_result(std::string_view in);

// A point's merged prefix (sweep.hpp), the journal's compact record.
[[nodiscard]] bytes serialize(const merged_prefix& p);
[[nodiscard]] bytes serialize_merged_prefix(std::size_t point, std::uint64_t blocks,
                                            const point_statistics& stats);
[[nodiscard]] merged_prefix deserialize_merged_prefix(std::string_view in);
// Whether serialized bytes hold a merged prefix (else a unit's result).
[[nodiscard]] bool is_merged_prefix(std::string_view in) noexcept;
// Throws stickslip::error (io_failure) unless `p` has the shape of the
// merged prefix of a point of `s`: the point in the grid, 1 .. blocks per
// point blocks, their realization count, the point's binning and levels.
void check_prefix_shape(const sweep_spec& s, const merged_prefix& p);

// Throws stickslip::error (io_failure) unless `r` is exactly what
// simulate_block(s, u) has the shape of: the unit lies in the grid, the
// realization count matches the block, the histograms have the point's
// binning, no convergence trace, and records only when s.keep_records.
// Guards the merger against well-formed but foreign data.
void check_block_shape(const sweep_spec& s, const work_unit& u, const block_result& r);

// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320), as in zlib and PNG.
[[nodiscard]] std::uint32_t crc32(std::string_view data, std::uint32_t crc = 0) noexcept;

// True when two specs give the same results bit for bit: every field equal
// to the bit, except those that only change speed (the engine).
[[nodiscard]] bool same_results(const sweep_spec& a, const sweep_spec& b);

// A 64-bit fingerprint of the results-relevant part of a spec (FNV-1a over
// its serialized bytes, engine reset) and of the build (version, git
// revision, SIMD target): specs with same_results() give equal fingerprints
// within one build. Stamped on every journal segment, so a resume or merge
// never mixes in units computed by another build (they are recomputed).
[[nodiscard]] std::uint64_t fingerprint(const sweep_spec& s);

// Human-readable name of the first results-relevant field in which two specs
// differ, with both values ("realizations: 2000 vs 4000"); empty when
// same_results(a, b).
[[nodiscard]] std::string first_difference(const sweep_spec& a, const sweep_spec& b);

}  // namespace stickslip
