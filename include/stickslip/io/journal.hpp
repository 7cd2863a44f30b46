// Checkpoint journal of a sweep: every finished work unit is kept on disk so
// that a killed run (crash, kill -9, job time limit) can be resumed, and so
// that shards of a job array can be merged. Layout inside the output
// directory DIR (docs/scaling.md):
//
//   DIR/.journal/config.toml     the resolved configuration, for people
//   DIR/.journal/header.bin      format version, the exact sweep spec, the
//                                first run's metadata; CRC-32
//   DIR/.journal/seg-<run>-<n>.bin  a segment: the spec's fingerprint, the
//                                run's elapsed time, then records
//                                [length u32][crc32 u32][serialized record],
//                                a record being a unit's block result or a
//                                point's merged prefix (sweep.hpp)
//
// A whole run journals merged prefixes: every checkpoint writes, for each
// point that advanced, its blocks merged so far (one record, whatever their
// number), plus the few blocks that wait for an earlier one; a segment whose
// records are all superseded by later ones of the same writer is removed.
// So the journal's size and a resume's memory grow with the grid, not with
// the realizations. Shards and sweeps that keep raw records journal every
// block as it is.
//
// Every file is written to a unique temporary name, fsynced, and renamed
// (then the directory is fsynced), so a completed segment is never lost or
// half-visible; a kill leaves at most a stray temporary, which is ignored and
// removed. Readers still check everything: a truncated or corrupt segment, or
// a record whose CRC, shape or fingerprint does not fit, is reported and its
// units are recomputed; the valid records before it are kept.
#pragma once
#include <chrono>
#include <cstdint>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "stickslip/io/metadata.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::io {

inline constexpr const char* journal_directory = ".journal";

// DIR/.journal
[[nodiscard]] std::string journal_path(const std::string& dir);
// True when DIR holds a journal (its header or any segment).
[[nodiscard]] bool journal_exists(const std::string& dir);

// Where a checked journal record's payload is: read back, and checked again,
// when it is used. A resume of a large grid holds every journaled point until
// its window comes, and `merge` every shard's units; holding their bytes made
// a resume peak far above the uninterrupted run, whose outputs are streamed
// (the 100,000-point grid's resume after 60,400 of 100,000 units: 253 MB,
// against 92 MB uninterrupted), and `merge` of that grid's two shards held
// 577 MB of decoded units. Holding where they are takes ~100 bytes a record
// with its map node: the resume 88 MB, the merge 140-202 MB. Reading back
// checks the length and the CRC again: a journal changed on disk since it
// was read throws io_failure (the output lock keeps other stickslip runs out
// of a run's own directory; `merge` reads shard directories it does not
// lock).
struct journal_place {
  std::shared_ptr<const std::string> segment;  // the segment file's path
  std::uint64_t offset = 0;                    // of the record's payload in it
  std::uint32_t length = 0, crc = 0;           // of the payload
};

// Reads journal records back, keeping the last 8 segments open
// (restore_window reads a window's records in their segments' order).
class journal_readback {
 public:
  // The record's payload, every check passed at reading; throws io_failure
  // if the file no longer holds it.
  [[nodiscard]] std::string bytes(const journal_place& at);

 private:
  struct open_segment {
    std::shared_ptr<const std::string> path;
    std::ifstream in;
  };
  std::vector<open_segment> open_;  // the most recently used last
};

// A point's longest valid merged prefix.
struct journaled_prefix {
  std::uint64_t blocks = 0;
  journal_place place;
  [[nodiscard]] std::string bytes() const;  // serialize(merged_prefix)
  [[nodiscard]] merged_prefix decode(journal_readback& from) const;
  [[nodiscard]] merged_prefix decode() const;
};

// A valid journaled unit: a shard's, a sweep's that keeps records, or one
// a whole run journaled while it waited for its point's earlier blocks.
struct journaled_unit {
  journal_place place;
  [[nodiscard]] std::string bytes() const;  // serialize(unit, block)
  [[nodiscard]] block_result decode(journal_readback& from) const;
  [[nodiscard]] block_result decode() const;
};

