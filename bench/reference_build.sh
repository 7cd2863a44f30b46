#!/usr/bin/env bash
# A Release build of an earlier commit, for side-by-side benchmarks
# (bench/user_commands.sh): a git worktree of REV in DIR/src, built into
# DIR/build (the CLI and, where the commit has it, the Python module).
# Usage: bench/reference_build.sh REV DIR     e.g. 6d302e1 (0.1.0) /tmp/ref-0.1.0
set -euo pipefail
rev=${1:?usage: bench/reference_build.sh REV DIR}
dir=${2:?usage: bench/reference_build.sh REV DIR}
top=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel)
mkdir -p "$dir"
[[ -d $dir/src ]] || git -C "$top" worktree add --detach "$dir/src" "$rev"
cmake -S "$dir/src" -B "$dir/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DSTICKSLIP_BUILD_TESTS=OFF -DSTICKSLIP_BUILD_BENCH=OFF -DPython3_EXECUTABLE=/usr/bin/python3
targets=(stickslip)
grep -q 'stickslip_python' "$dir/build/build.ninja" && targets+=(stickslip_python)
cmake --build "$dir/build" -j "$(nproc)" --target "${targets[@]}"
echo "reference build of $rev: $dir/build"
