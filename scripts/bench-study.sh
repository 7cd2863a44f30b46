#!/usr/bin/env bash
# The paper's full study timed end to end, beside its floor.
# Prints, as medians of N runs: the study wall time for k = 4 and k = 40,
# the floor (all belt switch times of the same study drawn alone), the ratio
# study/floor, realizations/s, events/s by type, peak RSS, and the thread
# scaling 1 -> 2 threads. Needs a Release build with benchmarks:
#   cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release && ninja -C build stickslip_bench_study
# Usage: scripts/bench-study.sh [build-dir] [runs]   (default: build 5)
# STUDY_ENGINE=fast|reference selects the engine (default fast,
# the lane engine; see bench_study.cpp).
set -euo pipefail
build=${1:-build}
runs=${2:-5}
exe="$build/bench/stickslip_bench_study"
[[ -x "$exe" ]] || { echo "missing $exe: build the target stickslip_bench_study (Release)" >&2; exit 1; }

# median KEY FILE: median of the KEY= values in FILE
median() { grep "^$1=" "$2" | cut -d= -f2 | sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores; load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "runs per figure: $runs (median); engine: ${STUDY_ENGINE:-fast}"
for k in 4 40; do
  for t in 2 1; do
    for ((i = 0; i < runs; ++i)); do
      extra=(--engine "${STUDY_ENGINE:-fast}")
      [[ $t == 1 ]] && extra+=(--no-floor)
      "$exe" --k "$k" --threads "$t" "${extra[@]}" >> "$tmp/k$k-t$t"
    done
  done
  f="$tmp/k$k-t2"
  [[ $k == 4 ]] && echo "SIMD target (chosen at run time): $(grep -m1 -o 'simd_target=[^ ]*' "$f" | cut -d= -f2)"
  s2=$(median study_seconds "$f"); s1=$(median study_seconds "$tmp/k$k-t1")
  fl=$(median floor_seconds "$f")
  echo
  echo "k = $k (40 lambda x 8 mu x 2000 realizations, t_a = 50)"
  printf '  study, 2 threads        %8.3f s   (target <= 2.0 s)\n' "$s2"
  printf '  floor, 2 threads        %8.3f s   (switch times alone: Philox + vector log)\n' "$fl"
  printf '  ratio study/floor       %8.2f     (target <= 3)\n' "$(echo "$s2 / $fl" | bc -l)"
  printf '  study, 1 thread         %8.3f s\n' "$s1"
  printf '  scaling 1 -> 2 threads  %8.2f x   (target >= 1.8)\n' "$(echo "$s1 / $s2" | bc -l)"
  printf '  realizations/s          %8.3g\n' "$(median realizations_per_s "$f")"
  printf '  events/s                %8.3g\n' "$(median events_per_s "$f")"
  for e in belt_switches stick_onsets stick_breaks slip_reversals; do
    n=$(median "$e" "$f")
    printf '    %-21s %8.3g events, %8.3g /s\n' "$e" "$n" "$(echo "$n / $s2" | bc -l)"
  done
  printf '  CPU per event           %8.2f ns\n' "$(median cpu_ns_per_event "$f")"
  printf '  CPU time study/floor    %8.2f     (robust to other load on the machine)\n' "$(median cpu_ratio_study_over_floor "$f")"
  printf '  CPU time study          %8.3f s   (wall on an idle machine ~ this / threads)\n' "$(median study_cpu_seconds "$f")"
  printf '  peak RSS                %8.1f MB  (target <= 100 MB)\n' "$(median peak_rss_mb "$f")"
done
