// Run under mpirun -np P: the distributed sweep must give exactly the
// single-process result (compared through the exact serialization, so every
// bit of every accumulator, histogram and convergence point counts), also
// when some units come from elsewhere (resume), and an error on any rank must
// end every rank with that error on rank 0. Exit 0 on success.
#include <fmt/format.h>

#include <cstdlib>
#include <string>
#include <vector>

#include "stickslip/error.hpp"
#include "stickslip/mpi/distributed_sweep.hpp"
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

  fmt::print("mpi_equivalence: {} ranks x {} threads: {} units bit-identical; resume, stop and "
             "error paths OK\n",
             ses.size(), threads, unit_count(spec));
  return 0;
}
