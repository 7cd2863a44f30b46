#include "stickslip/run/journaled_run.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/io/writers.hpp"
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

}  // namespace

run_outcome run_journaled(const sweep_spec& spec, const run_plan& plan,
                          const io::run_metadata& fresh, runner& r) {
  const auto t0 = std::chrono::steady_clock::now();
  if (plan.slice && !spec.target_statistic.empty())
    throw invalid_value("--shard", plan.slice->tag(),
                        "no shards with a precision target (--target-ci): the stop rule "
                        "needs every block of a point in one run");
  run_outcome out;
  io::journal_contents loaded = load_journal(spec, plan);
  out.metadata = loaded.metadata ? *loaded.metadata : fresh;

  ordered_merger merger(spec);
  if (plan.slice) merger.discard_results();  // a shard only journals (merge combines them)
  const std::uint64_t nb = blocks_per_point(spec);
  std::vector<char> done(unit_count(spec), 0);
  for (auto& [u, res] : loaded.units) {
    done[u.point * nb + u.block] = 1;
    merger.add(u, std::move(res));
    ++out.resumed_units;
  }
  loaded.units.clear();

  io::journal_writer journal(plan.dir, spec, out.metadata, plan.slice ? plan.slice->tag() : "run",
                             plan.checkpoint_interval);
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
    journal.add(u, res);
    if (work) work->add(u);
  };
  hooks.wanted = [&](const work_unit& u) {
    return !(plan.stop && plan.stop->requested()) && to_run(u);
  };
  r.run(spec, merger, hooks);
  journal.flush();
  out.computed_units = journal.units_written();
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

void write_outputs(const run_outcome& out, const std::string& dir, bool keep_journal) {
  try {
    io::write_all(*out.results, out.metadata, dir);
  } catch (const error& e) {
    if (e.code() != exit_code::io_failure) throw;
    throw error(e.code(), std::string(e.what()) +
                              "; the finished units stay in the journal: rerun with --resume "
                              "to write the outputs");
  }
  if (!keep_journal) io::remove_journal(dir);
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
  const auto before = directory_state::of(plan.dir);
  try {
    auto out = run_journaled(spec, plan, fresh, r);
    if (out.results) write_outputs(out, plan.dir, keep_journal);
    return out;
  } catch (const error& e) {
    clean_up_after_failure(e, plan.dir, before);
    throw;
  }
}

}  // namespace stickslip::run
