// `stickslip merge` (apps/stickslip/cmd_merge.cpp -> run::merge_shards,
// src/run/merge.cpp) on arbitrary shard directories.
//
// Once per process, the real journal writer (io::journal_writer) writes, for
// three small family specs (A; B = A with another seed; C = a records-keeping
// spec), one segment per unit for every shard layout i/n (n = 1, 2, 3) and,
// for A and B, one segment per merged prefix (point p, its first L blocks) as
// a whole run journals them; the bytes and names are kept in memory, with the
// direct run (run_sweep on one thread) of each spec as the reference.
//
// Each input then builds 1 to 4 input directories in a temporary directory
// (/dev/shm when there is one) from those files and edits them:
//   byte 0: the shard count n = 1 + (b & 3) % 3; directory count = 1 + (b >> 2) % 4
//   per directory, kind byte k: layout = k & 7
//       0..3 shard i/n, i = (k >> 3) % n      4 a whole run: merged prefixes
//       of L_p blocks (the next byte, 2 bits per point) then the later units
//       5 an empty directory (no journal)    6 a path that does not exist
//       7 a shard journal without header.bin
//     spec = A, or B when (k >> 5) == 6, C when (k >> 5) == 7;
//     then a drop mask (bit j drops the directory's j-th unit segment:
//     missing units) and a duplicate mask (bit j adds unit j's segment from
//     another shard: duplicated units)
//   then up to 12 edits: cmd byte, op = cmd & 7 on directory (cmd >> 3) & 3,
//   file index byte (0 = header.bin, then the segments in order):
//     0 xor a byte (u16 offset, u8 mask)   1 truncate (u16)
//     2 overwrite (u16, n u8, bytes)       3 insert (u16, n u8, bytes)
//     4 erase (u16, n u8)                  5 replace by a file of another
//       directory (dir u8, file u8): mixed specs, foreign headers
//     6 remove, or (cmd & 0x80) a directory in its place
//     7 replace by raw bytes (n u16, bytes)
// CRCs are never recomputed here: a consistent forgery cannot be told from
// data (fuzz_journal_reader covers the decoders behind the CRCs).
//
// Properties: merge_shards either throws stickslip::error with exit code 2, 3
// or 5 (never internal, never another exception, never a crash or sanitizer
// report), or returns results equal, bit for bit (every point's statistics,
// convergence trace and raw records), to the direct run of the spec of one
// of the fixture journals: nothing is silently misread. Without edits the
// outcome is known: all headers of one spec and every unit covered give
// results, directories without a journal give invalid_input (2), two specs
// give resume_mismatch (5), and missing units give invalid_input (2).
// FUZZ_TRACE=1 prints the decoded directories and the outcome.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "fuzz_common.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/journal.hpp"
#include "stickslip/run/merge.hpp"
#include "stickslip/run/shard.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/sweep.hpp"

namespace {

namespace fs = std::filesystem;
using namespace stickslip;

struct byte_source {
  const std::uint8_t* p;
  std::size_t n;
  std::uint8_t u8() {
    if (n == 0) return 0;
    --n;
    return *p++;
  }
  std::uint16_t u16() { return static_cast<std::uint16_t>(u8() | (u8() << 8)); }
  std::string bytes(std::size_t len) {
    len = std::min(len, n);
    std::string s(reinterpret_cast<const char*>(p), len);
    p += len;
    n -= len;
    return s;
  }
};

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void spill(const fs::path& path, const std::string& data) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(data.data(), static_cast<std::streamsize>(data.size()));
  FUZZ_CHECK(out.good(), "cannot write %s", path.c_str());
}

struct journal_file {
  std::string name, bytes;
};

