#!/usr/bin/env bash
# The 10^7-execution fuzz runs recorded in docs/bad-input.md ("Long runs").
#
#   scripts/fuzz_long.sh [TARGET...]      (default: all eight targets, one after another)
#
# Builds two fuzz variants without AddressSanitizer (UndefinedBehaviorSanitizer
# and libFuzzer only, 1.8-2.5x more executions per second than the CI build):
#   build-fuzz-ub  with CMP tracing (the parsers, family_toml, merge_inputs)
#   build-fuzz-nc  without CMP tracing (-fno-sanitize-coverage=trace-cmp: the
#                  model and journal targets, 1.6-1.9x faster again)
# and runs each target for -runs=10000000 at nice 19 from the committed corpus
# (tests/fuzz/corpus/<target>, read only) into $FUZZ_LONG_DIR/corpus/<target>.
# Logs: $FUZZ_LONG_DIR/log-<target>.txt; one line per finished run in
# $FUZZ_LONG_DIR/results.txt; crash inputs in $FUZZ_LONG_DIR/crashes.
# Never SIGSTOP a running fuzzer: libFuzzer counts the pause against
# -timeout and writes a spurious timeout input (then exits).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
out=${FUZZ_LONG_DIR:-$root/build-fuzz-long}
jobs=${FUZZ_BUILD_JOBS:-$(nproc)}
all=(config_toml grid_spec switch_times simulator model_family journal_reader merge_inputs family_toml)
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=("${all[@]}")
variant_of() {  # TARGET -> build directory
  case $1 in
    simulator | model_family | journal_reader) echo build-fuzz-nc ;;
    *) echo build-fuzz-ub ;;
  esac
}
gen=(); command -v ninja >/dev/null && gen=(-G Ninja)
for dir in build-fuzz-ub build-fuzz-nc; do
  flags="-fno-sanitize-recover=all"
  [ $dir = build-fuzz-nc ] && flags="$flags -fno-sanitize-coverage=trace-cmp"
  CC=clang CXX=clang++ cmake -S . -B $dir "${gen[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSTICKSLIP_BUILD_FUZZERS=ON -DSTICKSLIP_BUILD_TESTS=OFF -DSTICKSLIP_BUILD_BENCH=OFF \
    -DSTICKSLIP_WITH_MPI=OFF -DSTICKSLIP_SANITIZE=fuzzer-no-link,undefined \
    -DCMAKE_CXX_FLAGS="$flags" >/dev/null
done
mkdir -p "$out/crashes" "$out/bin"
for t in "${targets[@]}"; do
  dir=$(variant_of "$t")
  cmake --build "$dir" -j "$jobs" --target "fuzz_$t" >"$out/build-$t.log" 2>&1 \
    || { tail -n 40 "$out/build-$t.log"; exit 1; }
  cp "$dir/tests/fuzz/fuzz_$t" "$out/bin/"  # rebuilding later does not touch a running run
done
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
commit=$(git rev-parse --short HEAD)
for t in "${targets[@]}"; do
  mkdir -p "$out/corpus/$t"
  start=$(date -u +%FT%TZ)
  s=$(date +%s)
  rc=0
  (cd "$out" && nice -n 19 bin/fuzz_$t corpus/$t "$root/tests/fuzz/corpus/$t" -runs=10000000 \
    -timeout=10 -rss_limit_mb=2048 -max_len=4096 -print_final_stats=1 \
    -artifact_prefix=crashes/$t- >log-$t.txt 2>&1) || rc=$?
  n=$(grep -Eo 'number_of_executed_units: *[0-9]+' "$out/log-$t.txt" | grep -Eo '[0-9]+$' || echo '?')
  echo "$t $(variant_of "$t") commit=$commit start=$start seconds=$(($(date +%s) - s)) rc=$rc executions=$n" \
    | tee -a "$out/results.txt"
done
