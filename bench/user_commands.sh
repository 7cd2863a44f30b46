#!/usr/bin/env bash
# The commands users run, side by side: this build against a reference build
# (an earlier commit, e.g. 0.1.0 = 6d302e1, or the previous head), run
# interleaved after one warm-up of each, in alternating order (ref new, new
# ref, ref new, ...: whichever runs second in a pair was ~2 % slower on the
# Intel Xeon of 2026-11-29), and the medians of whole-process figures: wall
# and CPU seconds (user + sys), peak resident memory (GNU time's maximum
# RSS) and the bytes the command wrote; then `pairs`, the median of the
# per-pair wall and CPU ratios new/ref (take an even number of runs).
#
# Usage: bench/user_commands.sh NEW_BUILD REF_BUILD [runs] [case ...]
#   NEW_BUILD, REF_BUILD  CMake build directories (apps/stickslip/stickslip,
#                         and python/ for the python case)
#   runs                  interleaved runs of each build (default 5)
#   case                  any of: sweep sweep_R sweep_all observe damped family
#                         grid6400 grid100k
#                         peak reproduce_nofig reproduce python (default:
#                         sweep damped family peak python); sweep_R and
#                         sweep_all add --statistics R / all where the build
#                         has the flag (0.1.0 then runs the plain sweep)
# Make a reference build of any commit with bench/reference_build.sh.
# A command the reference does not have (e.g. `peak` before 0.2) shows n/a.
# Times are noisy on a shared 2-core machine: compare the ratios of one run.
set -euo pipefail
new=${1:?usage: bench/user_commands.sh NEW_BUILD REF_BUILD [runs] [case ...]}
ref=${2:?usage: bench/user_commands.sh NEW_BUILD REF_BUILD [runs] [case ...]}
runs=${3:-5}
shift $(( $# < 3 ? $# : 3 ))
cases=("$@")
((${#cases[@]})) || cases=(sweep damped family peak python)
python=/usr/bin/python3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

paper_grid=(--lambda log:0.1:30:40 --mu 0.5,1,2,3,4,5,6,7 --realizations 2000 --seed 1)
# args_of CASE: the command line after the binary (DIR is the output)
args_of() {
  case $1 in
    sweep) echo sweep "${paper_grid[*]}" -o DIR ;;
    # The paper grid for R alone: --statistics R with the new build, the
    # plain sweep with a reference that has no --statistics (0.1.0).
    sweep_R) echo sweep "${paper_grid[*]}" STATS_R -o DIR ;;
    sweep_all) echo sweep "${paper_grid[*]}" STATS_ALL -o DIR ;;
    observe) echo sweep "${paper_grid[*]}" --observe-times lin:0:50:101 -o DIR ;;
    damped) echo sweep "${paper_grid[*]}" --c 0.632 -o DIR ;;
    family) echo sweep --lambda log:0.1:30:40 --mu-k 0.5,1,2,3,4,5,6,7 --mu-s 8 --realizations 2000 --seed 1 -o DIR ;;
    # The issue's large grids: 6,400 points (100 realizations) and 100,000
    # points (20 realizations), both on 2 threads: their outputs are written
    # window by window as the run goes (docs/outputs.md).
    grid6400) echo sweep --lambda log:0.1:30:80 --mu lin:0.5:7:80 --realizations 100 --threads 2 -o DIR ;;
    grid100k) echo sweep --lambda log:0.1:30:400 --mu lin:0.5:7:250 --realizations 20 --threads 2 -o DIR ;;
    peak) echo peak --statistic R --over lambda --range 0.1:30 --k 40 --mu 5 --seed 1 --format json ;;
    reproduce_nofig) echo reproduce --no-figures -o DIR ;;
    reproduce) echo reproduce -o DIR ;;
    python) echo "<python> stickslip.sweep(lam=np.geomspace(0.1, 30, 40), mu=[0.5,1,2,3,4,5,6,7], realizations=2000, seed=1, output=DIR)" ;;
    *) echo "unknown case $1" >&2; exit 2 ;;
  esac
}

