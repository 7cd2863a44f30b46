#!/usr/bin/env bash
# Paired timing of two stickslip binaries on one command, for changes whose
# effect is smaller than this machine's drift between runs (2 shared cores):
# N pairs run back to back, and the figure is the median of the per-pair
# ratios new/old, which cancels the slow drift that the medians of separate
# series keep. The order alternates (old new, new old, old new, ...: ABBA),
# so that an effect of running second (a warm page cache, a CPU that has
# just sped up or throttled) falls on each binary in half of the pairs
# (take N even).
#
#   bench/paired.sh OLD_BINARY NEW_BINARY N SUBCOMMAND ARGS...
#   e.g. bench/paired.sh /tmp/old/stickslip build/apps/stickslip/stickslip 10 \
#          sweep --lambda log:0.1:30:40 --mu 0.5,1,2,3,4,5,6,7 --realizations 2000 --seed 1
#
# Each run writes to a fresh temporary directory (-o DIR is appended for
# sweep and reproduce). Prints the median ratio of wall and CPU (user + sys)
# seconds, the median seconds of each binary, and every pair's wall ratio.
set -euo pipefail
(($# >= 4)) || { sed -n 2,17p "$0"; exit 2; }
old=$1 new=$2 n=$3
shift 3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
times=$work/times
for i in $(seq "$n"); do
  order=(old new)
  ((i % 2 == 0)) && order=(new old)
  for tag in "${order[@]}"; do
    bin=$old
    [[ $tag == new ]] && bin=$new
    out=()
    case $1 in sweep | reproduce) out=(-o "$work/out") ;; esac
    rm -rf "$work/out"
    /usr/bin/time -f "$tag $i %e %U %S" -a -o "$times" "$bin" "$@" "${out[@]}" >/dev/null 2>&1 ||
      { echo "paired.sh: $bin $* failed" >&2; exit 1; }
  done
done
python3 - "$times" <<'PY'
import statistics as st, sys
runs = {}
for line in open(sys.argv[1]):
    tag, i, wall, user, sys_ = line.split()
    runs.setdefault(i, {})[tag] = (float(wall), float(user) + float(sys_))
wall = [r["new"][0] / r["old"][0] for r in runs.values()]
cpu = [r["new"][1] / r["old"][1] for r in runs.values()]
print("pairs %d: median new/old wall %.3f, CPU %.3f | median wall old %.2f s, new %.2f s"
      % (len(runs), st.median(wall), st.median(cpu),
         st.median(r["old"][0] for r in runs.values()),
         st.median(r["new"][0] for r in runs.values())))
print("wall ratios:", " ".join("%.3f" % x for x in wall), "(odd pairs ran old first, even pairs new first)")
PY
