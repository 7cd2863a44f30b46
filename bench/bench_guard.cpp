// main() for the benchmark executables. Timings from a build with assertions
// on are meaningless, so such a build refuses to run.
#include <benchmark/benchmark.h>

#include <cstdio>

int main(int argc, char** argv) {
#ifndef NDEBUG
  std::fprintf(stderr, "%s: built with assertions on (NDEBUG undefined); benchmarks need a Release build\n", argv[0]);
  return 1;
#else
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
#endif
}
