// The checkpoint journal reader (io/journal.hpp, src/io/store/journal_read.cpp)
// on damaged journals. Once per process a small valid journal is written in
// a temporary directory: a two-point family sweep (damping, two rates, raw
// records kept, three observe times), 4 work units in two segments of two
// records each, plus the serialized bytes of every unit as the reference. Each input is a list of
// edits, applied to a fresh copy of that journal before it is read:
//   cmd byte: edit = cmd & 7, file = (cmd >> 3) & 3 (header.bin, segment 1,
//   segment 2, or an extra segment that starts as a copy of segment 1 or 2:
//   the same units twice)
//     0 xor one byte (offset u16, mask u8)     1 truncate (offset u16)
//     2 overwrite (offset u16, n u8, bytes)    3 insert (offset u16, n u8, bytes)
//     4 erase (offset u16, n u8)               5 recompute every CRC of the file
//     6 remove the file, or (cmd & 0x80) put a directory in its place
//     7 replace the whole file (n u16, bytes)
// Edit 5 lets damage through the CRCs to the decoders (deserialize_sweep_spec,
// deserialize_unit_result, check_block_shape). The journal is then read as
// --resume reads it (the expected spec) and as merge first reads it (none).
// Properties: no crash, no sanitizer report, no error but resume_mismatch
// (with the expected spec, after the header was edited); every skipped file
// or record is reported; an undamaged journal is accepted whole; and no unit
// is misread: each accepted unit serializes to exactly its original bytes,
// or, only once CRCs were recomputed over edits, to the bytes of a record
// that is on disk (a consistent forgery cannot be told from data).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "fuzz_common.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/journal.hpp"
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

std::uint64_t le(const std::string& s, std::size_t at, int width) {
  std::uint64_t v = 0;
  for (int i = width - 1; i >= 0; --i) v = (v << 8) | static_cast<std::uint8_t>(s[at + i]);
  return v;
}
void put_le32(std::string& s, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) s[at + i] = static_cast<char>(v >> (8 * i));
}

// The frame of a header or segment: magic(4) version(4) length(8) crc(4)
// payload; a segment then has records length(4) crc(4) payload. Calls
// `record(offset of its length field, payload offset, payload length)`
// for every record that fits; returns the end of the frame (0: none).
template <class Record>
std::size_t walk(const std::string& s, bool segment, Record record) {
  if (s.size() < 20) return 0;
  const std::uint64_t len = le(s, 8, 8);
  if (len > s.size() - 20) return 0;
  std::size_t pos = 20 + static_cast<std::size_t>(len);
  if (segment) {
    while (s.size() - pos >= 8) {
      const std::uint64_t rlen = le(s, pos, 4);
      if (rlen > s.size() - pos - 8) break;
      record(pos, pos + 8, static_cast<std::size_t>(rlen));
      pos += 8 + static_cast<std::size_t>(rlen);
    }
  }
  return 20 + static_cast<std::size_t>(len);
}

void fix_crcs(std::string& s, bool segment) {
  const std::size_t frame_end =
      walk(s, segment, [&](std::size_t at, std::size_t from, std::size_t len) {
        put_le32(s, at + 4, crc32(std::string_view(s).substr(from, len)));
      });
  if (frame_end) put_le32(s, 16, crc32(std::string_view(s).substr(20, frame_end - 20)));
}

struct journal_fixture {
  fs::path root, jdir;
  sweep_spec spec;
  std::string header, config;
  std::vector<std::string> segment_names;      // the two segments, as written
  std::vector<std::string> segments;           // their bytes
  std::map<work_unit, std::string> originals;  // serialize(unit, block) of every unit

  journal_fixture() {
    // In memory when possible: every input rewrites the journal's files.
    const fs::path base =
        fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    std::string tmpl = (base / "stickslip-fuzz-journal-XXXXXX").string();
    FUZZ_CHECK(::mkdtemp(tmpl.data()) != nullptr, "mkdtemp failed");
    root = tmpl;
    jdir = io::journal_path(root.string());

    spec.base.window = 4.0;
    spec.base.damping = 0.3;
    spec.base.static_friction = 1.5;
    spec.base.kinetic_friction = 1.0;
    spec.base.belt_levels = {1.0, -0.5};
    spec.base.belt_rates = {1.0, 2.0};
    spec.axes = {axis{"k", {4.0, 9.0}}};
    spec.realizations = 4;
    spec.block_size = 2;
    spec.histograms.bins = 5;
    spec.keep_records = true;
    spec.seed = 7;
    spec.observe_times = {0.0, 1.5, 4.0};  // the observe-time block and its sketches
    validate(spec);
    {
      io::journal_writer w(root.string(), spec, io::run_metadata{"fuzz", "", "", "", ""}, "fuzz",
                           std::chrono::hours(1));
      for (std::uint64_t i = 0; i < unit_count(spec); ++i) {
        const work_unit u = unit_at(spec, i);
        const block_result r = simulate_block(spec, u);
        originals[u] = serialize(u, r);
        w.add(u, r);
        if (i % 2 == 1) w.flush();
      }
    }
    header = slurp(jdir / "header.bin");
    config = slurp(jdir / "config.toml");
    for (const auto& e : fs::directory_iterator(jdir)) {
      const auto name = e.path().filename().string();
      if (name.starts_with("seg-")) segment_names.push_back(name);
    }
    std::sort(segment_names.begin(), segment_names.end());
    FUZZ_CHECK(segment_names.size() == 2 && originals.size() == 4, "fixture: %zu segments",
               segment_names.size());
    for (const auto& name : segment_names) segments.push_back(slurp(jdir / name));
  }
  ~journal_fixture() {
    std::error_code ec;
    fs::remove_all(root, ec);
  }
};

