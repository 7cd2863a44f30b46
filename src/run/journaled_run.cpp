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
#include "stickslip/io/writers.hpp"
#include "stickslip/serialize.hpp"
#include "stickslip/run/result_memory.hpp"
#include "stickslip/run/work_meter.hpp"

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
// not being changed.
class prefix_checkpoint {
 public:
  prefix_checkpoint(const sweep_spec& spec, const ordered_merger& merger, io::journal_writer& journal)
      : merger_(merger), journal_(journal), written_(point_count(spec)) {
    for (std::size_t p = 0; p < written_.size(); ++p) written_[p] = merger.merged_blocks(p);
  }
  void write(const work_unit* just_done, const block_result* result) {
    for (std::size_t p = 0; p < written_.size(); ++p) {
      const auto blocks = merger_.merged_blocks(p);
      if (blocks == written_[p]) continue;
      journal_.add_prefix(p, blocks, merger_.merged(p));
      written_[p] = blocks;
    }
    std::erase_if(waiting_written_, [&](const work_unit& u) {
      return u.block < merger_.merged_blocks(u.point);
    });
    for (const auto& [u, r] : merger_.waiting())
      if (waiting_written_.insert(u).second) journal_.add(u, r);
    if (just_done) journal_.add(*just_done, *result);
    journal_.flush();
  }

 private:
  const ordered_merger& merger_;
  io::journal_writer& journal_;
  std::vector<std::uint64_t> written_;  // blocks in the last prefix written, per point
  std::set<work_unit> waiting_written_;
};

}  // namespace

run_outcome run_journaled(const sweep_spec& spec, const run_plan& plan,
                          const io::run_metadata& fresh, runner& r) {
  const auto t0 = std::chrono::steady_clock::now();
  if (plan.slice && !spec.target_statistic.empty())
    throw invalid_value("--shard", fmt::format("{}/{}", plan.slice->index, plan.slice->count),
                        "no shards with a precision target (--target-ci): the stop rule "
                        "needs every block of a point in one run");
  check_result_memory(spec, r.threads());  // every front end: sweep, reproduce, Python
  run_outcome out;
  io::journal_contents loaded = load_journal(spec, plan);
  out.metadata = loaded.metadata ? *loaded.metadata : fresh;

  ordered_merger merger(spec);
  if (plan.slice) merger.discard_results();  // a shard only journals (merge combines them)
  const std::uint64_t nb = blocks_per_point(spec);
  std::vector<char> done(unit_count(spec), 0);
  for (auto& [point, prefix] : loaded.prefixes) {
    std::fill_n(done.begin() + static_cast<std::ptrdiff_t>(point * nb), prefix.blocks, 1);
    out.resumed_units += prefix.blocks;
    if (!plan.slice) merger.restore(std::move(prefix));
  }
  loaded.prefixes.clear();
  for (auto& [u, res] : loaded.units) {
    done[u.point * nb + u.block] = 1;
    merger.add(u, std::move(res));
    ++out.resumed_units;
  }
  loaded.units.clear();

  io::journal_writer journal(plan.dir, spec, out.metadata, plan.slice ? plan.slice->tag() : "run",
                             plan.checkpoint_interval);
  // A whole run journals merged prefixes (io/journal.hpp); a shard, whose
  // blocks of a point are not contiguous, and a sweep that keeps raw
  // records journal every unit.
  const bool journal_prefixes = !plan.slice && !spec.keep_records;
  prefix_checkpoint checkpoint(spec, merger, journal);
  auto to_run = [&](const work_unit& u) {
    return !done[u.point * nb + u.block] && (!plan.slice || plan.slice->owns(spec, u));
  };
  std::optional<work_meter> work;
  sweep_hooks hooks;
  if (plan.progress) {
    work.emplace(spec, to_run);
    hooks.progress = [&](std::uint64_t d, std::uint64_t total) {
      plan.progress(d, total, work->fraction());
    };
  }
  hooks.unit_done = [&](const work_unit& u, const block_result& res) {
    ++out.computed_units;
    if (work) work->add(u);
    if (!journal_prefixes)
      journal.add(u, res);
    else if (journal.due())
      checkpoint.write(&u, &res);  // u is merged right after this hook
  };
  hooks.wanted = [&](const work_unit& u) {
    return !(plan.stop && plan.stop->requested()) && to_run(u);
  };
  r.run(spec, merger, hooks);
  if (journal_prefixes) checkpoint.write(nullptr, nullptr);
  journal.flush();
  out.elapsed_this_run = seconds_since(t0);
  if (plan.stop && plan.stop->requested()) {
    const int sig = plan.stop->reason();
    throw error(static_cast<exit_code>(128 + sig),
                fmt::format("interrupted by signal {}: {} finished units are journaled in {}; "
                            "continue with the same command and --resume",
                            sig, merger.merged_units(), io::journal_path(plan.dir)));
  }
  if (plan.slice) return out;
  if (!merger.complete())
    throw error(exit_code::internal, "the run ended with units missing from the merge");
  out.results = make_result_set(spec, std::move(merger));
  out.results->elapsed_seconds = loaded.elapsed_seconds + out.elapsed_this_run;
  out.results->threads = r.threads();
  out.results->ranks = static_cast<unsigned>(r.ranks());
  return out;
}

void write_outputs(const run_outcome& out, const std::string& dir, bool keep_journal,
                   const io::output_options& options) {
  try {
    io::write_all(*out.results, out.metadata, dir, options);
  } catch (const error& e) {
    if (e.code() != exit_code::io_failure) throw;
    throw error(e.code(), std::string(e.what()) +
                              "; the finished units stay in the journal: rerun with --resume "
                              "to write the outputs");
  }
  if (!keep_journal) io::remove_journal(dir);
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
    auto out = run_journaled(spec, plan, fresh, r);
    if (out.results) write_outputs(out, plan.dir, keep_journal, plan.outputs);
    return out;
  } catch (const error& e) {
    // The shards of one directory share it and its journal: a failed shard
    // removes nothing (the others' work is in the same files).
    if (!plan.slice) clean_up_after_failure(e, plan.dir, before);
    throw;
  }
}

}  // namespace stickslip::run