# run_once BUILD CASE OUTFILE: appends "wall cpu maxrss_kb bytes" or "n/a"
run_once() {
  local build=$1 case=$2 out=$3 dir="$tmp/out" t="$tmp/time"
  rm -rf "$dir"
  local cmd
  if [[ $case == python ]]; then
    [[ -d $build/python/stickslip ]] || { echo n/a >>"$out"; return; }
    cmd=(env PYTHONPATH="$build/python" "$python" -c
         "import numpy as np, stickslip; stickslip.sweep(lam=np.geomspace(0.1, 30, 40), mu=[0.5,1,2,3,4,5,6,7], realizations=2000, seed=1, output='$dir')")
  else
    local line; line=$(args_of "$case")
    # --statistics only where the build has it
    local stats_r="" stats_all=""
    if "$build/apps/stickslip/stickslip" sweep --help 2>/dev/null | grep -- '--statistics' >/dev/null; then
      stats_r="--statistics R" stats_all="--statistics all"
    fi
    line=${line//STATS_R/$stats_r}
    line=${line//STATS_ALL/$stats_all}
    # shellcheck disable=SC2206
    cmd=("$build/apps/stickslip/stickslip" ${line//DIR/$dir})
  fi
  if ! /usr/bin/time -f '%e %U %S %M' -o "$t" "${cmd[@]}" >"$tmp/stdout" 2>"$tmp/err"; then
    echo n/a >>"$out"
    echo "  $case failed with $build: $(tail -n 3 "$tmp/err")" >&2
    return
  fi
  # Bytes written: the output directory, or what the command printed.
  local bytes; bytes=$(stat -c %s "$tmp/stdout")
  [[ -e $dir ]] && bytes=$(du -sb "$dir" | cut -f1)
  awk -v b="$bytes" '{printf "%s %.3f %s %s\n", $1, $2 + $3, $4, b}' "$t" >>"$out"
}

# median COLUMN FILE
median() {
  awk -v c="$1" '$1 != "n/a" {print $c}' "$2" | sort -g |
    awk '{a[NR]=$1} END {if (!NR) print "n/a"; else print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'
}
ratio() { awk -v a="$1" -v b="$2" 'BEGIN {if (a == "n/a" || b == "n/a" || b == 0) print "n/a"; else printf "%.2f", a / b}'; }

echo "machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores; load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "new: $new ($(git -C "$(dirname "$0")/.." rev-parse --short HEAD 2>/dev/null || echo ?)); ref: $ref; $runs interleaved runs after a warm-up; medians"
printf '%-16s %-5s %9s %9s %11s %12s\n' case build wall_s cpu_s peak_MB out_bytes
for c in "${cases[@]}"; do
  run_once "$ref" "$c" /dev/null
  run_once "$new" "$c" /dev/null
  for ((i = 0; i < runs; ++i)); do
    if ((i % 2 == 0)); then
      run_once "$ref" "$c" "$tmp/$c.ref"
      run_once "$new" "$c" "$tmp/$c.new"
    else
      run_once "$new" "$c" "$tmp/$c.new"
      run_once "$ref" "$c" "$tmp/$c.ref"
    fi
  done
  for b in ref new; do
    f="$tmp/$c.$b"
    mb=$(median 3 "$f"); [[ $mb != n/a ]] && mb=$(awk -v k="$mb" 'BEGIN {printf "%.1f", k / 1024}')
    printf '%-16s %-5s %9s %9s %11s %12s\n' "$c" "$b" "$(median 1 "$f")" "$(median 2 "$f")" "$mb" "$(median 4 "$f")"
  done
  printf '%-16s %-5s %9s %9s %11s %12s\n' "$c" "ratio" \
    "$(ratio "$(median 1 "$tmp/$c.new")" "$(median 1 "$tmp/$c.ref")")" \
    "$(ratio "$(median 2 "$tmp/$c.new")" "$(median 2 "$tmp/$c.ref")")" \
    "$(ratio "$(median 3 "$tmp/$c.new")" "$(median 3 "$tmp/$c.ref")")" \
    "$(ratio "$(median 4 "$tmp/$c.new")" "$(median 4 "$tmp/$c.ref")")"
  # The median of the ratios of each pair (run i of each build), which
  # cancels the machine's slow drift that the separate medians keep.
  printf '%-16s %-5s %9s %9s\n' "$c" "pairs" \
    "$(paste "$tmp/$c.new" "$tmp/$c.ref" | awk 'NF == 8 && $5 > 0 {printf "%.4f\n", $1 / $5}' | sort -g |
       awk '{a[NR]=$1} END {if (!NR) print "n/a"; else printf "%.2f", (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}')" \
    "$(paste "$tmp/$c.new" "$tmp/$c.ref" | awk 'NF == 8 && $6 > 0 {printf "%.4f\n", $2 / $6}' | sort -g |
       awk '{a[NR]=$1} END {if (!NR) print "n/a"; else printf "%.2f", (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}')"
  echo "  command: stickslip $(args_of "$c")"
done
