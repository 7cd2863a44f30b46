// Run under mpirun -np P: the distributed sweep must give exactly the
// single-process result (compared through the exact serialization, so every
// bit of every accumulator, histogram and convergence point counts), also
// when some units come from elsewhere (resume), and an error on any rank must
// end every rank with that error on rank 0; and a journaled run of a grid in
// windows on the MPI runner (one spec per window) must give the bits of one
// window in one process. Exit 0 on success.
#include <fmt/format.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/mpi/distributed_sweep.hpp"
#include "stickslip/mpi/mpi_runner.hpp"
#include "stickslip/run/journaled_run.hpp"
#include "stickslip/run/result_memory.hpp"
#include "stickslip/serialize.hpp"

using namespace stickslip;

namespace {

sweep_spec test_spec() {
  sweep_spec s;
  s.axes = {{"lambda", {0.05, 0.4, 3.0, 12.0}}, {"mu", {0.5, 2.0}}};
  s.base.window = 20.0;
  s.realizations = 60;
  s.block_size = 7;  // a short last block
  s.seed = 42;
  s.histograms.bins = 16;
  return s;
}

std::string encode(const sweep_spec& s, ordered_merger& m) {
  std::string out;
  for (std::size_t i = 0; i < point_count(s); ++i)
    out += serialize(work_unit{i, 0}, block_result{m.points()[i], {}});
  return out;
}

int fail(const std::string& what) {
  fmt::print(stderr, "mpi_equivalence: FAILED: {}\n", what);
  return 1;
}

// The MPI runner, counting the specs it is handed (one per window).
class counting_runner final : public run::runner {
 public:
  explicit counting_runner(run::runner& inner) : inner_(inner) {}
  void run(const sweep_spec& s, ordered_merger& m, const sweep_hooks& h) override {
    ++runs;
    inner_.run(s, m, h);
  }
  [[nodiscard]] int ranks() const noexcept override { return inner_.ranks(); }
  [[nodiscard]] unsigned threads() const noexcept override { return inner_.threads(); }
  [[nodiscard]] bool runs_any_spec() const noexcept override { return inner_.runs_any_spec(); }
  int runs = 0;

