#include "stickslip/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <sys/stat.h>

#include "stickslip/error.hpp"

namespace stickslip::io::detail {
namespace {

std::string errno_text(const char* what) {
  return fmt::format("{} failed: {}", what, std::strerror(errno));
}

std::string parent_directory(const std::string& path) {
  auto parent = std::filesystem::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

}  // namespace

std::string temporary_path(const std::string& path) { return path + ".tmp"; }

void remove_file_quietly(const std::string& path) noexcept {
  ::unlink(path.c_str());  // unlink(2) never removes a directory
}

std::vector<created_directory> create_directories(const std::string& dir) {
  namespace fs = std::filesystem;
  std::vector<created_directory> missing;
  std::error_code ec;
  for (fs::path p = dir; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    missing.push_back(p.string());
    if (p == p.parent_path()) break;
  }
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw io_error(dir, "exists and is not a directory");
  fs::create_directories(dir, ec);
  if (ec) throw io_error(dir, "cannot create the directory: " + ec.message());
  return missing;
}

void remove_created(const std::vector<created_directory>& created) noexcept {
  std::error_code ec;
  for (const auto& d : created) std::filesystem::remove(d, ec);  // only removes empty directories
}

void sync_file(const std::string& path, const std::string& report_as) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw io_error(report_as, errno_text("open for fsync"));
  const int rc = ::fsync(fd);
  const int saved = errno;
  ::close(fd);
  errno = saved;
  if (rc != 0) throw io_error(report_as, errno_text("fsync"));
}

void commit_rename(const std::string& from, const std::string& to) {
  if (std::rename(from.c_str(), to.c_str()) != 0)
    throw io_error(to, errno_text(fmt::format("rename from '{}'", from).c_str()));
  // Make the new directory entry durable. Some file systems refuse fsync on
  // directories (EINVAL); the data itself is already synced, so that is fine.
  const int fd = ::open(parent_directory(to).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

void text_sink::flush() {
  if (!file_ || buf_.size() == 0) return;
  if (std::fwrite(buf_.data(), 1, buf_.size(), file_) != buf_.size())
    throw io_error(report_as_, errno_text("write"));
  buf_.clear();
}

text_temporary::text_temporary(std::string path)
    : path_(std::move(path)), tmp_(temporary_path(path_)) {
  file_ = std::fopen(tmp_.c_str(), "wb");
  if (!file_) throw io_error(path_, errno_text(fmt::format("creating '{}'", tmp_).c_str()));
  sink_ = std::make_unique<text_sink>(file_, path_);
}

text_temporary::~text_temporary() {
  if (file_) std::fclose(file_);
  if (!finished_) remove_file_quietly(tmp_);
}

void text_temporary::finish() {
  sink_->flush();
  if (std::fflush(file_) != 0) throw io_error(path_, errno_text("flush"));
  if (::fsync(::fileno(file_)) != 0) throw io_error(path_, errno_text("fsync"));
  std::FILE* f = file_;
  file_ = nullptr;
  if (std::fclose(f) != 0) throw io_error(path_, errno_text("close"));
  finished_ = true;
}

void write_text_temporary(const std::string& path, const std::function<void(text_sink&)>& fill) {
  text_temporary out(path);
  try {
    fill(out.sink());
  } catch (const stickslip::error&) {
    throw;
  } catch (const std::exception& e) {  // e.g. out of memory while formatting
    throw io_error(path, e.what());
  }
  out.finish();
}

void write_text_atomically(const std::string& path, const std::function<void(text_sink&)>& fill) {
  write_text_temporary(path, fill);
  try {
    commit_rename(temporary_path(path), path);
  } catch (...) {
    remove_file_quietly(temporary_path(path));
    throw;
  }
}

}  // namespace stickslip::io::detail
