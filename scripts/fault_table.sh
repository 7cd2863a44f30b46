#!/usr/bin/env bash
# The full fault-injection table of docs/reliability.md: runs
# tests/faults/fault_table.sh with the full trial counts (SCALE 1) on the
# binary built in build/ (or $STICKSLIP_BIN), at low priority, and prints the
# date, the binary, the command and the table.
# Usage: scripts/fault_table.sh [SCALE] [ROW...]   (default SCALE 1: ~15-25 min on 2 cores)
#   Short version (as ctest runs it):  scripts/fault_table.sh 0.06
set -uo pipefail
cd "$(dirname "$0")/.."
bin=${STICKSLIP_BIN:-build/apps/stickslip/stickslip}
[[ -x $bin ]] || { echo "fault_table.sh: $bin not found: build first (scripts/build.sh)" >&2; exit 2; }
scale=${1:-1}
shift $(($# ? 1 : 0))
echo "date: $(date -u)"
echo "binary: $bin ($(stat -c '%y' "$bin" | cut -d. -f1), git $(git rev-parse --short HEAD 2>/dev/null || echo '?'))"
echo "host: $(nproc) cores, $(uname -sr), $(mpirun --version 2>/dev/null | head -1 || echo 'no mpirun')"
echo "command: nice -n 10 tests/faults/fault_table.sh $bin $scale $*"
echo
exec nice -n 10 bash tests/faults/fault_table.sh "$bin" "$scale" "$@"
