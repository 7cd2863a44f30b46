#include "stickslip/run/journaled_run.hpp"
#include "stickslip/uncertainty/sensitivity_design.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <set>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/io/config.hpp"
#include "stickslip/io/output_files.hpp"
#include "stickslip/io/output_lock.hpp"
#include "stickslip/io/streamed_outputs.hpp"
#include "stickslip/io/writers.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/run/result_memory.hpp"
#include "stickslip/run/stop.hpp"
#include "stickslip/run/work_meter.hpp"
#include "grid_windows.hpp"

namespace stickslip::run {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

io::journal_contents load_journal(const sweep_spec& spec, const run_plan& plan) {
  io::journal_contents loaded;
  if (io::journal_exists(plan.dir)) {
    if (!plan.resume)
      throw invalid_value("-o (output directory)", plan.dir,
                          "a directory without the journal of an unfinished run (found " +
                              io::journal_path(plan.dir) +
                              "): add --resume to continue that run, or remove the journal");
    loaded = io::read_journal(plan.dir, &spec, plan.report);
    if (loaded.damaged && plan.report)
      plan.report(fmt::format("{} damaged file(s) or record(s) skipped; their units are "
                              "recomputed", loaded.damaged));
  } else if (plan.resume && plan.report) {
    plan.report(fmt::format("no journal in {}: starting from the beginning", plan.dir));
  }
  return loaded;
}

// One checkpoint of a whole run: the merged prefix of every point that
// advanced since the last one, the blocks waiting for an earlier block (each
// once), and the unit just finished (not merged yet), then a segment.
// Called from the runner's serialized unit_done hook, where the merger is
// not being changed. The merger holds a window of the grid whose point 0 is
// point `offset` of the journal's spec (grid_window).
class prefix_checkpoint {
 public:
  prefix_checkpoint(const sweep_spec& window, const ordered_merger& merger,
                    io::journal_writer& journal, std::size_t offset)
      : merger_(merger), journal_(journal), offset_(offset), written_(point_count(window)) {
    for (std::size_t p = 0; p < written_.size(); ++p) written_[p] = merger.merged_blocks(p);
  }
  void write(const work_unit* just_done, const block_result* result) {
    for (std::size_t p = 0; p < written_.size(); ++p) {
      const auto blocks = merger_.merged_blocks(p);
      if (blocks == written_[p]) continue;
      journal_.add_prefix(p + offset_, blocks, merger_.merged(p));
      written_[p] = blocks;
    }
    std::erase_if(waiting_written_, [&](const work_unit& u) {
      return u.block < merger_.merged_blocks(u.point);
    });
    for (const auto& [u, r] : merger_.waiting())
      if (waiting_written_.insert(u).second) journal_.add({u.point + offset_, u.block}, r);
    if (just_done) journal_.add({just_done->point + offset_, just_done->block}, *result);
    journal_.flush();
  }

 private:
  const ordered_merger& merger_;
  io::journal_writer& journal_;
  std::size_t offset_;
  std::vector<std::uint64_t> written_;  // blocks in the last prefix written, per point
  std::set<work_unit> waiting_written_;
};

// Whether `spec` runs window by window on `r` (grid_windows.hpp): a runner
// that takes any spec, and a grid that splits_into_windows. A shard too:
// it journals every unit and keeps no results, so a window is all it holds
// (a whole-grid merger of the 100,000-point grid held 590 MB in each of two
// shards).
bool runs_in_windows(const sweep_spec& spec, const run_plan& plan, const runner& r) {
  return r.runs_any_spec() && detail::splits_into_windows(spec, plan.window_points);
}

// `write()` (the outputs, whole or a streamed window), whose I/O failure
// says that the journal keeps the run.
template <class W>
auto with_resume_advice(W&& write) {
  try {
    return write();
  } catch (const error& e) {
    if (e.code() != exit_code::io_failure) throw;
    throw error(e.code(), std::string(e.what()) +
                              "; the units of the journal's last checkpoint, if any, stay in "
                              "it: rerun with --resume to write the outputs (units finished "
                              "after that checkpoint are computed again)");
  }
}

}  // namespace

bool streams_outputs(const sweep_spec& spec, const run_plan& plan, const runner& r) {
  return !plan.slice && runs_in_windows(spec, plan, r) && io::streams_outputs(spec);
}

std::size_t memory_window(const sweep_spec& spec, const run_plan& plan, const runner& r) {
  if (!runs_in_windows(spec, plan, r)) return 0;
  return plan.stream ? streamed_window_points(spec, plan.window_points) : plan.window_points;
}

