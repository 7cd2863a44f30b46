// Checkpoint journal: reading and checking. Nothing read from disk is
// trusted: each file and record is checked (magic, version, lengths, CRC-32,
// decoding, spec fingerprint, block shape) and skipped with a report when it
// fails, so its units are recomputed. See include/stickslip/io/journal.hpp.
#include <algorithm>
#include <cmath>
#include <set>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iterator>

#include "journal_detail.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/journal.hpp"

namespace stickslip::io {
namespace fs = std::filesystem;

namespace detail {
namespace {

// Reads a whole file; nullopt (with `problem`) if it cannot be read.
// Only regular files are read (a directory or device named like a journal
// file is damage, not data).
std::optional<std::string> slurp(const std::string& path, std::string& problem) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    problem = "not a regular file";
    return std::nullopt;
  }
  try {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      problem = "cannot open";
      return std::nullopt;
    }
    std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) {
      problem = "read error";
      return std::nullopt;
    }
    return data;
  } catch (const std::exception& e) {
    problem = std::string("read error: ") + e.what();
    return std::nullopt;
  }
}

// magic, version, length, crc, payload -> the checked payload.
std::string_view checked_frame(byte_reader& r, std::string_view magic, std::string_view what) {
  if (r.raw(magic.size(), what) != magic) throw corrupt(fmt::format("{}: bad magic", what));
  const auto version = r.u32(what);
  if (version != serial_format_version)
    throw corrupt(fmt::format("{}: format version {} (this program reads {})", what, version,
                              serial_format_version));
  const auto len = r.u64(what);
  const auto crc = r.u32(what);
  if (len > r.remaining())
    throw corrupt(fmt::format("{}: truncated ({} of {} bytes)", what, r.remaining(), len));
  const auto payload = r.raw(static_cast<std::size_t>(len), what);
  if (crc32(payload) != crc) throw corrupt(fmt::format("{}: CRC mismatch", what));
  return payload;
}

}  // namespace

journal_header decode_header(std::string_view data) {
  byte_reader outer(data);
  byte_reader r(checked_frame(outer, header_magic, "journal header"));
  outer.finish("journal header");
  journal_header h;
  h.spec = deserialize_sweep_spec(r.str("spec"));
  for (auto* f : {&h.metadata.command_line, &h.metadata.resolved_config, &h.metadata.version,
                  &h.metadata.git_revision, &h.metadata.created_utc})
    *f = r.str("run metadata");
  r.finish("journal header");
  return h;
}

std::optional<journal_header> read_header_file(const std::string& path, std::string* problem) {
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    if (problem) *problem = "missing";
    return std::nullopt;
  }
  std::string why;
  auto data = slurp(path, why);
  if (!data) {
    if (problem) *problem = why;
    return std::nullopt;
  }
  try {
    return decode_header(*data);
  } catch (const error& e) {
    if (problem) *problem = e.what();
    return std::nullopt;
  }
}

}  // namespace detail

namespace {

struct segment_reader {
  const sweep_spec& spec;
  std::uint64_t fingerprint;
  const journal_report& report;
  journal_contents& out;
  std::map<std::string, double> run_elapsed;  // run id -> latest elapsed
  // Records are kept as where they are (journal_place), not decoded: a
  // record read twice is told apart from a conflicting one by reading the
  // first back (rare: the same unit in two segments).
  std::set<work_unit> conflicting;
  std::set<std::size_t> conflicting_points;
  journal_readback earlier;

  // Whether an earlier record, read back, is `payload`: one whose segment
  // changed since it was read is not (both are then recomputed), rather
  // than an error blamed on the record being read now.
  bool holds(const journal_place& at, std::string_view payload) {
    try {
      return earlier.bytes(at) == payload;
    } catch (const error&) {
      return false;
    }
  }

  void note(const std::string& msg) {
    ++out.damaged;
    if (report) report(msg);
  }

