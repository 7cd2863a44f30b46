#!/usr/bin/env bash
# Sanitizer runs for CI, each in its own build directory:
#   build-asan  AddressSanitizer + UndefinedBehaviorSanitizer (no recovery):
#               the unit, property, regression, reference and resume test
#               suites (GoogleTest executables) under ctest. Every SIMD
#               target the CPU runs (AVX-512, AVX2, SSE4, ...; dispatched at
#               run time) is exercised by tests/unit/test_reproducible_bits.cpp,
#               which forces each one in turn.
#   build-tsan  ThreadSanitizer: the threaded sweep (4 threads, journaled,
#               killed and resumed) and the threaded-sweep unit tests.
# MPI is off in these builds (Open MPI itself is not sanitizer-clean).
# Usage: scripts/sanitizers.sh [asan|tsan]   (default: both)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
jobs=${SANITIZER_JOBS:-$(nproc)}
gen=(); command -v ninja >/dev/null && gen=(-G Ninja)
# -O1 and line tables only (-g1, CMakeLists.txt): the sanitizers' usual
# setting, with file:line in every report; it halves the build, which was
# most of CI's time (ASan+UBSan 791 s against 1,362 s with -O2 -g).
common=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -DNDEBUG"
        -DSTICKSLIP_WITH_MPI=OFF -DSTICKSLIP_BUILD_BENCH=OFF -DSTICKSLIP_BUILD_TESTS=ON)
gtests=(unit_tests property_tests regression_tests reference_tests resume_tests)
which=${1:-all}

existing_targets() {  # the gtest targets this tree defines
  # The help text is read once into a variable: `cmake ... | grep -q` under
  # pipefail fails at random once the text is long (grep exits early, cmake
  # gets SIGPIPE), and the target would be dropped.
  local dir=$1; shift
  local help
  help=$(cmake --build "$dir" --target help 2>/dev/null)
  for t in "$@"; do
    if grep -qE "(^|[ /])$t(:| )" <<<"$help"; then echo "$t"; fi
  done
}

if [[ $which == all || $which == asan ]]; then
  echo "== ASan + UBSan: unit tests"
  t0=$SECONDS
  cmake -S . -B build-asan "${gen[@]}" "${common[@]}" -DSTICKSLIP_SANITIZE=address,undefined \
    -DCMAKE_CXX_FLAGS="-fno-sanitize-recover=all" >/dev/null
  mapfile -t targets < <(existing_targets build-asan "${gtests[@]}")
  ((${#targets[@]} > 0)) || { echo "sanitizers.sh: no test targets found in build-asan" >&2; exit 1; }
  cmake --build build-asan -j "$jobs" --target "${targets[@]}"
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:halt_on_error=1
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  regex=$(IFS='|'; echo "${targets[*]}")
  # Not here: the Monte Carlo agreement tests that take 40-100 s each under
  # ASan (670 of the 1,145 s of test time on a 2-core machine, 2026-11-30).
  # They rerun the code paths of their suites' other tests, which stay (every
  # suite keeps at least one test here), thousands of times over, to a
  # statistical tolerance; the main ctest runs them all without sanitizers.
  slow='SobolCoverage\.(IshigamiDeterministic|GFunctionDeterministic|GFunctionWithNoise|Saltelli2010FormWithNoise)'
  slow+='|SensitivityDesign\.SharesAgreeWithQuadratureOfFixedValueSweeps|CrnSlopes\.AgreeWithTheLikelihoodRatioDerivatives'
  slow+='|(ScoreDerivative|BeltGeneratorScore|BeltRateScore)\.AgreesWithCommonRandomNumberDifferences'
  slow+='|CausalScore\.AgreesWithCommonRandomNumberDifferencesAndHasLessVariance'
  ctest --test-dir build-asan -L "^(${regex})\$" -E "^(${slow})\$" -j 2 --output-on-failure --timeout 600
  echo "== ASan + UBSan: passed (${targets[*]}) in $((SECONDS - t0)) s"
fi

if [[ $which == all || $which == tsan ]]; then
  echo "== TSan: threaded sweep"
  t0=$SECONDS
  cmake -S . -B build-tsan "${gen[@]}" "${common[@]}" -DSTICKSLIP_SANITIZE=thread >/dev/null
  cmake --build build-tsan -j "$jobs" --target stickslip unit_tests
  export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1"
  bin=$root/build-tsan/apps/stickslip/stickslip
  work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
  args=(sweep --lambda 0.1,1,8 --mu 0.5,3 --ta 30 --realizations 120 --block-size 10 --records
        --threads 4 --checkpoint-interval 0.05)
  "$bin" "${args[@]}" -o "$work/a"
  # Interrupt a journaled run (SIGTERM: finished units journaled), resume it.
  "$bin" "${args[@]}" -o "$work/b" & pid=$!
  sleep 1; kill -TERM $pid 2>/dev/null || true
  wait $pid || true
  "$bin" "${args[@]}" -o "$work/b" --resume
  cmp "$work/a/summary.csv" "$work/b/summary.csv"
  cmp "$work/a/records.csv" "$work/b/records.csv"
  "$root/build-tsan/tests/unit/unit_tests" --gtest_filter='*Sweep*:*Thread*:*Merge*:*Fast*'
  echo "== TSan: passed in $((SECONDS - t0)) s"
fi