journal_fixture& fixture() {
  static journal_fixture f;
  return f;
}

struct file_state {
  std::optional<std::string> bytes;  // nullopt: absent
  bool directory = false;
};

// Checks one read of the journal.
void check(const journal_fixture& f, const io::journal_contents& c, std::size_t reports,
           bool pristine, bool crcs_recomputed, const std::set<std::string>& on_disk) {
  FUZZ_CHECK(reports == c.damaged, "%zu files or records skipped, %zu reported", c.damaged,
             reports);
  FUZZ_CHECK(std::isfinite(c.elapsed_seconds) && c.elapsed_seconds >= 0, "elapsed seconds %g",
             c.elapsed_seconds);
  if (pristine) {
    FUZZ_CHECK(c.damaged == 0 && c.units.size() == f.originals.size() && c.spec &&
                   same_results(*c.spec, f.spec),
               "an undamaged journal: %zu of %zu units, %zu damaged", c.units.size(),
               f.originals.size(), c.damaged);
  }
  for (const auto& [u, place] : c.units) {
    const block_result block = place.decode();  // read back from the files still on disk
    const std::string got = serialize(u, block);
    const auto it = f.originals.find(u);
    if (it != f.originals.end() && got == it->second) continue;
    FUZZ_CHECK(crcs_recomputed, "point %zu block %llu accepted with contents other than written",
               u.point, static_cast<unsigned long long>(u.block));
    FUZZ_CHECK(on_disk.count(got), "point %zu block %llu accepted, but no record on disk holds it",
               u.point, static_cast<unsigned long long>(u.block));
    const sweep_spec& s = c.spec ? *c.spec : f.spec;
    try {
      check_block_shape(s, u, block);
    } catch (const error& e) {
      FUZZ_CHECK(false, "an accepted unit fails check_block_shape: %s", e.what());
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  journal_fixture& f = fixture();
  // [0] header.bin, [1], [2] the segments, [3] an extra segment (absent)
  std::vector<file_state> files(4);
  files[0].bytes = f.header;
  files[1].bytes = f.segments[0];
  files[2].bytes = f.segments[1];
  bool crcs_recomputed = false;

  byte_source in{data, size};
  for (int edits = 0; in.n > 0 && edits < 16; ++edits) {
    const std::uint8_t cmd = in.u8();
    const int op = cmd & 7;
    const std::size_t which = (cmd >> 3) & 3;
    file_state& file = files[which];
    if (which == 3 && !file.bytes && !file.directory)
      file.bytes = f.segments[(cmd >> 5) & 1];  // the same units twice
    if (!file.bytes) file.bytes = std::string();
    file.directory = false;
    std::string& s = *file.bytes;
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
      case 5:
        fix_crcs(s, which != 0);
        break;
      case 6:
        file.bytes.reset();
        file.directory = cmd & 0x80;
        break;
      default:
        s = in.bytes(in.u16());
    }
    if (op == 5) crcs_recomputed = true;
  }

  // Write the edited journal.
  std::error_code ec;
  fs::remove_all(f.jdir, ec);
  fs::create_directories(f.jdir);
  spill(f.jdir / "config.toml", f.config);
  const std::string names[4] = {"header.bin", f.segment_names[0], f.segment_names[1],
                                "seg-zz-extra.bin"};
  std::set<std::string> on_disk;  // the payloads of every record that fits its frame
  for (std::size_t i = 0; i < 4; ++i) {
    if (files[i].directory) fs::create_directory(f.jdir / names[i]);
    if (!files[i].bytes) continue;
    spill(f.jdir / names[i], *files[i].bytes);
    if (i > 0)
      walk(*files[i].bytes, true, [&](std::size_t, std::size_t from, std::size_t len) {
        on_disk.insert(files[i].bytes->substr(from, len));
      });
  }
  const bool pristine = files[0].bytes == f.header && files[1].bytes == f.segments[0] &&
                        files[2].bytes == f.segments[1] && !files[3].bytes && !files[0].directory &&
                        !files[1].directory && !files[2].directory && !files[3].directory;

  // As --resume reads it.
  std::size_t reports = 0;
  const io::journal_report count = [&](const std::string&) { ++reports; };
  try {
    const io::journal_contents c = io::read_journal(f.root.string(), &f.spec, count);
    if (c.spec)
      FUZZ_CHECK(same_results(*c.spec, f.spec), "the header's spec differs and was not refused");
    check(f, c, reports, pristine, crcs_recomputed, on_disk);
  } catch (const error& e) {
    FUZZ_CHECK(e.code() == exit_code::resume_mismatch, "unexpected error: %s", e.what());
    FUZZ_CHECK(files[0].bytes && *files[0].bytes != f.header,
               "resume_mismatch with the original header: %s", e.what());
  }
  // As merge first reads it (no expected spec).
  reports = 0;
  try {
    const io::journal_contents c = io::read_journal(f.root.string(), nullptr, count);
    check(f, c, reports, pristine, crcs_recomputed, on_disk);
  } catch (const error& e) {
    FUZZ_CHECK(false, "unexpected error: %s", e.what());
  }
  return 0;
}
