#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: install everything, build, and
# reproduce the paper's study (figures + report) into results/paper/.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh -DSTICKSLIP_BUILD_TESTS=OFF -DSTICKSLIP_BUILD_BENCH=OFF
out=${1:-results/paper}
build/apps/stickslip/stickslip reproduce --overwrite -o "$out"
echo "main: report at $out/report.html (and $out/report.md), figures in $out/figures/"