 private:
  run::runner& inner_;
};

// Every point's statistics as the outputs read them (release_unselected),
// serialized, with its grid index.
std::string encode(const result_set& rs) {
  std::string out;
  for (const auto& p : rs.points) {
    auto st = p.stats;
    run::release_unselected(st, rs.spec);
    out += serialize(work_unit{}, block_result{st, {}});
    for (auto i : p.index) out += std::to_string(i) + ",";
  }
  return out;
}

// 5. A whole journaled run of a grid larger than its window (run_journaled,
// window_points = 3: one lambda slab of 2 points at a time, 4 windows) on
// the MPI runner: one spec per window goes to the serving ranks, and the
// results are those of one window on one process.
int windowed_run(const mpi::session& ses, unsigned threads, const sweep_spec& spec) {
  const auto dir = [](const char* name) {
    return (std::filesystem::temp_directory_path() /
            fmt::format("stickslip-mpi-windows-{}-{}", name, ::getpid()))
        .string();
  };
  const io::run_metadata meta{"cmd", "cfg", "v", "g", "t"};
  run::run_plan one;
  one.dir = dir("one");
  one.window_points = 0;
  run::run_plan windows = one;
  windows.dir = dir("windows");
  windows.window_points = 3;
  struct removed {  // before and after, also when run_journaled throws
    std::string a, b;
    void now() const {
      std::error_code ec;
      std::filesystem::remove_all(a, ec);
      std::filesystem::remove_all(b, ec);
    }
    ~removed() { now(); }
  } cleanup{one.dir, windows.dir};
  cleanup.now();
  run::thread_runner local(1);
  const auto want = run::run_journaled(spec, one, meta, local);
  mpi::runner distributed(ses, threads);
  if (!distributed.runs_any_spec()) return fail("case 5: the MPI runner takes one spec only");
  counting_runner counted(distributed);
  const auto got = run::run_journaled(spec, windows, meta, counted);
  if (counted.runs != 4) return fail(fmt::format("case 5: {} windows, expected 4", counted.runs));
  if (!want.results || !got.results) return fail("case 5: no results");
  if (encode(*got.results) != encode(*want.results))
    return fail("case 5: the windowed MPI run differs from one window on one process");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const unsigned threads = argc > 1 ? static_cast<unsigned>(std::atoi(argv[1])) : 1;
  mpi::session ses;
  const auto spec = test_spec();

  // 1. everything distributed == everything on one process
  if (!ses.is_root()) {
    mpi::serve(ses, threads);  // case 1
    mpi::serve(ses, threads);  // case 2
    mpi::serve(ses, threads);  // case 3
    mpi::serve(ses, threads);  // case 4, stopped
    mpi::serve(ses, threads);  // case 4, resumed
    while (mpi::serve(ses, threads)) {
    }  // case 5: a spec per window, until rank 0 cancels
    return 0;
  }
  ordered_merger reference(spec);
  run_units(spec, 1, reference);
  const auto want = encode(spec, reference);

  ordered_merger m1(spec);
  std::uint64_t progress_calls = 0, done_calls = 0;
  sweep_hooks h1;
  h1.progress = [&](std::uint64_t, std::uint64_t) { ++progress_calls; };
  h1.unit_done = [&](const work_unit&, const block_result&) { ++done_calls; };
  mpi::coordinate(ses, spec, threads, m1, h1);
  if (!m1.complete()) return fail("case 1: merger incomplete");
  if (encode(spec, m1) != want) return fail("case 1: results differ from the single-process run");
  if (done_calls != unit_count(spec) || progress_calls != unit_count(spec))
    return fail("case 1: hooks not called once per unit");

  // 2. resume: every third unit comes from a journal, the rest distributed
  ordered_merger m2(spec);
  for (std::uint64_t i = 0; i < unit_count(spec); i += 3) {
    const auto u = unit_at(spec, i);
    m2.add(u, simulate_block(spec, u));
  }
  sweep_hooks h2;
  h2.wanted = [&](const work_unit& u) {
    return (u.point * blocks_per_point(spec) + u.block) % 3 != 0;
  };
  mpi::coordinate(ses, spec, threads, m2, h2);
  if (!m2.complete() || encode(spec, m2) != want)
    return fail("case 2: resumed results differ from the single-process run");

  // 3. an error on some rank (work bound hit) ends all ranks; rank 0 reports it
  auto bad = spec;
  bad.max_events = 40;
  ordered_merger m3(bad);
  try {
    mpi::coordinate(ses, bad, threads, m3);
    return fail("case 3: no error although units exceed max_events");
  } catch (const error& e) {
    if (e.code() != exit_code::work_bound) return fail(fmt::format("case 3: wrong error: {}", e.what()));
  }

  // 4. a stop (what a signal does: `wanted` turns false) after 10 merged
  // units: every rank returns, every unit handed out is merged exactly once
  // and reported to unit_done; then the rest, resumed, completes the run.
  // Blocks of one realization: many more units than the ranks hold at once
  // (each asks for batches of 20 per thread).
  auto small = spec;
  small.block_size = 1;
  ordered_merger ref4(small);
  run_units(small, 1, ref4);
  const auto want4 = encode(small, ref4);
  ordered_merger m4(small);
  std::vector<char> done(unit_count(small), 0);
  std::uint64_t done4 = 0;
  bool twice = false;
  sweep_hooks h4;
  h4.unit_done = [&](const work_unit& u, const block_result&) {
    auto& d = done[u.point * blocks_per_point(small) + u.block];
    twice |= d != 0;
    d = 1;
    ++done4;
  };
  h4.wanted = [&](const work_unit& u) {
    return done4 < 10 && !done[u.point * blocks_per_point(small) + u.block];
  };
  mpi::coordinate(ses, small, threads, m4, h4);
  if (twice) return fail("case 4: a unit was merged twice");
  if (m4.merged_units() != done4 || done4 < 10 || m4.complete())
    return fail(fmt::format("case 4: {} units reported, {} merged, complete = {}", done4,
                            m4.merged_units(), m4.complete()));
  h4.wanted = [&](const work_unit& u) { return !done[u.point * blocks_per_point(small) + u.block]; };
  mpi::coordinate(ses, small, threads, m4, h4);
  if (twice || !m4.complete() || encode(small, m4) != want4)
    return fail("case 4: the stopped and resumed run differs from the single-process run");

  int windowed = 0;
  try {
    windowed = windowed_run(ses, threads, spec);
  } catch (const std::exception& e) {
    windowed = fail(fmt::format("case 5: {}", e.what()));
  }
  mpi::cancel(ses);  // the serving ranks return
  if (windowed != 0) return windowed;

  fmt::print("mpi_equivalence: {} ranks x {} threads: {} units bit-identical; resume, stop and "
             "error paths OK; a windowed journaled run (4 windows) bit-identical\n",
             ses.size(), threads, unit_count(spec));
  return 0;
}
