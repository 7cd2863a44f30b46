// Internals shared by journal.cpp (writing) and journal_read.cpp (reading).
#pragma once
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "stickslip/io/metadata.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::io::detail {

using stickslip::detail::byte_reader;
using stickslip::detail::byte_writer;
using stickslip::detail::corrupt;

inline constexpr std::string_view header_magic = "SSJH", segment_magic = "SSJS";
inline constexpr const char* header_file = "header.bin";
inline constexpr const char* config_file = "config.toml";

struct journal_header {
  sweep_spec spec;
  run_metadata metadata;
};

// header.bin: magic, version, payload length, CRC-32 of the payload, payload
// (serialized spec, then the five metadata strings).
[[nodiscard]] bytes encode_header(const sweep_spec& spec, const run_metadata& meta);
// Throws stickslip::error (io_failure) naming the problem.
[[nodiscard]] journal_header decode_header(std::string_view data);
// Reads and decodes `path`; nullopt if it does not exist or is damaged.
[[nodiscard]] std::optional<journal_header> read_header_file(const std::string& path,
                                                             std::string* problem = nullptr);

// Segment header: magic, version, body length, CRC-32 of the body, body
// (spec fingerprint, elapsed seconds of the run, run id, record count).
[[nodiscard]] bytes encode_segment_header(std::uint64_t fingerprint, double elapsed,
                                          const std::string& run_id, std::uint64_t records);

// write(2) the pieces one after the other (a segment's header and its
// records, without joining them) to a fresh file `tmp`, fsync, close, rename
// to `final_path`, fsync the directory: the file appears whole or not at
// all. On failure removes `tmp` and throws io_error(final_path, reason)
// (ENOSPC, EFBIG under `ulimit -f`, EIO, ...).
void write_file_durably(const std::string& tmp, const std::string& final_path,
                        std::initializer_list<std::string_view> pieces);
inline void write_file_durably(const std::string& tmp, const std::string& final_path,
                               std::string_view data) {
  write_file_durably(tmp, final_path, {data});
}
[[nodiscard]] std::string unique_suffix();

}  // namespace stickslip::io::detail