std::size_t sweep_memory_window(const sweep_spec& spec, const run_plan& plan, const runner& r) {
  return streams_outputs(spec, plan, r) ? streamed_window_points(spec, plan.window_points)
                                        : memory_window(spec, plan, r);
}

namespace {

std::vector<detail::grid_window> grid_windows(const sweep_spec& spec, const run_plan& plan,
                                              const runner& r) {
  if (!runs_in_windows(spec, plan, r)) return {{spec, 0}};
  return detail::windows_of(spec, memory_window(spec, plan, r));
}

}  // namespace

run_outcome run_journaled(const sweep_spec& spec, const run_plan& plan,
                          const io::run_metadata& fresh, runner& r) {
  const auto t0 = std::chrono::steady_clock::now();
  if (plan.slice && !spec.target_statistic.empty())
    throw invalid_value("--shard", fmt::format("{}/{}", plan.slice->index, plan.slice->count),
                        "no shards with a precision target (--target-ci): the stop rule "
                        "needs every block of a point in one run");
  const bool windowed = runs_in_windows(spec, plan, r);
  // For every front end (sweep, reproduce, Python), with what the windows hold.
  const bool streamed = windowed && plan.stream;
  check_result_memory(spec, r.threads(), memory_window(spec, plan, r), !plan.slice && !streamed);
  run_outcome out;
  io::journal_contents loaded = load_journal(spec, plan);
  out.metadata = loaded.metadata ? *loaded.metadata : fresh;

  io::journal_writer journal(plan.dir, spec, out.metadata, plan.slice ? plan.slice->tag() : "run",
                             plan.checkpoint_interval);
  // A whole run journals merged prefixes (io/journal.hpp); a shard, whose
  // blocks of a point are not contiguous, and a sweep that keeps raw
  // records journal every unit.
  const bool journal_prefixes = !plan.slice && !spec.keep_records;
  const std::uint64_t nb = blocks_per_point(spec);
  std::vector<char> done(unit_count(spec), 0);
  for (const auto& [point, prefix] : loaded.prefixes) {
    std::fill_n(done.begin() + static_cast<std::ptrdiff_t>(point * nb), prefix.blocks, 1);
    out.resumed_units += prefix.blocks;
  }
  for (const auto& [u, res] : loaded.units) {
    done[u.point * nb + u.block] = 1;
    ++out.resumed_units;
  }
  if (plan.slice) loaded.prefixes.clear();  // a shard journals its own units only
  auto to_run = [&](const work_unit& u) {
    return !done[u.point * nb + u.block] && (!plan.slice || plan.slice->owns(spec, u));
  };
  std::optional<work_meter> work;
  if (plan.progress) work.emplace(spec, to_run);
  const auto stopped = [&] { return plan.stop && plan.stop->requested(); };
  // What the run does on a stop is decided on one reading per window (the
  // last window's checkpoint, whether to throw, and the count the message
  // gives): a stop that arrives after the last window's reading finds every
  // unit computed and merged, and the outputs are written as after a stop
  // during the writing. (Read twice, a stop between the readings threw "N
  // finished units are journaled" with the last window's checkpoint
  // skipped, so N counted units the journal did not hold.)
  bool stop_seen = false;
  const auto stop_now = [&] { return stop_seen = stop_seen || stopped(); };

  // A large grid runs window by window (grid_windows): only one window's
  // accumulators are held in full; a finished window's points keep what the
  // outputs read (release_unselected) and join `all` in grid order.
  result_set all;
  all.spec = spec;
  if (!plan.slice && !streamed) all.points.reserve(point_count(spec));
  if (!plan.slice && spec.keep_records) all.records.reserve(point_count(spec));
  std::uint64_t merged_before = 0;  // units merged in the earlier windows
  auto windows = grid_windows(spec, plan, r);
  for (std::size_t wi = 0; wi < windows.size(); ++wi) {
    auto& w = windows[wi];
    if (stop_now()) {  // the later windows' journaled units count as finished
      for (const auto& [point, prefix] : loaded.prefixes) merged_before += prefix.blocks;
      merged_before += loaded.units.size();
      break;
    }
    const std::size_t offset = w.offset;
    ordered_merger merger(w.spec);
    if (plan.slice) merger.discard_results();  // a shard only journals (merge combines them)
    detail::restore_window(w, loaded.prefixes, loaded.units, merger);
    const auto whole = [offset](const work_unit& u) { return work_unit{u.point + offset, u.block}; };
    prefix_checkpoint checkpoint(w.spec, merger, journal, offset);
    sweep_hooks hooks;
    if (plan.progress)
      hooks.progress = [&](std::uint64_t d, std::uint64_t) {
        plan.progress(merged_before + d, unit_count(spec), work->fraction());
      };
    hooks.unit_done = [&](const work_unit& u, const block_result& res) {
      ++out.computed_units;
      if (work) work->add(whole(u));
      if (!journal_prefixes)
        journal.add(whole(u), res);
      else if (journal.due())
        checkpoint.write(&u, &res);  // u is merged right after this hook
    };
    hooks.wanted = [&](const work_unit& u) { return !stopped() && to_run(whole(u)); };
    r.run(w.spec, merger, hooks);
    // The window's last checkpoint: always when stopped (the finished units
    // are what an interrupted run keeps), after every window but the last
    // (a later window's checkpoints do not hold this one's points, so its
    // units since the last segment would stay unjournaled however long the
    // run went on), and when the caller writes no outputs at once
    // (!outputs_follow: the journal is the finished run's only copy); else,
    // after the last window of sweep_into, only when one is due, as during
    // the run. Writing every point's merged statistics once more just
    // before the outputs hold them cost a 101-observe-time paper grid a
    // third of a second on one core (18.7 MB serialized, checksummed and
    // fsynced); a failure from here to the outputs loses at most the units
    // finished since the last segment, as a kill at any other moment does.
    const bool last_window = wi + 1 == windows.size();
    const bool stop = stop_now();
    if (journal_prefixes && (stop || !last_window || !plan.outputs_follow || journal.due()))
      checkpoint.write(nullptr, nullptr);
    merged_before += merger.merged_units();
    if (stop || plan.slice) continue;
    if (!merger.complete())
      throw error(exit_code::internal, "the run ended with units missing from the merge");
    if (streamed)
      with_resume_advice([&] {
        plan.stream(detail::slab_of(spec, make_result_set(w.spec, std::move(merger)), offset),
                    out.metadata);
      });
    else
      detail::append_window(all, make_result_set(w.spec, std::move(merger)), offset, windowed);
  }
  journal.flush();
  out.elapsed_this_run = seconds_since(t0);
  if (stop_seen) {
    const int sig = plan.stop->reason();
    throw error(interrupted_by(sig),
                fmt::format("interrupted by {}: {} finished units are journaled in {}; "
                            "continue with the same command and --resume",
                            signal_text(sig), merged_before, io::journal_path(plan.dir)));
  }
  if (plan.slice) return out;
  out.results = std::move(all);
  out.results->elapsed_seconds = loaded.elapsed_seconds + out.elapsed_this_run;
  out.results->threads = r.threads();
  out.results->ranks = static_cast<unsigned>(r.ranks());
  return out;
}

