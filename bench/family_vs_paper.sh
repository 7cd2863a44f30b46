#!/usr/bin/env bash
# The model family's speed requirement: "with mu_s != mu_k and two-level belts, at
# most 1.5 x the paper model's time on the paper grid". Times `stickslip
# sweep` on the paper's grid (40 lambda log-spaced in [0.1, 30] x 8 mu x
# 2000 realizations, k = 40, t_a = 50) for
#   paper   the paper's model: --mu 0.5,1,2,3,4,5,6,7;
#   family  mu_s = 8 > mu_k = 0.5 .. 7 on the paper's belt (+-1, rates lambda);
#   asym    the same friction on the belt levels 1, -0.5 (rates lambda);
#   scalar  family with --engine reference (simulate_model, one realization
#           at a time: what family points ran before the lane engine took them);
#   damped  the paper's friction with damping ratio zeta = 0.05 (c = 0.632):
#           simulate_model with certified root isolation (target: <= 4 x);
# interleaved (paper, family, asym, scalar, paper, ...), and prints medians of
# the wall time and of the CPU time (user + sys; robust to other load on the
# machine) and the ratios to the paper.
# Usage: bench/family_vs_paper.sh [build-dir] [runs] [threads]   (default: build 3 2)
set -euo pipefail
build=${1:-build}
runs=${2:-3}
threads=${3:-2}
exe="$build/apps/stickslip/stickslip"
[[ -x "$exe" ]] || { echo "missing $exe: build stickslip (Release)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

grid=(--lambda log:0.1:30:40 --k 40 --realizations 2000 --threads "$threads" --overwrite)
mus=0.5,1,2,3,4,5,6,7
declare -A args=(
  [paper]="--mu $mus"
  [family]="--mu-k $mus --mu-s 8"
  [asym]="--mu-k $mus --mu-s 8 --belt-levels 1,-0.5"
  [scalar]="--mu-k $mus --mu-s 8 --engine reference"
  [damped]="--mu $mus --c 0.632"
)
cases=(paper family asym scalar damped)

# median FILE: the median of the numbers in FILE, one a line
median() { sort -g "$1" | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores; load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "runs per case: $runs (interleaved, medians); threads: $threads"
for ((i = 0; i < runs; ++i)); do
  for c in "${cases[@]}"; do
    # shellcheck disable=SC2086
    /usr/bin/time -f "%e %U %S" -o "$tmp/time" "$exe" sweep "${grid[@]}" ${args[$c]} -o "$tmp/out-$c" > /dev/null 2>&1
    read -r wall user sys < "$tmp/time"
    echo "$wall" >> "$tmp/$c.wall"
    echo "$user + $sys" | bc -l >> "$tmp/$c.cpu"
  done
done
pw=$(median "$tmp/paper.wall"); pc=$(median "$tmp/paper.cpu")
printf '%-8s %10s %10s %14s %14s\n' case wall_s cpu_s wall/paper cpu/paper
for c in "${cases[@]}"; do
  w=$(median "$tmp/$c.wall"); u=$(median "$tmp/$c.cpu")
  printf '%-8s %10.3f %10.3f %14.2f %14.2f\n' "$c" "$w" "$u" "$(echo "$w / $pw" | bc -l)" \
    "$(echo "$u / $pc" | bc -l)"
done
echo "model family targets: family / paper <= 1.5, damped / paper <= 4"
