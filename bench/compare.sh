#!/usr/bin/env bash
# One comparison table: our exact method beside Octave ode45 (the
# paper's method), SUNDIALS CVODE and Boost.Odeint dopri5, on identical
# scenarios (initial conditions and switch times from the core's streams).
#
#   bench/compare.sh            Octave on 10 s windows, 2 realizations per
#                               (k, lambda): ~4 min on an idle 2-core machine
#   bench/compare.sh --full     Octave on the full 50 s windows, 4 realizations
#                               (no extrapolation; ~40 min on 2 cores)
#   options: --octave-window S  --realizations N  --jobs N (parallel Octave runs)
#            --build-dir DIR (default build-bench)  --no-octave
#
# Exact, CVODE and odeint always run the full 50 s windows. Octave's CPU time
# on the short window is scaled linearly to 50 s; the table marks it with ~.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build="$root/build-bench"
octave_window=10
realizations=2
jobs=2
run_octave=1
while [[ $# -gt 0 ]]; do
  case "$1" in
    --full) octave_window=50; realizations=4 ;;
    --octave-window) octave_window="$2"; shift ;;
    --realizations) realizations="$2"; shift ;;
    --jobs) jobs="$2"; shift ;;
    --build-dir) build="$2"; shift ;;
    --no-octave) run_octave=0 ;;
    -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
    *) echo "compare.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done

if [[ ! -f "$build/CMakeCache.txt" ]]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DSTICKSLIP_BUILD_TESTS=OFF -DSTICKSLIP_BUILD_BENCH=ON >/dev/null
fi
cmake --build "$build" --target stickslip_compare >/dev/null
tool="$build/bench/stickslip_compare"
dir="$build/compare-w${octave_window}-r${realizations}"
mkdir -p "$dir"
grid=(--dir "$dir" --octave-window "$octave_window" --realizations "$realizations")
"$tool" emit "${grid[@]}"
rm -f "$dir"/*.octave

if [[ $run_octave == 1 ]] && command -v octave >/dev/null; then
  n=$(ls "$dir"/scenario_*.txt | wc -l)
  echo "Running Octave ode45 on $n scenarios of ${octave_window} s ($jobs at a time)..." >&2
  ls "$dir"/scenario_*.txt | xargs -P "$jobs" -I{} sh -c \
    'f="$1"; octave --no-gui --no-window-system -q --eval "addpath(\"$2\"); stickslip_ode45(\"$f\", \"${f%.txt}.octave.tmp\")" >/dev/null 2>&1 && mv "${f%.txt}.octave.tmp" "${f%.txt}.octave"; echo "  done $(basename "$f")" >&2' \
    _ {} "$root/bench/octave"
elif [[ $run_octave == 1 ]]; then
  echo "octave not found: the Octave rows are left out" >&2
fi

echo "Machine: $(lscpu | sed -n 's/^Model name:[[:space:]]*//p'), $(nproc) cores; $(date -u +%Y-%m-%dT%H:%MZ); git $(git -C "$root" rev-parse --short HEAD)"
echo
"$tool" table "${grid[@]}"
