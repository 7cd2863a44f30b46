#!/usr/bin/env bash
# The paper grid (40 lambda x 8 mu x 2000 realizations, k = 40, t_a = 50) from
# the CLI and from Python, interleaved, REPS times each; prints the median wall
# time of each -- the whole process (for Python including the interpreter's
# start and importing numpy, pandas and xarray) and, for Python, the
# stickslip.sweep() call alone (simulation, results.nc, reading it back) --
# and their ratios to the CLI.
#   bench/python_vs_cli.sh [BUILD_DIR] [REPS]
set -euo pipefail
build=${1:-build}; reps=${2:-5}
bin=$build/apps/stickslip/stickslip
export PYTHONPATH=$build/python
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
grid=(--lambda log:0.1:30:40 --mu 0.5,1,2,3,4,5,6,7 --k 40 --realizations 2000 --seed 1)
py='import time, numpy as np, stickslip
t0 = time.perf_counter()
stickslip.sweep(lam=np.logspace(-1, np.log10(30), 40), mu=[0.5,1,2,3,4,5,6,7], k=40, realizations=2000, seed=1)
print(f"{time.perf_counter() - t0:.3f}")'
now() { date +%s.%N; }
cli_t=(); py_t=(); call_t=()
for ((i = 0; i < reps; i++)); do
  t0=$(now); "$bin" sweep "${grid[@]}" -o "$work/cli$i" 2>/dev/null; t1=$(now)
  call_t+=("$(/usr/bin/python3 -c "$py")"); t2=$(now)
  cli_t+=("$(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.3f", b - a}')")
  py_t+=("$(awk -v a="$t1" -v b="$t2" 'BEGIN {printf "%.3f", b - a}')")
done
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
mc=$(median "${cli_t[@]}"); mp=$(median "${py_t[@]}")
echo "CLI    sweep: median ${mc} s of: ${cli_t[*]}"
echo "Python sweep: median ${mp} s of: ${py_t[*]}"
mcall=$(median "${call_t[@]}")
echo "Python sweep() call alone: median ${mcall} s of: ${call_t[*]}"
echo "Python process / CLI: $(awk -v a="$mp" -v b="$mc" 'BEGIN {printf "%.3f", a / b}')"
echo "Python call / CLI:    $(awk -v a="$mcall" -v b="$mc" 'BEGIN {printf "%.3f", a / b}')"
