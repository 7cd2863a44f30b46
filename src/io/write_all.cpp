// write_all: every output of a sweep into one directory, all or nothing.
// Phase 1 writes each file to `<name>.tmp` (flushed, fsynced). Only when all
// of them succeeded does phase 2 rename them into place. A failure in phase 1
// removes the temporaries; a failure in phase 2 (rare: a rename within one
// directory) also removes the files this call already renamed. A directory
// this call created is removed again on failure, so nothing is left behind.
#include <filesystem>
#include <functional>
#include <system_error>

#include "stickslip/error.hpp"
#include "stickslip/io/writers.hpp"
#include "writers_detail.hpp"

namespace stickslip::io {
namespace {

namespace fs = std::filesystem;

// Creates `dir` and any missing parents; returns the directories it created,
// deepest first (so they can be removed again in that order).
std::vector<fs::path> create_directory(const fs::path& dir) {
  std::vector<fs::path> missing;
  std::error_code ec;
  for (fs::path p = dir; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    missing.push_back(p);
    if (p == p.parent_path()) break;
  }
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw io_error(dir.string(), "exists and is not a directory");
  fs::create_directories(dir, ec);
  if (ec) throw io_error(dir.string(), "cannot create the output directory: " + ec.message());
  return missing;
}

void remove_created(const std::vector<fs::path>& created) noexcept {
  std::error_code ec;
  for (const auto& d : created) fs::remove(d, ec);  // only removes empty directories
}

}  // namespace

void write_all(const result_set& rs, const run_metadata& meta, const std::string& dir) {
  detail::check_shape(rs);
  const auto created = create_directory(dir);
  const auto in_dir = [&](const char* name) { return (fs::path(dir) / name).string(); };

  struct output {
    std::string path;
    std::function<void(const std::string&)> write_temporary;
  };
  std::vector<output> outputs{
      {in_dir(results_file),
       [&](const std::string& p) { detail::write_netcdf_temporary(rs, meta, p); }},
      {in_dir(summary_json_file),
       [&](const std::string& p) {
         detail::write_text_temporary(
             p, [&](detail::text_sink& out) { detail::fill_summary_json(out, rs, meta); });
       }},
      {in_dir(summary_csv_file),
       [&](const std::string& p) {
         detail::write_text_temporary(
             p, [&](detail::text_sink& out) { detail::fill_summary_csv(out, rs); });
       }},
  };
  if (rs.spec.keep_records)
    outputs.push_back({in_dir(records_csv_file), [&](const std::string& p) {
                         detail::write_text_temporary(p, [&](detail::text_sink& out) {
                           detail::fill_records_csv(out, rs);
                         });
                       }});

  std::size_t written = 0, renamed = 0;
  try {
    for (; written < outputs.size(); ++written) outputs[written].write_temporary(outputs[written].path);
    for (; renamed < outputs.size(); ++renamed)
      detail::commit_rename(detail::temporary_path(outputs[renamed].path), outputs[renamed].path);
  } catch (...) {
    // The output that failed has already removed its own temporary.
    for (std::size_t i = 0; i < renamed; ++i) detail::remove_file_quietly(outputs[i].path);
    for (std::size_t i = renamed; i < written; ++i)
      detail::remove_file_quietly(detail::temporary_path(outputs[i].path));
    remove_created(created);
    throw;
  }
  // A records.csv left by an earlier run into the same directory would
  // describe other results: once this set is in place, it goes.
  if (!rs.spec.keep_records) detail::remove_file_quietly(in_dir(records_csv_file));
}

}  // namespace stickslip::io
