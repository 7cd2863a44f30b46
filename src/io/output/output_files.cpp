#include "stickslip/io/output_files.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <system_error>

#include "stickslip/io/atomic_file.hpp"
#include "stickslip/error.hpp"
#include "stickslip/io/writers.hpp"

namespace stickslip::io {

namespace fs = std::filesystem;

std::vector<std::string> existing_sweep_results(const std::string& dir) {
  std::vector<std::string> found;
  for (const char* name : {results_file, summary_json_file, summary_csv_file, records_csv_file,
                           sensitivity_file}) {
    const auto path = (fs::path(dir) / name).string();
    std::error_code ec;
    if (fs::exists(fs::symlink_status(path, ec))) found.push_back(path);
  }
  return found;
}

void refuse_to_replace(const std::vector<std::string>& paths, const std::string& what,
                       const std::string& how_to_proceed) {
  std::vector<std::string> found;
  for (const auto& p : paths) {
    std::error_code ec;
    if (fs::exists(fs::symlink_status(p, ec))) found.push_back(fmt::format("'{}'", p));
  }
  if (found.empty()) return;
  // Every one of them: what an overwrite would replace or remove (a review
  // found a study's sensitivity.nc removed by a sweep's --overwrite that the
  // refusal had named only summary.json of).
  const std::string others =
      found.size() == 1
          ? ""
          : fmt::format(", and so do {}",
                        fmt::join(std::vector<std::string>(found.begin() + 1, found.end()), ", "));
  throw error(exit_code::invalid_input,
              fmt::format("{} already exists ({}){}: {}", found.front(), what, others,
                          how_to_proceed));
}

std::string removed_outputs_note(const std::vector<std::string>& removed) {
  std::vector<std::string> gone;
  for (const auto& p : removed) {
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(p, ec))) gone.push_back(fmt::format("'{}'", p));
  }
  if (gone.empty()) return {};
  return fmt::format("removed {}: {} an earlier run's, which this run does not write",
                     fmt::join(gone, ", "), gone.size() == 1 ? "it was" : "they were");
}

namespace {

void check_targets(const std::vector<text_output>& files) {
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::error_code ec;
    if (fs::is_directory(files[i].path, ec))
      throw invalid_value(files[i].flag, files[i].path, "a file name, not a directory");
    for (std::size_t j = 0; j < i; ++j) {
      if (fs::path(files[i].path).lexically_normal() == fs::path(files[j].path).lexically_normal())
        throw invalid_value(files[i].flag, files[i].path,
                            "a file other than the one " + files[j].flag + " names");
    }
  }
}

}  // namespace

void write_text_files(const std::vector<text_output>& files, bool replace_existing,
                      const std::string& how_to_proceed) {
  check_targets(files);
  if (!replace_existing) {
    std::vector<std::string> paths;
    for (const auto& f : files) paths.push_back(f.path);
    refuse_to_replace(paths, "an output of an earlier run", how_to_proceed);
  }
  std::vector<detail::created_directory> created;
  std::size_t written = 0, renamed = 0;
  try {
    for (const auto& f : files) {
      const auto dir = fs::path(f.path).parent_path();
      if (!dir.empty()) {
        auto made = detail::create_directories(dir.string());
        created.insert(created.end(), made.begin(), made.end());
      }
    }
    for (; written < files.size(); ++written) {
      const std::string text = files[written].text();
      detail::write_text_temporary(files[written].path,
                                   [&](detail::text_sink& out) { out.write(text); });
    }
    for (; renamed < files.size(); ++renamed)
      detail::commit_rename(detail::temporary_path(files[renamed].path), files[renamed].path);
  } catch (...) {
    for (std::size_t i = 0; i < renamed; ++i) detail::remove_file_quietly(files[i].path);
    for (std::size_t i = renamed; i < written; ++i)
      detail::remove_file_quietly(detail::temporary_path(files[i].path));
    detail::remove_created(created);
    throw;
  }
}

}  // namespace stickslip::io