namespace {

// The outputs written by `write` (all or nothing), then the journal removed
// unless kept; an io_failure says that the journal keeps the run.
template <class W>
std::vector<std::string> outputs_then_journal(const std::string& dir, bool keep_journal, W&& write) {
  std::vector<std::string> removed = with_resume_advice(write);
  if (!keep_journal) io::remove_journal(dir);
  return removed;
}

// A streamed run's outputs, finished with its elapsed time.
std::vector<std::string> commit_streamed(io::streamed_outputs& streamed, const run_outcome& out,
                                         const std::string& dir, bool keep_journal) {
  return outputs_then_journal(dir, keep_journal, [&] {
    return streamed.commit(out.results->elapsed_seconds, out.metadata);
  });
}

}  // namespace

std::vector<std::string> write_outputs(const run_outcome& out, const std::string& dir,
                                       bool keep_journal, const io::output_options& options) {
  return outputs_then_journal(dir, keep_journal, [&] {
    return io::write_all(*out.results, out.metadata, dir, options);
  });
}

std::optional<io::run_metadata> finished_outputs_of(const sweep_spec& spec,
                                                    const std::string& dir) {
  const auto found = io::existing_sweep_results(dir);
  if (found.empty()) return std::nullopt;
  const std::string nothing_to_resume =
      "; there is no journal, so --resume has nothing to continue: choose another -o DIR for "
      "this configuration, or add --overwrite to replace those results";
  std::string problem;
  const auto meta = io::read_finished_metadata(dir, &problem);
  if (!meta)
    throw error(exit_code::invalid_input,
                fmt::format("-o '{}' holds the outputs of a finished run ('{}' found) whose "
                            "configuration cannot be read ({}){}",
                            dir, found.front(), problem, nothing_to_resume));
  std::string difference;
  try {
    sweep_spec theirs = io::parse_sweep_toml(
        meta->resolved_config,
        (std::filesystem::path(dir) /
         (is_sensitivity(spec) ? io::sensitivity_file : io::results_file)).string());
    // A configuration file holds the selection of statistics, not the engine
    // settings the front ends derive from it (apply_statistics_selection).
    if (theirs.statistics == spec.statistics) {
      theirs.family_statistics = spec.family_statistics;
      theirs.means_only = spec.means_only;
    }
    if (!same_results(theirs, spec)) difference = first_difference(theirs, spec);
  } catch (const error& e) {
    difference = fmt::format("its resolved_config does not parse here: {}", e.what());
  }
  if (!difference.empty())
    throw error(exit_code::invalid_input,
                fmt::format("-o '{}' holds the finished run of another configuration ({}; "
                            "those results vs this command){}",
                            dir, difference, nothing_to_resume));
  std::vector<std::string> wanted{io::results_file, io::summary_json_file, io::summary_csv_file};
  if (is_sensitivity(spec)) wanted = {io::sensitivity_file, io::summary_json_file};
  if (spec.keep_records) wanted.push_back(io::records_csv_file);
  for (const auto& name : wanted) {
    const auto path = (std::filesystem::path(dir) / name).string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
      throw error(exit_code::invalid_input,
                  fmt::format("-o '{}' holds an incomplete set of finished outputs of this "
                              "configuration ('{}' is missing){}",
                              dir, path, nothing_to_resume));
  }
  return meta;
}

