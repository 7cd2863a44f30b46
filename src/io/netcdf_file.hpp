// netCDF-C++'s file and exceptions as the io library reports them. Private to
// the io library.
#pragma once
#include <ncCheck.h>
#include <netcdf>

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

}  // namespace stickslip::io::detail
