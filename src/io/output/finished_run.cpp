// Reads back what a finished sweep's results.nc says about the run that
// wrote it (its global attributes), so that `--resume` can tell this
// configuration's finished results from another's.
#include <netcdf>

#include <filesystem>
#include <system_error>

#include "../netcdf_file.hpp"
#include "stickslip/io/output_files.hpp"
#include "stickslip/io/writers.hpp"

namespace stickslip::io {
namespace fs = std::filesystem;

namespace {

// The file that speaks for a finished run in DIR: results.nc, or a study's
// sensitivity.nc.
std::string finished_result_path(const std::string& dir) {
  auto path = (fs::path(dir) / results_file).string();
  std::error_code ec;
  if (!fs::is_regular_file(path, ec) && fs::is_regular_file(fs::path(dir) / sensitivity_file, ec))
    path = (fs::path(dir) / sensitivity_file).string();
  return path;
}

}  // namespace

std::optional<run_metadata> read_finished_metadata(const std::string& dir, std::string* problem) {
  const auto path = finished_result_path(dir);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    if (problem) *problem = "'" + path + "' is missing";
    return std::nullopt;
  }
  try {
    detail::nc_file f(path, netCDF::NcFile::read);
    run_metadata m;
    auto text = [&](const char* name, std::string& into) {
      const auto att = f.getAtt(name);
      if (att.isNull()) return false;
      att.getValues(into);
      return true;
    };
    if (!text("resolved_config", m.resolved_config)) {
      if (problem) *problem = "'" + path + "' has no resolved_config attribute";
      return std::nullopt;
    }
    text("command_line", m.command_line);
    text("version", m.version);
    text("git_revision", m.git_revision);
    text("created_utc", m.created_utc);
    return m;
  } catch (const netCDF::exceptions::NcException& e) {
    if (problem) *problem = "'" + path + "' cannot be read (" + detail::netcdf_message(e) + ")";
    return std::nullopt;
  } catch (const std::exception& e) {
    if (problem) *problem = "'" + path + "' cannot be read (" + e.what() + ")";
    return std::nullopt;
  }
}

std::string read_finished_warning(const std::string& dir) {
  try {
    detail::nc_file f(finished_result_path(dir), netCDF::NcFile::read);
    const auto att = f.getAtt("warning");
    std::string text;
    if (!att.isNull()) att.getValues(text);
    return text;
  } catch (const std::exception&) {
    return {};
  }
}

}  // namespace stickslip::io