directory_state directory_state::of(const std::string& dir) {
  return {std::filesystem::exists(dir), io::journal_exists(dir)};
}

void clean_up_after_failure(const error& e, const std::string& dir, const directory_state& before) {
  if (e.code() != exit_code::work_bound && e.code() != exit_code::invalid_input) return;
  std::error_code ec;
  if (!before.existed)
    std::filesystem::remove_all(dir, ec);
  else if (!before.journal_existed)
    io::remove_journal(dir);
}

run_outcome sweep_into(const sweep_spec& spec, const run_plan& plan, const io::run_metadata& fresh,
                       runner& r, bool keep_journal) {
  // What DIR held before this run (for the clean-up of a failure), then one
  // writer at a time from here until the outputs are written. A refusal
  // throws before the try below: it cleans up nothing of the other writer's.
  auto before = directory_state::of(plan.dir);
  const io::output_lock lock(plan.dir, plan.writer, plan.slice ? plan.slice->tag() : "");
  // Under the lock: no writer that finished in between can have left a
  // journal this run would take for its own.
  before.journal_existed = io::journal_exists(plan.dir);
  if (!plan.resume && !plan.overwrite && !plan.replace_advice.empty())
    io::refuse_to_replace(io::existing_sweep_results(plan.dir), "the results of an earlier run",
                          plan.replace_advice);
  if (plan.resume && !plan.overwrite && !io::journal_exists(plan.dir)) {
    if (auto finished = finished_outputs_of(spec, plan.dir)) {
      run_outcome out;
      out.metadata = std::move(*finished);
      out.already_complete = true;
      return out;
    }
  }
  try {
    run_plan then_outputs = plan;
    then_outputs.outputs_follow = true;
    std::optional<io::streamed_outputs> streamed;
    if (streams_outputs(spec, plan, r)) {
      result_set header;
      header.spec = spec;
      header.threads = r.threads();
      header.ranks = static_cast<unsigned>(r.ranks());
      streamed.emplace(std::move(header), plan.dir, plan.outputs);
      then_outputs.stream = [&](const result_set& slab, const io::run_metadata& meta) {
        streamed->slab(slab, meta);
      };
    }
    auto out = run_journaled(spec, then_outputs, fresh, r);
    if (streamed && out.results)
      out.removed_outputs = commit_streamed(*streamed, out, plan.dir, keep_journal);
    else if (out.results)
      out.removed_outputs = write_outputs(out, plan.dir, keep_journal, plan.outputs);
    return out;
  } catch (const error& e) {
    // The shards of one directory share it and its journal: a failed shard
    // removes nothing (the others' work is in the same files).
    if (!plan.slice) clean_up_after_failure(e, plan.dir, before);
    throw;
  }
}

}  // namespace stickslip::run
