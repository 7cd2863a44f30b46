// Atomic output files: write `path.tmp`, flush and fsync it, then rename it
// onto `path` (rename(2) within one directory is atomic), so a reader sees
// either the old file or the complete new one, never a partial file.
// Every failure removes the temporary and throws stickslip::io_error naming
// the final path.
#pragma once
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

namespace stickslip::io::detail {

[[nodiscard]] std::string temporary_path(const std::string& path);

// Removes a regular file if it exists (never a directory); ignores errors.
void remove_file_quietly(const std::string& path) noexcept;

// Creates `dir` and any missing parents. Returns the directories it created,
// deepest first, for remove_created. Throws io_error(dir, reason).
using created_directory = std::string;
[[nodiscard]] std::vector<created_directory> create_directories(const std::string& dir);
// Removes directories that create_directories made (only if empty again).
void remove_created(const std::vector<created_directory>& created) noexcept;

// fsync an existing file by name (for files that a library wrote and closed,
// e.g. NetCDF). Throws io_error(report_as, ...).
void sync_file(const std::string& path, const std::string& report_as);

// rename(from, to), then fsync the directory that holds `to` so the rename
// itself is durable. Throws io_error(to, ...).
void commit_rename(const std::string& from, const std::string& to);

// Buffered text output to a FILE* (or, without one, into memory). Flushes
// every 64 KiB so that large outputs (raw records) need no large buffer.
// Errors are reported with the final path, not the temporary name.
class text_sink {
 public:
  text_sink() = default;  // in memory: take the text with str()
  text_sink(std::FILE* f, std::string report_as) : file_(f), report_as_(std::move(report_as)) {}
  text_sink(const text_sink&) = delete;
  text_sink& operator=(const text_sink&) = delete;

  void write(std::string_view s) {
    buf_.append(s.data(), s.data() + s.size());
    maybe_flush();
  }
  void put(char c) {
    buf_.push_back(c);
    maybe_flush();
  }
  template <class... Args>
  void print(fmt::format_string<Args...> f, Args&&... args) {
    fmt::format_to(std::back_inserter(buf_), f, std::forward<Args>(args)...);
    maybe_flush();
  }
  void flush();  // writes what is buffered to the file; no-op in memory
  [[nodiscard]] std::string str() const { return fmt::to_string(buf_); }

 private:
  void maybe_flush() {
    if (file_ && buf_.size() >= (1u << 16)) flush();
  }
  std::FILE* file_ = nullptr;
  std::string report_as_;
  fmt::memory_buffer buf_;
};

// `path.tmp` open for writing over time (an output streamed as a run goes:
// streamed_outputs.hpp): print into sink(), then finish() flushes, fsyncs and
// closes it, without renaming. Destroyed unfinished (a failure, a stop), it
// removes the temporary. Errors throw io_error(path, ...).
class text_temporary {
 public:
  explicit text_temporary(std::string path);
  text_temporary(const text_temporary&) = delete;
  text_temporary& operator=(const text_temporary&) = delete;
  ~text_temporary();
  [[nodiscard]] text_sink& sink() { return *sink_; }
  void finish();

 private:
  std::string path_, tmp_;
  std::FILE* file_ = nullptr;
  std::unique_ptr<text_sink> sink_;
  bool finished_ = false;
};

// Writes `path.tmp` through `fill` (which prints into the sink), flushes,
// fsyncs and closes it. Does not rename: the caller commits with
// commit_rename (write_all renames only after every file succeeded).
// On failure removes the temporary and throws io_error(path, ...).
void write_text_temporary(const std::string& path, const std::function<void(text_sink&)>& fill);

// write_text_temporary + commit_rename.
void write_text_atomically(const std::string& path, const std::function<void(text_sink&)>& fill);

}  // namespace stickslip::io::detail
