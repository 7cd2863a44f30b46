// Checkpoint journal: writing. Layout and guarantees: include/stickslip/io/journal.hpp.
#include "stickslip/io/journal.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fmt/format.h>

#include <algorithm>
#include <atomic>

#include "stickslip/io/atomic_file.hpp"
#include "journal_detail.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/serialize.hpp"

namespace stickslip::io {
namespace fs = std::filesystem;

std::string journal_path(const std::string& dir) {
  return (fs::path(dir) / journal_directory).string();
}

bool journal_exists(const std::string& dir) {
  std::error_code ec;
  return fs::is_directory(journal_path(dir), ec);
}

void remove_journal(const std::string& dir) {
  std::error_code ec;
  fs::remove_all(journal_path(dir), ec);
  if (ec) throw io_error(journal_path(dir), "could not remove the journal: " + ec.message());
}

namespace detail {

// magic, format version, payload size, CRC-32 of the payload, payload.
bytes framed(std::string_view magic, const bytes& payload) {
  byte_writer w;
  w.raw(magic);
  w.u32(serial_format_version);
  w.u64(payload.size());
  w.u32(crc32(payload));
  w.raw(payload);
  return w.take();
}

bytes encode_header(const sweep_spec& spec, const run_metadata& meta) {
  byte_writer body;
  body.str(serialize(spec));
  for (const auto* f : {&meta.command_line, &meta.resolved_config, &meta.version,
                        &meta.git_revision, &meta.created_utc})
    body.str(*f);
  return framed(header_magic, body.take());
}

bytes encode_segment_header(std::uint64_t fingerprint, double elapsed, const std::string& run_id,
                            std::uint64_t records) {
  byte_writer body;
  body.u64(fingerprint);
  body.f64(elapsed);
  body.str(run_id);
  body.u64(records);
  return framed(segment_magic, body.take());
}

void write_file_durably(const std::string& tmp, const std::string& final_path,
                        std::initializer_list<std::string_view> pieces) {
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) throw io_error(final_path, fmt::format("cannot create '{}': {}", tmp, std::strerror(errno)));
  auto fail = [&](const char* what) {
    const int saved = errno;
    ::close(fd);
    ::unlink(tmp.c_str());
    return io_error(final_path, fmt::format("{} failed: {}", what, std::strerror(saved)));
  };
  for (const std::string_view data : pieces) {
    std::size_t done = 0;
    while (done < data.size()) {
      const auto n = ::write(fd, data.data() + done, data.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        if (n == 0) errno = ENOSPC;
        throw fail("write");
      }
      done += static_cast<std::size_t>(n);
    }
  }
  if (::fsync(fd) != 0) throw fail("fsync");
  if (::close(fd) != 0) {
    const int saved = errno;
    ::unlink(tmp.c_str());
    throw io_error(final_path, fmt::format("close failed: {}", std::strerror(saved)));
  }
  try {
    io::detail::commit_rename(tmp, final_path);
  } catch (...) {
    ::unlink(tmp.c_str());
    throw;
  }
}

std::string unique_suffix() {
  static std::atomic<unsigned> counter{0};  // several sweeps may run at once (Python threads)
  return fmt::format("{}-{}", static_cast<long>(::getpid()), counter++);
}

}  // namespace detail

