#!/usr/bin/env bash
# All tests on a fresh Debian 12 machine: install everything, build, run the
# unit/property/reference/integration/CLI/MPI suites, then the sanitizer
# builds and bounded fuzz runs. Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
scripts/build.sh -DSTICKSLIP_BUILD_TESTS=ON -DSTICKSLIP_BUILD_BENCH=OFF -DSTICKSLIP_WARNINGS_AS_ERRORS=ON
ctest --test-dir build --output-on-failure -j 2 --timeout 900
for extra in scripts/sanitizers.sh scripts/fuzz.sh; do
  if [[ -x $extra ]]; then
    echo "== $extra"
    "$extra"
  fi
done
echo "test: all suites passed"
