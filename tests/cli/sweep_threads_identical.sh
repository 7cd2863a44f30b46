# The sweep's results are bit-identical for --threads 1, 2 and 8:
# the "points" text of summary.json, summary.csv, records.csv and every
# NetCDF variable (ncdump without the global attributes, which hold the
# creation time, elapsed time, thread count and command line). The same holds
# for --engine reference (the plain one-realization-at-a-time exact path)
# against the default SIMD lane engine.
source "$(dirname "$0")/lib.sh"

for t in 1 2 8; do
  run_ok sweep --lambda log:0.1:30:6 --mu 0.5,5 --ta 20 --realizations 230 --block-size 16 \
    --seed 5 --records --threads "$t" -o "t$t"
  grep -qE '^2760 realizations in [0-9.e+-]+ s' stderr || fail "final line: $(cat stderr)"
done

points() {  # the raw text of the "points" array of summary.json
  "$PY" -c '
import json, sys
text = open(sys.argv[1]).read()
start = text.index("\"points\"")
json.loads(text)  # valid JSON
depth, i = 0, text.index("[", start)
for j in range(i, len(text)):
    depth += {"[": 1, "]": -1}.get(text[j], 0)
    if depth == 0:
        print(text[start:j + 1])
        break
' "$1"
}
variables() { ncdump "$1" | sed '/^\/\/ global attributes:/,/^data:/{/^data:/!d}'; }

points t1/summary.json >p1
[[ $(wc -c <p1) -gt 1000 ]] || fail "points section looks empty"
variables t1/results.nc >v1
grep -q "R_mean" v1 || grep -q "stick_fraction" v1 || fail "ncdump shows no statistics"
for t in 2 8; do
  points "t$t/summary.json" >"p$t"
  cmp -s p1 "p$t" || fail "summary.json points differ between --threads 1 and $t"
  variables "t$t/results.nc" >"v$t"
  cmp -s v1 "v$t" || fail "NetCDF variables differ between --threads 1 and $t: $(diff v1 "v$t" | head -5)"
  cmp -s t1/summary.csv "t$t/summary.csv" || fail "summary.csv differs for --threads $t"
  cmp -s t1/records.csv "t$t/records.csv" || fail "records.csv differs for --threads $t"
  checks=$((checks + 4))
done

run_ok sweep --lambda log:0.1:30:6 --mu 0.5,5 --ta 20 --realizations 230 --block-size 16 \
  --seed 5 --records --threads 2 --engine reference -o ref
points ref/summary.json >pref
cmp -s p1 pref || fail "summary.json points differ between the fast and reference engines"
cmp -s t1/records.csv ref/records.csv || fail "records.csv differs between engines"
variables ref/results.nc | grep -v 'engine = ' >vref
grep -v 'engine = ' v1 >v1e
cmp -s v1e vref || fail "NetCDF variables differ between engines"
checks=$((checks + 3))
expect_fail "invalid --engine: 'turbo' (allowed: fast or reference)" sweep --lambda 1 --engine turbo
finish