namespace {

// Run ids sort by start time, so segments are read back in the order written.
// Unique per writer: the process id alone is not enough, since one process
// (a Python session) may journal the same directory twice within a second
// (interrupted, then resumed), and the second writer's segments must not
// replace the first one's.
std::string make_run_id(const std::string& tag) {
  static std::atomic<unsigned> writers{0};
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  ::gmtime_r(&now, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%S", &utc);
  std::string clean;
  for (char c : tag) clean.push_back(std::isalnum(static_cast<unsigned char>(c)) ? c : '-');
  return fmt::format("{}-{}-{}-{}", clean.empty() ? "run" : clean, stamp,
                     static_cast<long>(::getpid()), writers++);
}

}  // namespace

journal_writer::journal_writer(const std::string& dir, const sweep_spec& spec,
                               const run_metadata& meta, const std::string& run_tag,
                               std::chrono::duration<double> flush_interval)
    : journal_dir_(journal_path(dir)),
      fingerprint_(fingerprint(spec)),
      run_id_(make_run_id(run_tag)),
      interval_(flush_interval),
      started_(std::chrono::steady_clock::now()),
      last_flush_(started_) {
  std::error_code ec;
  fs::create_directories(journal_dir_, ec);
  if (ec) throw io_error(journal_dir_, "cannot create the journal directory: " + ec.message());

  const std::string header = (fs::path(journal_dir_) / detail::header_file).string();
  if (auto existing = detail::read_header_file(header)) {
    if (!same_results(existing->spec, spec))
      throw error(exit_code::resume_mismatch,
                  fmt::format("{} was written for another configuration ({})", header,
                              first_difference(existing->spec, spec)));
    return;  // keep the first run's header and metadata
  }
  const std::string suffix = detail::unique_suffix();
  const std::string cfg = (fs::path(journal_dir_) / detail::config_file).string();
  detail::write_file_durably(cfg + ".tmp-" + suffix, cfg, to_toml(spec));
  detail::write_file_durably(header + ".tmp-" + suffix, header, detail::encode_header(spec, meta));
}

journal_writer::~journal_writer() {
  try {
    flush();
  } catch (...) {  // reported by the flush that failed first; nothing more to do here
  }
}

namespace {
// [length u32][crc32 u32][record]
void append_record(std::string& buffer, const bytes& rec) {
  detail::byte_writer w;
  w.u32(static_cast<std::uint32_t>(rec.size()));
  w.u32(crc32(rec));
  buffer += w.take();
  buffer += rec;
}
}  // namespace

void journal_writer::add(const work_unit& u, const block_result& r) {
  // (Not timed: a run that journals every unit serializes it whether or not
  // a segment follows, so only the write is a checkpoint's own cost.)
  append_record(buffer_, serialize(u, r));
  buffered_covers_.emplace_back(u.point, u.block + 1);
  ++buffered_;
  ++buffered_units_;
  if (due()) flush();
}

void journal_writer::add_prefix(std::size_t point, std::uint64_t blocks,
                                const point_statistics& merged) {
  // Serialized from the merger's own statistics: no copy of them is kept.
  const auto t0 = std::chrono::steady_clock::now();
  append_record(buffer_, serialize_merged_prefix(point, blocks, merged));
  serializing_ += std::chrono::steady_clock::now() - t0;
  buffered_covers_.emplace_back(point, blocks);
  buffered_prefixes_.emplace_back(point, blocks);
  ++buffered_;
}

bool journal_writer::due() const noexcept {
  const auto since = std::chrono::steady_clock::now() - last_flush_;
  if (interval_.count() <= 0.0) return true;
  // 20 times the last checkpoint's own cost, but never more than 15
  // intervals (30 s by default) between segments.
  const auto wait = std::min(std::chrono::duration<double>(20 * last_cost_), 15 * interval_);
  return since >= interval_ && since >= wait;
}

// A segment can go when a later segment of this writer holds, for every
// point it covers, a prefix at least as long. The newest segment always
// stays (it holds the run's latest elapsed time). Removing is not made
// durable: a segment that reappears after a crash is superseded again.
void journal_writer::remove_superseded() {
  auto superseded = [&](const own_segment& seg) {
    for (const auto& [point, end] : seg.covers) {
      const auto it = longest_.find(point);
      if (it == longest_.end() || it->second.first < end || it->second.second == seg.seq)
        return false;
    }
    return true;
  };
  std::vector<own_segment> kept;
  for (std::size_t i = 0; i < own_.size(); ++i) {
    if (i + 1 < own_.size() && superseded(own_[i]))
      ::unlink(own_[i].path.c_str());
    else
      kept.push_back(std::move(own_[i]));
  }
  own_ = std::move(kept);
}

void journal_writer::flush() {
  if (buffered_ == 0) return;
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - started_).count();
  const std::string name = fmt::format("seg-{}-{:06}.bin", run_id_, segment_seq_);
  const std::string path = (fs::path(journal_dir_) / name).string();
  const bytes header = detail::encode_segment_header(fingerprint_, elapsed, run_id_, buffered_);
  try {
    detail::write_file_durably((fs::path(journal_dir_) / (".tmp-" + name)).string(), path,
                               {header, buffer_});
  } catch (const error& e) {
    if (e.code() != exit_code::io_failure) throw;
    // What the user can do: the segments written before this one stay.
    throw error(e.code(), std::string(e.what()) +
                              "; the journal keeps the units of its earlier segments, if any: "
                              "make room and rerun with --resume (the others are computed again)");
  }
  written_ += buffered_units_;
  own_.push_back({path, segment_seq_, std::move(buffered_covers_)});
  for (const auto& [point, blocks] : buffered_prefixes_) {
    auto& longest = longest_[point];
    if (blocks >= longest.first) longest = {blocks, segment_seq_};
  }
  buffer_.clear();
  buffered_covers_.clear();
  buffered_prefixes_.clear();
  buffered_ = buffered_units_ = 0;
  ++segment_seq_;
  remove_superseded();
  last_flush_ = std::chrono::steady_clock::now();
  last_cost_ = serializing_ + (last_flush_ - now);
  serializing_ = {};
}

}  // namespace stickslip::io