  void read(const std::string& path) {
    ++out.segments;
    std::string why;
    const auto data = detail::slurp(path, why);
    const auto segment = std::make_shared<const std::string>(path);
    if (!data) return note(fmt::format("{}: {}; its units will be recomputed", path, why));
    detail::byte_reader outer(*data);
    std::uint64_t count = 0;
    try {
      detail::byte_reader h(detail::checked_frame(outer, detail::segment_magic, "segment header"));
      const auto fp = h.u64("fingerprint");
      const double elapsed = h.f64("elapsed");
      const auto run = h.str("run id");
      count = h.u64("record count");
      h.finish("segment header");
      if (fp != fingerprint)
        return note(fmt::format(
            "{}: written for another configuration or by another build of stickslip; "
            "ignored, its units will be recomputed",
            path));
      out.runs.insert(run);
      auto& e = run_elapsed[run];
      if (std::isfinite(elapsed) && elapsed > e) e = elapsed;
    } catch (const error& e) {
      return note(fmt::format("{}: {}; its units will be recomputed", path, e.what()));
    }
    for (std::uint64_t k = 0; k < count; ++k) {
      try {
        const auto len = outer.u32("record length");
        const auto crc = outer.u32("record CRC");
        const auto payload = outer.raw(len, "record");
        if (crc32(payload) != crc) throw detail::corrupt("CRC mismatch");
        const auto place = [&](std::string_view p) {
          return journal_place{segment, static_cast<std::uint64_t>(p.data() - data->data()), len,
                               crc};
        };
        if (is_merged_prefix(payload)) {
          auto prefix = deserialize_merged_prefix(payload);
          check_prefix_shape(spec, prefix);
          add(prefix, payload, journaled_prefix{prefix.blocks, place(payload)});
          continue;
        }
        const auto [unit, block] = deserialize_unit_result(payload);
        check_block_shape(spec, unit, block);
        add(unit, payload, journaled_unit{place(payload)});
      } catch (const error& e) {
        return note(fmt::format("{}: record {} of {}: {}; it and the {} after it will be "
                                "recomputed",
                                path, k + 1, count, e.what(), count - k - 1));
      }
    }
    if (outer.remaining() != 0)
      note(fmt::format("{}: {} unexpected trailing bytes ignored", path, outer.remaining()));
  }

  // The longest prefix of each point wins; two of one length must be the
  // same bytes (they are the same merge), else the point is recomputed.
  void add(const merged_prefix& p, std::string_view payload, journaled_prefix&& where) {
    if (conflicting_points.count(p.point)) return;
    auto it = out.prefixes.find(p.point);
    if (it != out.prefixes.end() && it->second.blocks > p.blocks) return;
    if (it != out.prefixes.end() && it->second.blocks == p.blocks) {
      // read back only here: two prefixes of one length are rare (a point
      // that did not advance between two runs' checkpoints)
      if (holds(it->second.place, payload)) return;
      conflicting_points.insert(p.point);
      out.prefixes.erase(it);
      return note(fmt::format("point {}: two journaled merges of its first {} blocks differ; "
                              "they will be recomputed",
                              p.point, p.blocks));
    }
    out.prefixes.insert_or_assign(p.point, std::move(where));
  }

  void add(const work_unit& u, std::string_view payload, journaled_unit&& where) {
    if (conflicting.count(u)) return;
    const auto it = out.units.find(u);
    if (it == out.units.end()) {
      out.units.emplace(u, std::move(where));
    } else if (!holds(it->second.place, payload)) {  // cannot happen unless something is very wrong
      conflicting.insert(u);
      out.units.erase(u);
      note(fmt::format("point {} block {} is journaled twice with different contents; "
                       "it will be recomputed",
                       u.point, u.block));
    }
  }
};

}  // namespace

