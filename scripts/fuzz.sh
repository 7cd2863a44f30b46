#!/usr/bin/env bash
# libFuzzer runs of the fuzz targets (tests/fuzz), built with clang and
# -fsanitize=fuzzer,address,undefined in build-fuzz:
#   fuzz_config_toml   TOML sweep configuration parser (+ to_toml round trip)
#   fuzz_grid_spec     grid specifications, numbers, unsigned integers
#   fuzz_switch_times  switch-times file reader and --switch-times lists
#   fuzz_simulator     raw doubles -> validate -> simulate (small event bound)
#   fuzz_model_family  decoded family models -> validate -> simulate_model with
#                      replayed level switches: tiling, stick band, energy
#                      balance; lane engine vs simulate_model bit for bit
#   fuzz_journal_reader  edits of a valid checkpoint journal -> read_journal
#                      refuses or recomputes, never misreads a unit
#   fuzz_merge_inputs  shard directories built from real journals, then
#                      mutated -> merge_shards refuses with a stickslip error
#                      or equals the direct run of the spec
#   fuzz_family_toml   generated family TOML (levels, rates, generator, laws,
#                      initial state, grid) + byte damage -> error, or a spec
#                      that round-trips through to_toml; validate throws or accepts
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET [TARGET...]]   (default 25: the bounded CI run)
#   Longer run, documented in docs/bad-input.md:  scripts/fuzz.sh 1800
#   FUZZ_SANITIZERS=undefined FUZZ_DIR=build-fuzz-ub scripts/fuzz.sh 0 builds a
#   variant without AddressSanitizer (2-4x more executions per second) for the
#   10^7-execution runs (scripts/fuzz_long.sh); 0 seconds builds without running.
# New inputs are kept in $FUZZ_DIR/corpus/<target>; crashes in $FUZZ_DIR/crashes.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-25}
shift || true
dir=${FUZZ_DIR:-build-fuzz}
sanitizers=${FUZZ_SANITIZERS:-address,undefined}
jobs=${FUZZ_BUILD_JOBS:-$(nproc)}
if ! command -v clang++ >/dev/null; then
  echo "fuzz.sh: clang++ not found (Debian: clang, libclang-rt-14-dev); skipped"
  exit 0
fi
gen=(); command -v ninja >/dev/null && gen=(-G Ninja)
CC=clang CXX=clang++ cmake -S . -B "$dir" "${gen[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSTICKSLIP_BUILD_FUZZERS=ON -DSTICKSLIP_BUILD_TESTS=OFF -DSTICKSLIP_BUILD_BENCH=OFF \
  -DSTICKSLIP_WITH_MPI=OFF -DSTICKSLIP_SANITIZE="fuzzer-no-link,$sanitizers" \
  -DCMAKE_CXX_FLAGS="-fno-sanitize-recover=all" >/dev/null
targets=(config_toml grid_spec switch_times simulator model_family journal_reader merge_inputs family_toml)
[ $# -gt 0 ] && targets=("$@")
cmake --build "$dir" -j "$jobs" --target "${targets[@]/#/fuzz_}" >"$dir/build.log" 2>&1 \
  || { tail -n 40 "$dir/build.log"; exit 1; }
[ "$seconds" = 0 ] && exit 0
mkdir -p "$dir/crashes"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
status=0
for t in "${targets[@]}"; do
  corpus=$dir/corpus/$t
  mkdir -p "$corpus"
  log=$dir/fuzz_$t.log
  if "$dir"/tests/fuzz/fuzz_$t "$corpus" tests/fuzz/corpus/$t -max_total_time="$seconds" \
      -timeout=10 -rss_limit_mb=2048 -max_len=4096 -print_final_stats=1 \
      -artifact_prefix="$dir/crashes/$t-" >"$log" 2>&1; then
    runs=$(grep -Eo 'stat::number_of_executed_units: *[0-9]+' "$log" | grep -Eo '[0-9]+$' || echo '?')
    echo "fuzz_$t: ${seconds} s, $runs executions, no crash"
  else
    echo "fuzz_$t: FAILED (see $log and $dir/crashes/)"; tail -n 30 "$log"; status=1
  fi
done
exit $status
