// The run layer's one way to run a sweep that must survive: every finished
// unit goes to the checkpoint journal DIR/.journal (io/journal.hpp); a resume
// reloads it and runs only what is missing; a shard runs one slice and only
// journals it; a stop request (signal, KeyboardInterrupt) ends the run with
// every finished unit journaled. `sweep`, `merge`, `reproduce` and the Python
// package all go through here; the command line only parses and prints.
//
//   run_journaled   journal + resume + shard + stop around a runner
//   write_outputs   io::write_all with the first run's metadata, then the
//                   journal is removed (unless kept)
//   sweep_into      both, holding DIR's writer lock (io/output_lock.hpp)
//                   throughout, and on a deterministic failure (bad input,
//                   work bound) removes what this run created
#pragma once
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "stickslip/io/journal.hpp"
#include "stickslip/io/metadata.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/run/result_memory.hpp"
#include "stickslip/run/runner.hpp"
#include "stickslip/run/shard.hpp"
#include "stickslip/run/stop.hpp"
#include "stickslip/sweep.hpp"

namespace stickslip::run {

struct run_plan {
  std::string dir;                  // the output directory; the journal is DIR/.journal
  std::optional<shard> slice;       // --shard i/n: run and journal only this slice
  bool resume = false;              // continue the journal in DIR (refused without it)
  // The caller writes the outputs right after the run (sweep_into): the
  // run's last checkpoint is then written only when one is due. Otherwise
  // (reproduce's sweeps, Python) it is always written: the journal is the
  // finished run's only copy until its outputs are written later.
  bool outputs_follow = false;
  // --overwrite: finished outputs in DIR may be replaced. Without it, a
  // resume into a DIR without a journal but with finished outputs does
  // nothing when they are this spec's and is refused when they are not
  // (finished_outputs_of).
  bool overwrite = false;
  // Who writes DIR, for the message that refuses a second writer
  // (io/output_lock.hpp): "stickslip sweep", "stickslip.sweep (Python)".
  std::string writer = "stickslip";
  // Without resume or overwrite, finished results in DIR are refused under
  // the lock (io::refuse_to_replace) with this advice, when it is set.
  std::string replace_advice;
  io::output_options outputs;  // what the outputs hold beyond the defaults
  std::chrono::duration<double> checkpoint_interval{2.0};  // between journal segments
  // A run or a shard on a runner that takes any spec (runner::runs_any_spec)
  // merges a grid of more points than this window by window: whole slabs of
  // its first axis, at least one, about this many points at a time. Only a
  // window's accumulators are held in full (26 KB a point with the default
  // bins); the finished points of such a run keep only what the outputs
  // read (release_unselected: no unselected histograms), and a shard keeps
  // none. 0: the whole grid at once. The outputs are the same bits either
  // way. (merge_shards takes the same window.)
  std::size_t window_points = default_window_points;
  const stop_token* stop = nullptr;  // no unit starts once a stop is requested
  // Units merged so far (resumed ones included) of the total, and the
  // fraction of this run's expected work done (work_meter: for an honest
  // ETA); serialized.
  std::function<void(std::uint64_t done, std::uint64_t total, double work_done)> progress;
  // Problems found in the journal and notes on the resume, one line each.
  io::journal_report report;
  // A run that goes window by window hands each finished window to this,
  // in grid order, instead of keeping its points: a slab of the grid (its
  // spec the whole grid's, its points indexed on it, unselected
  // histograms released), with the run's metadata (sweep_into streams it to
  // the outputs, io/streamed_outputs.hpp). The result set then holds no
  // points. Unset, or for a run of one window, every point is kept.
  std::function<void(const result_set& slab, const io::run_metadata& meta)> stream;
};

struct run_outcome {
  std::optional<result_set> results;  // absent for a shard
  io::run_metadata metadata;          // the first run's (from the journal when resumed)
  std::uint64_t resumed_units = 0, computed_units = 0;
  double elapsed_this_run = 0;        // seconds
  // --resume found this spec's finished outputs in DIR and no journal:
  // nothing ran, nothing was written; `metadata` is the finished outputs'.
  bool already_complete = false;
  // The outputs of an earlier run in DIR that this one did not write and
  // removed (--overwrite: records.csv without --records, a study's files
  // under a sweep's), for the front end to name.
  std::vector<std::string> removed_outputs;
};

// A resume into `dir` that holds no journal: the finished outputs there, if
// any, must be exactly this configuration's. "Exactly" is established like a
// journal's: the resolved configuration in results.nc's global attributes
// (resolved_config, the TOML of the spec that made them) is parsed and
// compared with `spec` by same_results (every results-relevant field, to the
// bit; the engine does not count), and the set must be whole (results.nc,
// summary.json, summary.csv, and records.csv when spec.keep_records).
// Returns nullopt when `dir` holds no outputs (start from the beginning), the
// outputs' metadata when they are this spec's (nothing to do), and throws
// invalid_input (exit 2) naming `dir` and what to do when they are another
// configuration's or cannot be identified.
[[nodiscard]] std::optional<io::run_metadata> finished_outputs_of(const sweep_spec& spec,
                                                                  const std::string& dir);

// How many points run_journaled holds with every accumulator at a time, for
// `spec` and `plan` on `r`: the plan's window when the grid runs window by
// window (more points than the window, a runner that takes any spec, no
// sensitivity design, no survival grid still to be resolved; a run or a
// shard), widened when the run streams its windows (plan.stream:
// streamed_window_points), else 0 (the whole grid). The front ends pass it
// to check_result_memory before they touch the output directory, as
// run_journaled does; `sweep` passes sweep_memory_window, what the run of
// sweep_into will hold.
[[nodiscard]] std::size_t memory_window(const sweep_spec& spec, const run_plan& plan,
                                        const runner& r);
[[nodiscard]] std::size_t sweep_memory_window(const sweep_spec& spec, const run_plan& plan,
                                              const runner& r);

// Whether sweep_into streams `spec`'s outputs window by window on `r`
// (io::streamed_outputs): a whole run (not a shard) that goes window by
// window (memory_window) of a spec the writers can stream
// (io::streams_outputs). Its finished points are then not kept: `sweep`
// passes keeps_results = !plan.slice && !streams_outputs(...) to
// check_result_memory.
[[nodiscard]] bool streams_outputs(const sweep_spec& spec, const run_plan& plan, const runner& r);

// Journal, resume, shard and stop around `r`. `fresh` is the metadata a new
// journal records. Throws: invalid_input when DIR holds an unfinished journal
// and plan.resume is false; resume_mismatch when the journal was made with
// another spec; error(128 + signal) when stopped (every finished unit is
// journaled; the message says how to continue).
[[nodiscard]] run_outcome run_journaled(const sweep_spec& spec, const run_plan& plan,
                                        const io::run_metadata& fresh, runner& r);

// io::write_all(results, metadata, dir), then removes the journal unless
// keep_journal. An io_failure says that the units of the journal's last
// checkpoint, if any, stay in it (a sweep_into run skips its last
// checkpoint when none is due: run_plan::outputs_follow).
// Returns what write_all removed of an earlier run's outputs.
std::vector<std::string> write_outputs(const run_outcome& out, const std::string& dir,
                                       bool keep_journal, const io::output_options& options = {});

// What DIR held before a run, so that a failed run can remove what it created.
struct directory_state {
  bool existed = false, journal_existed = false;
  [[nodiscard]] static directory_state of(const std::string& dir);
};
// A deterministic failure (work bound, invalid input) cannot be fixed by a
// resume: remove what this run created (DIR if it is new, else its journal if
// that is new). Other failures (I/O, signals) keep the journal for a resume.
void clean_up_after_failure(const error& e, const std::string& dir, const directory_state& before);

// run_journaled, then (unless a shard) write_outputs into plan.dir; the
// result set records the runner's ranks and threads. A large grid's outputs
// are streamed window by window as the run goes (streams_outputs): the
// result set then holds no points. A resume into a DIR
// without a journal first checks its finished outputs (finished_outputs_of,
// unless plan.overwrite): this spec's give already_complete and nothing runs. Cleans up after a
// deterministic failure and rethrows.
[[nodiscard]] run_outcome sweep_into(const sweep_spec& spec, const run_plan& plan,
                                     const io::run_metadata& fresh, runner& r,
                                     bool keep_journal = false);

}  // namespace stickslip::run
