// Exact binary (de)serialization of sweep specs, work units and block results,
// for MPI messages and the checkpoint journal (src/io/store/journal*.cpp).
//
// The bytes are serial_bytes.hpp's: little-endian, doubles as their bit
// patterns, so a round trip is bit-exact. Every message starts with a 4-byte
// tag, the format version and the layout id (layout_id(): the list of
// statistics a block result holds, of model parameters a spec holds and of
// the fields of a record); vectors carry their length. The three lists are
// laid out by iterating them (statistics_schema.hpp, recorded_parameter_names
// in parameters.hpp, record_table in record_schema.hpp), so adding a
// statistic, a parameter or a record field changes the layout id, and data
// written without it is refused, never misread.
// Deserialization never trusts its input: every length is checked against
// the bytes that remain, every count against a sane bound, and histogram
// binnings against their invariants. Any problem throws stickslip::error
// (exit_code::io_failure) naming what was wrong; it never reads out of bounds.
// The journal adds a CRC-32 per record on top, to tell corruption from a bug.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

#include "stickslip/serial_bytes.hpp"
#include "stickslip/statistics_schema.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip {

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