// Writes what `fill` gives one writer into a fresh journal and returns its
// segments (one per flush), in the order written.
template <class Fill>
std::vector<journal_file> written_segments(const fs::path& dir, const sweep_spec& spec,
                                           const std::string& tag, Fill fill) {
  std::error_code ec;
  fs::remove_all(dir, ec);
  {
    io::journal_writer w(dir.string(), spec, io::run_metadata{"fuzz", "", "", "", ""}, tag,
                         std::chrono::hours(1));
    fill(w);
  }
  std::vector<journal_file> out;
  for (const auto& e : fs::directory_iterator(io::journal_path(dir.string()))) {
    const auto name = e.path().filename().string();
    if (name.starts_with("seg-")) out.push_back({name, slurp(e.path())});
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  return out;
}

// One spec's journal files and its direct run.
struct spec_fixture {
  sweep_spec spec;
  std::string header;
  std::uint64_t units = 0, blocks = 0;
  std::size_t points = 0;
  // by_shards[n - 1][unit index]: the unit's segment as shard (index % n)/n writes it
  std::vector<std::vector<journal_file>> by_shards;
  // prefixes[p][L - 1]: a whole run's segment holding point p's first L blocks merged
  std::vector<std::vector<journal_file>> prefixes;
  std::vector<std::string> direct;  // per point: its statistics and records, serialized

  spec_fixture(const sweep_spec& s, const fs::path& scratch) : spec(s) {
    validate(spec);
    units = unit_count(spec);
    blocks = blocks_per_point(spec);
    points = point_count(spec);
    std::vector<block_result> results;
    for (std::uint64_t i = 0; i < units; ++i) results.push_back(simulate_block(spec, unit_at(spec, i)));
    for (std::uint64_t n = 1; n <= 3; ++n) {
      std::vector<journal_file> segs(units);
      for (std::uint64_t i = 0; i < n; ++i) {
        const run::shard sh{i, n};
        std::vector<std::uint64_t> owned;
        const auto files = written_segments(scratch, spec, sh.tag(), [&](io::journal_writer& w) {
          for (std::uint64_t j = 0; j < units; ++j) {
            if (!sh.owns(spec, unit_at(spec, j))) continue;
            w.add(unit_at(spec, j), results[j]);
            w.flush();
            owned.push_back(j);
          }
        });
        FUZZ_CHECK(files.size() == owned.size(), "fixture: %zu segments for %zu units",
                   files.size(), owned.size());
        for (std::size_t k = 0; k < owned.size(); ++k) segs[owned[k]] = files[k];
      }
      by_shards.push_back(std::move(segs));
    }
    header = slurp(fs::path(io::journal_path(scratch.string())) / "header.bin");
    if (!spec.keep_records) {
      prefixes.resize(points);
      for (std::size_t p = 0; p < points; ++p) {
        ordered_merger m(spec);
        for (std::uint64_t b = 0; b < blocks; ++b) {
          m.add(work_unit{p, b}, results[p * blocks + b]);
          const auto files = written_segments(scratch, spec, "whole", [&](io::journal_writer& w) {
            w.add_prefix(p, b + 1, m.merged(p));
            w.flush();
          });
          FUZZ_CHECK(files.size() == 1, "fixture: %zu prefix segments", files.size());
          prefixes[p].push_back(files[0]);
        }
      }
    }
    const result_set r = run_sweep(spec, 1);
    for (std::size_t p = 0; p < points; ++p) direct.push_back(point_bytes(r, p));
  }

  static std::string point_bytes(const result_set& r, std::size_t p) {
    block_result b{r.points[p].stats, r.records.empty() ? std::vector<realization_record>{}
                                                        : r.records[p]};
    return serialize(work_unit{p, 0}, b);
  }
};

struct merge_fixture {
  fs::path root, scratch;
  std::vector<spec_fixture> specs;  // A, B, C

  merge_fixture() {
    const fs::path base = fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    std::string tmpl = (base / "stickslip-fuzz-merge-XXXXXX").string();
    FUZZ_CHECK(::mkdtemp(tmpl.data()) != nullptr, "mkdtemp failed");
    root = fs::path(tmpl) / "in";
    scratch = fs::path(tmpl) / "scratch";

    sweep_spec a;  // 2 points x 3 blocks of 2 realizations, damped, unequal friction
    a.base.window = 4.0;
    a.base.damping = 0.3;
    a.base.static_friction = 1.5;
    a.base.kinetic_friction = 1.0;
    a.base.belt_levels = {1.0, -0.5};
    a.base.belt_rates = {1.0, 2.0};
    a.axes = {axis{"k", {4.0, 9.0}}};
    a.realizations = 6;
    a.block_size = 2;
    a.histograms.bins = 2;
    a.seed = 7;
    a.observe_times = {0.0, 1.5, 4.0};  // the observe-time block and its sketches
    sweep_spec b = a;
    b.seed = 8;
    sweep_spec c = a;  // raw records: every block journaled as it is
    c.realizations = 4;
    c.keep_records = true;
    for (const auto& s : {a, b, c}) specs.emplace_back(s, scratch);
    std::error_code ec;
    fs::remove_all(scratch, ec);
  }
  ~merge_fixture() {
    std::error_code ec;
    fs::remove_all(root.parent_path(), ec);
  }
};

merge_fixture& fixture() {
  static merge_fixture f;
  return f;
}

struct input_dir {
  enum class layout { shard, whole, empty, absent, headerless } kind = layout::shard;
  std::size_t spec = 0;
  std::optional<std::string> header;  // header.bin (absent: nullopt)
  bool header_is_directory = false;
  std::vector<journal_file> segments;
  std::vector<bool> segment_is_directory;
  std::set<std::uint64_t> covered;  // unit indices its undamaged files cover
};

const char* layout_name(input_dir::layout k) {
  switch (k) {
    case input_dir::layout::shard: return "shard";
    case input_dir::layout::whole: return "whole run";
    case input_dir::layout::empty: return "no journal";
    case input_dir::layout::absent: return "absent";
    default: return "headerless";
  }
}

input_dir decode_dir(const merge_fixture& f, byte_source& in, std::uint64_t n) {
  input_dir d;
  const std::uint8_t k = in.u8();
  const int sel = k >> 5;
  d.spec = sel == 6 ? 1 : sel == 7 ? 2 : 0;
  const spec_fixture& s = f.specs[d.spec];
  const int kind = k & 7;
  if (kind == 5) d.kind = input_dir::layout::empty;
  if (kind == 6) d.kind = input_dir::layout::absent;
  if (kind == 5 || kind == 6) return d;
  const std::uint8_t drop = in.u8(), dup = in.u8();
  std::vector<std::uint64_t> wanted;
  if (kind == 4) {
    d.kind = input_dir::layout::whole;
    const std::uint8_t lengths = in.u8();
    for (std::size_t p = 0; p < s.points; ++p) {
      std::uint64_t from = 0;
      if (!s.prefixes.empty()) {
        from = ((lengths >> (2 * p)) & 3) % (s.blocks + 1);
        if (from > 0) {
          d.segments.push_back(s.prefixes[p][from - 1]);
          for (std::uint64_t b = 0; b < from; ++b) d.covered.insert(p * s.blocks + b);
        }
      }
      for (std::uint64_t b = from; b < s.blocks; ++b) wanted.push_back(p * s.blocks + b);
    }
  } else {
    d.kind = kind == 7 ? input_dir::layout::headerless : input_dir::layout::shard;
    const std::uint64_t i = (k >> 3) % n;
    for (std::uint64_t j = 0; j < s.units; ++j)
      if (j % n == i) wanted.push_back(j);
  }
  const auto& pool = s.by_shards[n - 1];
  for (std::size_t j = 0; j < wanted.size(); ++j) {
    if (j < 8 && (drop >> j) & 1) continue;
    d.segments.push_back(pool[wanted[j]]);
    d.covered.insert(wanted[j]);
  }
  for (std::uint64_t j = 0; j < std::min<std::uint64_t>(8, s.units); ++j) {
    if (!((dup >> j) & 1) || d.covered.count(j)) continue;
    d.segments.push_back(pool[j]);
    d.covered.insert(j);
  }
  if (d.kind != input_dir::layout::headerless) d.header = s.header;
  d.segment_is_directory.assign(d.segments.size(), false);
  return d;
}

// One edit of one file of one directory; false if it named nothing.
bool apply_edit(std::vector<input_dir>& dirs, byte_source& in) {
  const std::uint8_t cmd = in.u8();
  const int op = cmd & 7;
  input_dir& d = dirs[((cmd >> 3) & 3) % dirs.size()];
  if (d.kind == input_dir::layout::absent || d.kind == input_dir::layout::empty) return false;
  const std::size_t nfiles = 1 + d.segments.size();
  const std::size_t which = in.u8() % nfiles;
  std::optional<std::string>* header = which == 0 ? &d.header : nullptr;
  if (header && !*header) *header = std::string();
  std::string& s = header ? **header : d.segments[which - 1].bytes;
  if (header) d.header_is_directory = false;
  else d.segment_is_directory[which - 1] = false;
  auto offset = [&] { return static_cast<std::size_t>(in.u16()) % (s.size() + 1); };
  switch (op) {
    case 0: {
      const std::size_t at = offset();
      const std::uint8_t mask = in.u8();
      if (at < s.size()) s[at] = static_cast<char>(s[at] ^ (mask ? mask : 0xff));
      break;
    }
    case 1:
      s.resize(offset());
      break;
    case 2: {
      const std::size_t at = offset();
      const std::string b = in.bytes(in.u8());
      s.replace(at, std::min(b.size(), s.size() - at), b);
      break;
    }
    case 3: {
      const std::size_t at = offset();
      s.insert(at, in.bytes(in.u8()));
      break;
    }
    case 4: {
      const std::size_t at = offset();
      s.erase(at, in.u8());
      break;
    }
    case 5: {
      const input_dir& from = dirs[in.u8() % dirs.size()];
      const std::size_t j = in.u8() % (1 + from.segments.size());
      if (j == 0 && from.header) s = *from.header;
      else if (j > 0) s = from.segments[j - 1].bytes;
      break;
    }
    case 6:
      if (header) {
        header->reset();
        d.header_is_directory = cmd & 0x80;
      } else {
        s.clear();
        d.segment_is_directory[which - 1] = cmd & 0x80;
        if (!(cmd & 0x80)) d.segments[which - 1].name.clear();  // removed
      }
      break;
    default:
      s = in.bytes(in.u16());
  }
  return true;
}

void write_dir(const fs::path& path, const input_dir& d) {
  if (d.kind == input_dir::layout::absent) return;
  fs::create_directories(path);
  if (d.kind == input_dir::layout::empty) return;
  const fs::path j = io::journal_path(path.string());
  fs::create_directory(j);
  if (d.header_is_directory) fs::create_directory(j / "header.bin");
  else if (d.header) spill(j / "header.bin", *d.header);
  for (std::size_t i = 0; i < d.segments.size(); ++i) {
    if (d.segments[i].name.empty()) continue;
    if (d.segment_is_directory[i]) fs::create_directories(j / d.segments[i].name);
    else spill(j / d.segments[i].name, d.segments[i].bytes);
  }
}

bool trace() {
  static const bool on = std::getenv("FUZZ_TRACE") != nullptr;
  return on;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  merge_fixture& f = fixture();
  byte_source in{data, size};
  const std::uint8_t first = in.u8();
  const std::uint64_t n = 1 + (first & 3) % 3;
  const std::size_t ndirs = 1 + (first >> 2) % 4;
  std::vector<input_dir> dirs;
  for (std::size_t i = 0; i < ndirs; ++i) dirs.push_back(decode_dir(f, in, n));
  bool edited = false;
  for (int e = 0; in.n > 0 && e < 12; ++e) edited = apply_edit(dirs, in) || edited;

  std::error_code ec;
  fs::remove_all(f.root, ec);
  fs::create_directories(f.root);
  std::vector<std::string> paths;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    paths.push_back((f.root / ("shard" + std::to_string(i))).string());
    write_dir(paths.back(), dirs[i]);
  }

  // What an undamaged input must give.
  enum class expect { any, results, invalid_input, resume_mismatch } expected = expect::any;
  if (!edited) {
    const bool no_journal = std::any_of(dirs.begin(), dirs.end(), [](const input_dir& d) {
      return d.kind == input_dir::layout::absent || d.kind == input_dir::layout::empty;
    });
    const bool all_headers = std::all_of(dirs.begin(), dirs.end(), [](const input_dir& d) {
      return d.kind == input_dir::layout::shard || d.kind == input_dir::layout::whole;
    });
    const bool one_spec = std::all_of(dirs.begin(), dirs.end(), [&](const input_dir& d) {
      return d.spec == dirs[0].spec;
    });
    std::set<std::uint64_t> covered;
    for (const auto& d : dirs) covered.insert(d.covered.begin(), d.covered.end());
    if (no_journal) expected = expect::invalid_input;
    else if (all_headers && !one_spec) expected = expect::resume_mismatch;
    else if (all_headers && covered.size() == f.specs[dirs[0].spec].units) expected = expect::results;
    else if (all_headers) expected = expect::invalid_input;
  }
  if (trace()) {
    std::fprintf(stderr, "n = %llu, edited %d, expect %d\n", static_cast<unsigned long long>(n),
                 edited, static_cast<int>(expected));
    for (const auto& d : dirs)
      std::fprintf(stderr, "  %s, spec %zu, %zu segments (%zu bytes first), %zu units covered\n",
                   layout_name(d.kind), d.spec, d.segments.size(),
                   d.segments.empty() ? std::size_t{0} : d.segments[0].bytes.size(), d.covered.size());
  }

  try {
    const run::merged_shards m = run::merge_shards(paths);
    const auto spec = std::find_if(f.specs.begin(), f.specs.end(), [&](const spec_fixture& s) {
      return same_results(s.spec, m.results.spec);
    });
    FUZZ_CHECK(spec != f.specs.end(), "merged results of a spec no input was written with");
    FUZZ_CHECK(m.results.points.size() == spec->points, "%zu points", m.results.points.size());
    for (std::size_t p = 0; p < spec->points; ++p)
      FUZZ_CHECK(spec_fixture::point_bytes(m.results, p) == spec->direct[p],
                 "point %zu differs from the direct run of its spec", p);
    FUZZ_CHECK(expected == expect::any || expected == expect::results,
               "an undamaged input was merged, expected error %d", static_cast<int>(expected));
    if (trace()) std::fprintf(stderr, "  merged: equal to the direct run\n");
  } catch (const error& e) {
    const auto code = e.code();
    if (trace()) std::fprintf(stderr, "  refused (%d): %s\n", static_cast<int>(code), e.what());
    FUZZ_CHECK(code == exit_code::invalid_input || code == exit_code::resume_mismatch ||
                   code == exit_code::io_failure,
               "exit code %d: %s", static_cast<int>(code), e.what());
    FUZZ_CHECK(expected != expect::results, "an undamaged complete input was refused: %s",
               e.what());
    FUZZ_CHECK(expected != expect::invalid_input || code == exit_code::invalid_input,
               "expected invalid_input: %s", e.what());
    FUZZ_CHECK(expected != expect::resume_mismatch || code == exit_code::resume_mismatch,
               "expected resume_mismatch: %s", e.what());
  }
  return 0;
}