std::string journal_readback::bytes(const journal_place& at) {
  const auto fail = [&](const std::string& why) {
    return error(exit_code::io_failure,
                 fmt::format("{}: the journal changed since it was read ({}): a journaled "
                             "record could not be read back; run the command again",
                             at.segment ? *at.segment : std::string("(no segment)"), why));
  };
  if (!at.segment) throw fail("no segment");
  constexpr std::size_t kept = 8;  // open segments (journal.hpp)
  auto it = std::find_if(open_.begin(), open_.end(), [&](const open_segment& o) {
    return o.path == at.segment || *o.path == *at.segment;
  });
  if (it == open_.end()) {
    if (open_.size() == kept) open_.erase(open_.begin());
    open_.push_back({at.segment, std::ifstream(*at.segment, std::ios::binary)});
  } else if (it + 1 != open_.end()) {
    std::rotate(it, it + 1, open_.end());
  }
  std::ifstream& in = open_.back().in;
  if (!in.is_open()) {
    open_.pop_back();
    throw fail("cannot open");
  }
  std::string data(at.length, '\0');
  in.clear();
  in.seekg(static_cast<std::streamoff>(at.offset));
  if (!in.read(data.data(), static_cast<std::streamsize>(at.length))) throw fail("truncated");
  if (crc32(data) != at.crc) throw fail("CRC mismatch");
  return data;
}

std::string journaled_prefix::bytes() const { return journal_readback{}.bytes(place); }

merged_prefix journaled_prefix::decode(journal_readback& from) const {
  return deserialize_merged_prefix(from.bytes(place));
}

merged_prefix journaled_prefix::decode() const {
  journal_readback from;
  return decode(from);
}

std::string journaled_unit::bytes() const { return journal_readback{}.bytes(place); }

block_result journaled_unit::decode(journal_readback& from) const {
  return deserialize_unit_result(from.bytes(place)).second;
}

block_result journaled_unit::decode() const {
  journal_readback from;
  return decode(from);
}

journal_contents read_journal(const std::string& dir, const sweep_spec* expected,
                              const journal_report& report) {
  journal_contents out;
  const std::string jdir = journal_path(dir);
  std::error_code ec;
  if (!fs::is_directory(jdir, ec)) return out;

  std::string problem;
  const std::string header_path = (fs::path(jdir) / detail::header_file).string();
  if (auto h = detail::read_header_file(header_path, &problem)) {
    if (expected && !same_results(h->spec, *expected))
      throw error(exit_code::resume_mismatch,
                  fmt::format("the journal in '{}' was made with a different configuration "
                              "({}; journal vs now). Use the original configuration, or "
                              "another output directory",
                              dir, first_difference(h->spec, *expected)));
    out.spec = std::move(h->spec);
    out.metadata = std::move(h->metadata);
  } else {
    ++out.damaged;
    if (report)
      report(fmt::format("{}: {}; {}", header_path, problem,
                         expected ? "records are checked against the current configuration"
                                  : "this journal cannot be used"));
    if (!expected) return out;
  }
  const sweep_spec& spec = out.spec ? *out.spec : *expected;

  std::vector<std::string> segments;
  for (fs::directory_iterator it(jdir, ec), end; !ec && it != end; it.increment(ec)) {
    const auto name = it->path().filename().string();
    if (name.starts_with("seg-") && name.ends_with(".bin")) segments.push_back(it->path().string());
  }
  if (ec) throw io_error(jdir, "cannot list the journal: " + ec.message());
  std::sort(segments.begin(), segments.end());

  segment_reader reader{spec, fingerprint(spec), report, out, {}, {}, {}, {}};
  for (const auto& path : segments) reader.read(path);
  // Units that a point's prefix covers are not needed.
  std::erase_if(out.units, [&](const auto& kv) {
    const auto it = out.prefixes.find(kv.first.point);
    return it != out.prefixes.end() && kv.first.block < it->second.blocks;
  });
  for (const auto& [run, seconds] : reader.run_elapsed) out.elapsed_seconds += seconds;
  return out;
}

}  // namespace stickslip::io
