// netCDF-C++'s file and exceptions as the io library reports them. Private to
// the io library.
#pragma once
#include <netcdf>

#include <string>

namespace stickslip::io::detail {

// An NcFile whose destructor closes without printing. netCDF-C++'s own
// destructor cannot throw, so it prints a failed close to stderr: after a
// failed write (a full disk, `ulimit -f`) that printed "NetCDF: HDF error /
// file: ncFile.cpp line:33" ahead of the error the caller reports. A close
// that fails here has nothing more to say: the write's own error is reported.
class nc_file : public netCDF::NcFile {
 public:
  using netCDF::NcFile::NcFile;
  nc_file(const nc_file&) = delete;
  nc_file& operator=(const nc_file&) = delete;
  ~nc_file() {
    if (!nullObject) nc_close(myId);
    nullObject = true;  // NcFile's destructor then has nothing to close
  }
};

// The text of a netCDF-C++ exception without the source location netCDF-C++
// appends ("\nfile: ncVar.cpp  line:1049"); it already starts with "NetCDF: ".
inline std::string netcdf_message(const netCDF::exceptions::NcException& e) {
  std::string s = e.what();
  if (const auto at = s.find("\nfile:"); at != std::string::npos) s.erase(at);
  return s;
}

}  // namespace stickslip::io::detail
