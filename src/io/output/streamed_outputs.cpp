// A sweep's outputs written slab by slab (streamed_outputs.hpp).
#include "stickslip/io/streamed_outputs.hpp"

#include <filesystem>

#include "stickslip/error.hpp"
#include "stickslip/statistics_groups.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"
#include "writers_detail.hpp"

namespace stickslip::io {
namespace fs = std::filesystem;

bool streams_outputs(const sweep_spec& spec) {
  return !selects_estimates(spec.statistics) && spec.target_statistic.empty() &&
         !spec.keep_records && !is_sensitivity(spec);
}

struct streamed_outputs::files {
  std::vector<detail::created_directory> created;
  detail::netcdf_stream netcdf;
  detail::text_temporary json, csv;
  detail::summary_json_stream json_points;
  detail::summary_csv_rows csv_rows;
  files(const std::string& dir, std::vector<detail::created_directory> made,
        const result_set& header, const run_metadata& meta, const output_options& options)
      : created(std::move(made)),
        netcdf((fs::path(dir) / results_file).string()),
        json((fs::path(dir) / summary_json_file).string()),
        csv((fs::path(dir) / summary_csv_file).string()),
        json_points(json.sink(), header, meta, options),
        csv_rows(csv.sink(), header, {}) {}
};

streamed_outputs::streamed_outputs(result_set header, std::string dir, output_options options)
    : header_(std::move(header)), dir_(std::move(dir)), options_(options) {
  if (!streams_outputs(header_.spec))
    throw error(exit_code::internal, "streamed outputs of a sweep the writers cannot stream");
  header_.points.clear();
}

streamed_outputs::~streamed_outputs() {
  if (!files_) return;
  auto created = std::move(files_->created);
  files_.reset();  // removes the temporaries not yet finished
  // and those finished by a commit that failed after them
  for (const auto& path : paths()) detail::remove_file_quietly(detail::temporary_path(path));
  detail::remove_created(created);
}

std::vector<std::string> streamed_outputs::paths() const {
  return {(fs::path(dir_) / results_file).string(), (fs::path(dir_) / summary_json_file).string(),
          (fs::path(dir_) / summary_csv_file).string()};
}

void streamed_outputs::slab(const result_set& slab, const run_metadata& meta) {
  detail::check_slab(slab, points_);  // the next rows of the grid, in order
  if (!files_)
    files_ = std::make_unique<files>(dir_, detail::create_directories(dir_), header_, meta, options_);
  files_->netcdf.slab(header_, slab);
  files_->json_points.slab(slab);
  files_->csv_rows.print(slab);
  points_ += slab.points.size();
}

std::vector<std::string> streamed_outputs::commit(double elapsed_seconds, const run_metadata& meta) {
  if (!files_ || points_ != point_count(header_.spec))
    throw error(exit_code::internal,
                fmt::format("streamed outputs committed with {} of {} points", points_,
                            point_count(header_.spec)));
  header_.elapsed_seconds = elapsed_seconds;
  auto& f = *files_;
  f.netcdf.finish(header_, meta);
  f.json_points.end(header_);
  f.json.finish();
  f.csv.finish();
  auto removed = detail::commit_outputs(dir_, paths(), f.created);
  files_.reset();
  return removed;
}

}  // namespace stickslip::io
