// netCDF-C++'s file and exceptions as the io library reports them. Private to
// the io library.
#pragma once
#include <fmt/format.h>
#include <ncCheck.h>
#include <netcdf>
#include <sys/resource.h>
#include <sys/statvfs.h>

#include <filesystem>
#include <string>

namespace stickslip::io::detail {

// An NcFile that is closed once, and whose destructor closes without
// printing. netCDF-C++'s destructor cannot throw, so it prints a failed
// close to stderr: after a failed write (a full disk, `ulimit -f`) that
// printed "NetCDF: HDF error / file: ncFile.cpp line:33" ahead of the error
// the caller reports. And its close() marks the file closed only when
// nc_close succeeds, so a failed close was tried again by the destructor,
// which netCDF-C does not promise to survive. (nullObject and myId are
// netCDF-C++ 4.3's protected members of NcGroup.)
class nc_file : public netCDF::NcFile {
 public:
  using netCDF::NcFile::NcFile;
  nc_file(const nc_file&) = delete;
  nc_file& operator=(const nc_file&) = delete;
  ~nc_file() {
    if (!nullObject) nc_close(myId);  // after an error: the write's own is reported
    nullObject = true;                // NcFile's destructor then has nothing to close
  }
  // One attempt; throws the NcException of a failed close.
  void close() {
    if (nullObject) return;
    nullObject = true;
    netCDF::ncCheck(nc_close(myId), __FILE__, __LINE__);
  }
};

// The text of a netCDF-C++ exception without the source location netCDF-C++
// appends ("\nfile: ncVar.cpp  line:1049"): netCDF-C's own text, e.g.
// "NetCDF: HDF error", or an errno's ("File too large").
inline std::string netcdf_message(const netCDF::exceptions::NcException& e) {
  std::string s = e.what();
  if (const auto at = s.find("\nfile:"); at != std::string::npos) s.erase(at);
  return s;
}

// What a failed NetCDF write may have met, which netCDF does not say: HDF5
// reports a write past `ulimit -f` or on a full disk as "HDF error", and
// nc_create under `ulimit -f 0` as "Permission denied". " (...)" naming the
// file-size limit when there is one and the free space when it is below
// 16 MiB; "" when neither.
inline std::string write_limit_hint(const std::string& path) {
  std::string hint;
  rlimit limit{};
  if (getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    hint = fmt::format("the file-size limit (ulimit -f) is {} bytes", limit.rlim_cur);
  auto dir = std::filesystem::path(path).parent_path();
  if (dir.empty()) dir = ".";
  struct statvfs disk {};
  if (statvfs(dir.c_str(), &disk) == 0) {
    const auto free = static_cast<unsigned long long>(disk.f_bavail) * disk.f_frsize;
    if (free < (16ull << 20))
      hint += fmt::format("{}the disk holding it has {} bytes free", hint.empty() ? "" : "; ", free);
  }
  return hint.empty() ? "" : " (netCDF does not say why; " + hint + ")";
}

}  // namespace stickslip::io::detail
