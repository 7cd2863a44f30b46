// The paper's full study: 40 lambda log-spaced in [0.1, 30] x 8 mu
// in [0.5, 7] x 2000 realizations, t_a = 50, every statistic and histogram of
// the sweep, timed as run_sweep runs it; beside it the floor (floor.hpp), the
// time to draw all of the study's belt switch times alone, in the same run.
// Prints one key=value line per measurement (scripts/bench-study.sh takes
// medians). Release builds only.
//
//   stickslip_bench_study [--k 4] [--threads 2] [--realizations 2000]
//                         [--engine fast|reference] [--no-floor] [--family-statistics]
//   --family-statistics: also the model family's statistics (off in the study)
//   fast = the lane engine (the default), reference = simulate one
//   realization at a time (same results). The SIMD target is the one chosen
//   at run time (printed).
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "floor.hpp"
#include "stickslip/fast_math.hpp"
#include "stickslip/sweep.hpp"

namespace {

stickslip::sweep_spec paper_study(double stiffness, std::uint64_t realizations) {
  stickslip::sweep_spec s;
  s.base.stiffness = stiffness;
  s.base.window = 50.0;
  s.realizations = realizations;
  std::vector<double> lambda, mu;
  for (int i = 0; i < 40; ++i) lambda.push_back(0.1 * std::pow(300.0, i / 39.0));
  for (int i = 0; i < 8; ++i) mu.push_back(0.5 + 6.5 * i / 7.0);
  s.axes = {{"lambda", lambda}, {"mu", mu}};
  s.family_statistics = false;  // as the study runs it (--family-statistics: on)
  return s;
}

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace

int main(int argc, char** argv) {
#ifndef NDEBUG
  std::fprintf(stderr, "%s: built with assertions on; benchmarks need a Release build\n", argv[0]);
  return 1;
#endif
  double k = 4.0;
  unsigned threads = 2;
  std::uint64_t realizations = 2000;
  bool floor = true;
  bool family = false;
  std::uint64_t block_size = 0;  // 0: the sweep's default (50)
  auto engine = stickslip::sweep_engine::fast;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has = i + 1 < argc;
    if (a == "--k" && has) k = std::atof(argv[++i]);
    else if (a == "--threads" && has) threads = static_cast<unsigned>(std::atoi(argv[++i]));
    else if (a == "--realizations" && has) realizations = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--engine" && has) {
      const std::string e = argv[++i];
      if (e == "reference") engine = stickslip::sweep_engine::reference;
      else if (e == "fast" || e == "lanes") engine = stickslip::sweep_engine::fast;
      else {
        std::fprintf(stderr, "%s: --engine %s: expected fast or reference\n", argv[0], e.c_str());
        return 2;
      }
    }
    else if (a == "--no-floor") floor = false;
    else if (a == "--family-statistics") family = true;
    else if (a == "--block-size" && has) block_size = std::strtoull(argv[++i], nullptr, 10);
    else {
      std::fprintf(stderr, "usage: %s [--k K] [--threads N] [--realizations R] "
                   "[--engine fast|reference] [--block-size B] [--no-floor] "
                   "[--family-statistics]\n", argv[0]);
      return 2;
    }
  }
  auto s = paper_study(k, realizations);
  if (block_size > 0) s.block_size = block_size;
  s.engine = engine;
  s.family_statistics = family;

  const double c0 = cpu_seconds();
  const auto rs = stickslip::run_sweep(s, threads);
  const double cpu = cpu_seconds() - c0;
  stickslip::event_counts ev;
  for (const auto& p : rs.points) ev += p.stats.events;
  const double wall = rs.elapsed_seconds;
  const double n_real = static_cast<double>(s.realizations) * static_cast<double>(rs.points.size());
  std::printf("k=%g threads=%u engine=%s family_statistics=%d simd_target=%s\n", k, threads,
              stickslip::to_string(engine), family ? 1 : 0, stickslip::detail::fm::target_name());
  std::printf("study_seconds=%.4f\nstudy_cpu_seconds=%.4f\n", wall, cpu);
  std::printf("realizations=%.0f\nrealizations_per_s=%.4g\n", n_real, n_real / wall);
  std::printf("events=%llu\nevents_per_s=%.4g\n", static_cast<unsigned long long>(ev.total()),
              static_cast<double>(ev.total()) / wall);
  std::printf("belt_switches=%llu\nstick_onsets=%llu\nstick_breaks=%llu\nslip_reversals=%llu\n",
              static_cast<unsigned long long>(ev.belt_switches),
              static_cast<unsigned long long>(ev.stick_onsets),
              static_cast<unsigned long long>(ev.stick_breaks),
              static_cast<unsigned long long>(ev.slip_reversals));
  std::printf("cpu_ns_per_event=%.2f\n", cpu / static_cast<double>(ev.total()) * 1e9);
  if (floor) {
    const double fc0 = cpu_seconds();
    const auto f = stickslip::bench::draw_all_switch_times(s, threads);
    const double fcpu = cpu_seconds() - fc0;
    std::printf("floor_cpu_seconds=%.4f\n", fcpu);
    // On a loaded machine wall times stretch with the load; CPU times do not.
    std::printf("cpu_ratio_study_over_floor=%.3f\n", cpu / fcpu);
    std::printf("floor_seconds=%.4f\nfloor_switch_times=%llu\nfloor_checksum=%.6g\n", f.seconds,
                static_cast<unsigned long long>(f.switch_times), f.checksum);
    std::printf("ratio_study_over_floor=%.3f\n", wall / f.seconds);
    if (f.switch_times != ev.belt_switches)
      std::printf("warning: floor drew %llu switch times, the study had %llu belt switches\n",
                  static_cast<unsigned long long>(f.switch_times),
                  static_cast<unsigned long long>(ev.belt_switches));
  }
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  std::printf("peak_rss_mb=%.1f\n", static_cast<double>(u.ru_maxrss) / 1024.0);
  return 0;
}