// What a journal holds after reading and checking it.
struct journal_contents {
  std::optional<sweep_spec> spec;             // from the header (absent if unreadable)
  std::optional<run_metadata> metadata;       // the first run's metadata
  std::map<work_unit, journaled_unit> units;  // every valid journaled unit, once
  std::map<std::size_t, journaled_prefix> prefixes;  // the longest valid one per point
  std::set<std::string> runs;    // the run ids of its segments ("shard-3-of-8-...", "run-...")
  double elapsed_seconds = 0.0;  // sum over earlier runs of their last journaled time
  std::size_t segments = 0;      // segment files read
  std::size_t damaged = 0;       // files or records skipped as truncated/corrupt/foreign
};

// Problems found while reading are passed to `report` (one line each; the
// command line prints them on stderr). Default: ignore.
using journal_report = std::function<void(const std::string&)>;

// Reads DIR/.journal. If `expected` is given, the journal must have been made
// with exactly that spec: otherwise throws stickslip::error with
// exit_code::resume_mismatch naming the first difference. Records are
// checked (CRC, decoding, fingerprint, shape) against the header's spec, or
// `expected` when the header is unreadable; anything that fails is reported
// and skipped. Throws io_failure only if the directory cannot be listed.
[[nodiscard]] journal_contents read_journal(const std::string& dir,
                                            const sweep_spec* expected,
                                            const journal_report& report = {});

// Appends finished units to DIR/.journal in segments. Not thread-safe: call
// from one thread at a time (run_units' unit_done hook is serialized).
class journal_writer {
 public:
  // Creates DIR and DIR/.journal if needed and writes the header unless one
  // that matches `spec` is there already. `run_tag` becomes part of segment
  // names (e.g. "shard-3-of-8"); a unique suffix is added per process.
  // A segment is committed when `flush_interval` has passed since the last
  // one (zero: after every unit), at flush(), and by the destructor.
  journal_writer(const std::string& dir, const sweep_spec& spec, const run_metadata& meta,
                 const std::string& run_tag,
                 std::chrono::duration<double> flush_interval = std::chrono::seconds(2));
  journal_writer(const journal_writer&) = delete;
  journal_writer& operator=(const journal_writer&) = delete;
  ~journal_writer();  // commits what is buffered (errors are swallowed)

  void add(const work_unit& u, const block_result& r);
  // A point's blocks [0, blocks) merged in order; never flushes by itself.
  void add_prefix(std::size_t point, std::uint64_t blocks, const point_statistics& merged);
  // Whether the checkpoint interval has passed since the last segment, and
  // (a nonzero interval) 20 times what the last checkpoint itself cost (the
  // merged prefixes it serialized, and the write), up to 15 intervals:
  // prefix checkpoints take at most ~5 % of a run however large its points'
  // statistics (a paper grid with 101 observe times wrote 10 MB every 2 s).
  [[nodiscard]] bool due() const noexcept;
  // Commits the buffered records as one segment, then removes this writer's
  // earlier segments whose every record a later one supersedes (a prefix of
  // the same point as long or longer). Throws io_failure.
  void flush();
  [[nodiscard]] std::uint64_t units_written() const noexcept { return written_; }
  [[nodiscard]] std::size_t segments_written() const noexcept { return segment_seq_; }
  [[nodiscard]] std::size_t segments_kept() const noexcept { return own_.size(); }

 private:
  // What one of this writer's segments covers: per record, the point and
  // the end of the blocks it holds (a prefix's length, a unit's block + 1).
  struct own_segment {
    std::string path;
    std::size_t seq = 0;
    std::vector<std::pair<std::size_t, std::uint64_t>> covers;
  };
  void remove_superseded();
  std::vector<std::pair<std::size_t, std::uint64_t>> buffered_covers_, buffered_prefixes_;
  std::size_t buffered_units_ = 0;
  std::vector<own_segment> own_;
  // The longest prefix per point in this writer's segments, and which
  // segment (its sequence number) holds it.
  std::map<std::size_t, std::pair<std::uint64_t, std::size_t>> longest_;

  std::string journal_dir_;
  std::uint64_t fingerprint_;
  std::string run_id_;
  std::chrono::duration<double> interval_;
  std::chrono::steady_clock::time_point started_, last_flush_;
  // Time spent serializing merged prefixes since the last segment, and that
  // plus writing it for the last segment.
  std::chrono::steady_clock::duration serializing_{}, last_cost_{};
  std::string buffer_;  // encoded records not yet committed
  std::size_t buffered_ = 0;
  std::size_t segment_seq_ = 0;
  std::uint64_t written_ = 0;
};

// Removes DIR/.journal and everything in it (after a successful run).
void remove_journal(const std::string& dir);

}  // namespace stickslip::io
