// A sweep's outputs written as its run goes (run_plan::stream): a large
// grid's finished windows, each a slab of whole rows of its first axis,
// go to results.nc (hyperslabs: NetCDF writes by row range), summary.json
// and summary.csv as they are merged, so that the run holds one window of
// points, not the grid. The same files as write_all of the whole result set
// (the same values and text; results.nc's chunks end at the slabs'
// bounds), all or nothing: written under temporary names and renamed only by
// commit; a stream destroyed before (a failure, a stop) removes them.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "stickslip/io/metadata.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::io {

// Whether the writers can stream `spec`'s outputs: no derived estimates
// (their columns and variables exist only where some point has them), no
// precision target (its warning and the trace length depend on every
// point), no raw records (records.csv), no sensitivity design.
[[nodiscard]] bool streams_outputs(const sweep_spec& spec);

class streamed_outputs {
 public:
  // `header`: the run's spec (the whole grid), threads and ranks.
  streamed_outputs(result_set header, std::string dir, output_options options);
  streamed_outputs(const streamed_outputs&) = delete;
  streamed_outputs& operator=(const streamed_outputs&) = delete;
  ~streamed_outputs();
  // The next slab in grid order (checked: else an internal error): its spec
  // the whole grid's, its points whole rows of the first axis with their
  // indices on the whole grid. `meta` is the run's (a resumed run's first
  // run's), as write_all's: summary.json's is the first slab's.
  void slab(const result_set& slab, const run_metadata& meta);
  // Once every slab is written: the run's elapsed time, then every file
  // finished and renamed into place, and an earlier run's outputs that
  // these do not replace removed (write_all). Returns those.
  std::vector<std::string> commit(double elapsed_seconds, const run_metadata& meta);
  // Points written so far.
  [[nodiscard]] std::size_t points() const noexcept { return points_; }

 private:
  struct files;
  [[nodiscard]] std::vector<std::string> paths() const;  // the three outputs
  result_set header_;
  std::string dir_;
  output_options options_;
  std::unique_ptr<files> files_;
  std::size_t points_ = 0;
};

}  // namespace stickslip::io
