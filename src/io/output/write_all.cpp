// write_all: every output of a sweep into one directory, all or nothing.
// Phase 1 writes each file to `<name>.tmp` (flushed, fsynced). Only when all
// of them succeeded does phase 2 rename them into place. A failure in phase 1
// removes the temporaries; a failure in phase 2 (rare: a rename within one
// directory) also removes the files this call already renamed. A directory
// this call created is removed again on failure, so nothing is left behind.
#include <algorithm>
#include <filesystem>
#include <functional>
#include <system_error>

#include "stickslip/error.hpp"
#include "stickslip/io/output_files.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"
#include "writers_detail.hpp"

namespace stickslip::io {
namespace fs = std::filesystem;

std::vector<std::string> write_all(const result_set& rs, const run_metadata& meta, const std::string& dir,
               const output_options& options) {
  detail::check_shape(rs);
  const auto created = detail::create_directories(dir);
  const auto in_dir = [&](const char* name) { return (fs::path(dir) / name).string(); };

  struct output {
    std::string path;
    std::function<void(const std::string&)> write_temporary;
  };
  std::vector<output> outputs;
  if (is_sensitivity(rs.spec)) {
    outputs = {
        {in_dir(sensitivity_file),
         [&](const std::string& p) { detail::write_sensitivity_temporary(rs, meta, p); }},
        {in_dir(summary_json_file),
         [&](const std::string& p) {
           detail::write_text_temporary(
               p, [&](detail::text_sink& out) { detail::fill_sensitivity_json(out, rs, &meta); });
         }},
    };
  } else {
    outputs = {
      {in_dir(results_file),
       [&](const std::string& p) { detail::write_netcdf_temporary(rs, meta, p); }},
      {in_dir(summary_json_file),
       [&](const std::string& p) {
         detail::write_text_temporary(
             p, [&](detail::text_sink& out) { detail::fill_summary_json(out, rs, meta, options); });
       }},
      {in_dir(summary_csv_file),
       [&](const std::string& p) {
         detail::write_text_temporary(
             p, [&](detail::text_sink& out) { detail::fill_summary_csv(out, rs); });
       }},
    };
  }
  if (rs.spec.keep_records)
    outputs.push_back({in_dir(records_csv_file), [&](const std::string& p) {
                         detail::write_text_temporary(p, [&](detail::text_sink& out) {
                           detail::fill_records_csv(out, rs);
                         });
                       }});

  std::size_t written = 0;
  try {
    for (; written < outputs.size(); ++written) outputs[written].write_temporary(outputs[written].path);
  } catch (...) {
    // The output that failed has already removed its own temporary.
    for (std::size_t i = 0; i < written; ++i)
      detail::remove_file_quietly(detail::temporary_path(outputs[i].path));
    detail::remove_created(created);
    throw;
  }
  std::vector<std::string> paths;
  for (const auto& o : outputs) paths.push_back(o.path);
  return detail::commit_outputs(dir, paths, created);
}

namespace detail {

std::vector<std::string> commit_outputs(const std::string& dir, const std::vector<std::string>& paths,
                                        const std::vector<created_directory>& created) {
  const auto in_dir = [&](const char* name) { return (fs::path(dir) / name).string(); };
  // A study's figure is ours only beside its sensitivity.nc (a file of the
  // same name in a directory without one is left alone): one of an earlier
  // run, before this one's is renamed into place.
  std::error_code exists_ec;
  const bool earlier_study = fs::exists(in_dir(sensitivity_file), exists_ec);
  std::size_t renamed = 0;
  try {
    for (; renamed < paths.size(); ++renamed) commit_rename(temporary_path(paths[renamed]), paths[renamed]);
  } catch (...) {
    for (std::size_t i = 0; i < renamed; ++i) remove_file_quietly(paths[i]);
    for (std::size_t i = renamed; i < paths.size(); ++i) remove_file_quietly(temporary_path(paths[i]));
    remove_created(created);
    throw;
  }
  // What an earlier run left in the same directory and this one did not
  // write would describe other results beside these (records.csv without
  // --records; a sweep's files under a sensitivity study's, or the other
  // way round; a study's figure, which `sensitivity` draws after this, or
  // not with --no-figure): once this set is in place, it goes (a new
  // user's --overwrite left them).
  std::vector<std::string> earlier = existing_sweep_results(dir);
  if (earlier_study)
    for (const char* ext : figure_extensions)
      earlier.push_back(in_dir(sensitivity_figure_stem) + ext);
  std::vector<std::string> removed;
  for (const auto& path : earlier)
    if (std::find(paths.begin(), paths.end(), path) == paths.end()) {
      std::error_code ec;  // a file that cannot be removed stays, and is not named as removed
      if (fs::is_regular_file(path, ec) && fs::remove(path, ec)) removed.push_back(path);
    }
  return removed;
}

}  // namespace detail

}  // namespace stickslip::io
