#!/usr/bin/env bash
# `stickslip sensitivity`: the outputs (sensitivity.nc with an `input`
# dimension, summary.json, --format json, the figure), bit-identical indices
# for 1 and 2 threads, after kill -9 + --resume and from shards + merge, and
# bad input refused with exit 2 and nothing written.
source "$(dirname "$0")/lib.sh" "$@"
A=(sensitivity --k 40 --ta 20 --mu 'uniform(2,7)' --lambda 'loguniform(0.5,10)' --samples 600
   --block-size 20 --seed 3)

indices() {  # the estimates of summary.json (no timings, no run metadata)
  "$PY" - "$1" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
print(json.dumps({k: d[k] for k in ("statistic", "realizations", "samples", "laws", "mean",
                                     "variance", "intrinsic_variance", "indices", "shares")},
                 sort_keys=True))
PY
}

run_ok "${A[@]}" --threads 1 -o one --format json
cp "$WORK/stdout" one.json
"$PY" - one.json <<'PY' || fail "--format json lacks what the issue lists"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["statistic"] == "R" and d["realizations"] == 600 * 5 and d["samples"] == 600
assert isinstance(d["elapsed_seconds"], float)
means = [i for i in d["indices"] if i["of"] == "mean"]
resp = [i for i in d["indices"] if i["of"] == "response"]
assert [i["input"] for i in means] == ["mu", "lambda"] and len(resp) == 2
for i in means:
    for k in ("first_order", "total_order"):
        lo, hi = i[k + "_ci95"]
        assert lo <= i[k] <= hi, i
for k in ("parameters", "intrinsic"):
    lo, hi = d["shares"][k + "_ci95"]
    assert lo <= d["shares"][k] <= hi
assert abs(d["shares"]["parameters"] + d["shares"]["intrinsic"] - 1) < 1e-12
PY
pass
for f in sensitivity.nc summary.json; do
  [[ -f one/$f ]] || fail "one/$f missing"
done
if command -v gnuplot >/dev/null; then
  for f in sensitivity.png sensitivity.svg sensitivity.dat sensitivity.gp; do
    [[ -s one/$f ]] || fail "one/$f missing or empty"
  done
fi
"$PY" - one/sensitivity.nc <<'PY' || fail "sensitivity.nc lacks its variables"
import sys, netCDF4
with netCDF4.Dataset(sys.argv[1]) as ds:
    assert ds.dimensions["input"].size == 2
    assert list(ds["input"][:]) == ["mu", "lambda"]
    for v in ("first_order", "total_order", "response_first_order"):
        for s in ("", "_ci95_low", "_ci95_high"):
            assert ds[v + s].dimensions == ("input",)
    for v in ("parameter_share", "intrinsic_share"):
        float(ds[v][...])
    assert "uniform" in ds.resolved_config
PY
pass

run_ok "${A[@]}" --threads 2 -o two
expect_eq "indices with 1 and 2 threads" "$(indices two/summary.json)" "$(indices one/summary.json)"

# kill -9 part-way, then --resume: the same indices.
"$BIN" "${A[@]/600/3000}" --threads 2 -o killed --checkpoint-interval 0 >/dev/null 2>&1 & pid=$!
sleep 0.7; kill -9 $pid 2>/dev/null; { wait $pid; } 2>/dev/null
run_ok "${A[@]/600/3000}" --threads 2 -o straight
run_ok "${A[@]/600/3000}" --threads 1 -o killed --resume
expect_eq "indices after kill -9 and --resume" "$(indices killed/summary.json)" \
  "$(indices straight/summary.json)"

# Shards + merge.
run_ok "${A[@]}" --shard 0/2 -o shard0
run_ok "${A[@]}" --shard 1/2 -o shard1
run_ok merge shard0 shard1 -o merged
expect_eq "indices from shards + merge" "$(indices merged/summary.json)" "$(indices one/summary.json)"

# One writer per directory: a second sensitivity (or sweep) into a running
# study's DIR is refused at once, naming it; a sensitivity into a running
# sweep's DIR too.
"$BIN" "${A[@]/600/400000}" --threads 1 --checkpoint-interval 0.2 -o busy >/dev/null 2>&1 &
first=$!
for _ in $(seq 1 200); do [[ -s busy/.stickslip.lock ]] && break; sleep 0.05; done
"$BIN" "${A[@]}" --resume -o busy >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of a second writer" "$?" "2"
checks=$((checks + 1))
grep -qF "is in use by stickslip sensitivity (pid $first on host " "$WORK/stderr" ||
  fail "the second writer is not refused naming the first: $(cat "$WORK/stderr")"
"$BIN" sweep --lambda 1 --realizations 10 --overwrite -o busy >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of a sweep into a running study" "$?" "2"
kill -9 $first 2>/dev/null; { wait $first; } 2>/dev/null

# Bad input: exit 2, nothing written.
bad() {  # bad "phrases" ARGS...
  local phrases=$1; shift
  "$BIN" "$@" -o "bad_$checks" >"$WORK/stdout" 2>"$WORK/stderr"
  expect_eq "exit code of $*" "$?" "2"
  [[ -e bad_$checks ]] && fail "'$*' failed but wrote bad_$checks"
  local p; IFS='|' read -r -a list <<<"$phrases"
  for p in "${list[@]}"; do
    grep -qF -- "$p" "$WORK/stderr" || fail "stderr of '$*' lacks '$p': $(cat "$WORK/stderr")"
  done
}
bad "no uncertain input" sensitivity --k 40 --mu 5
bad "--lambda|has no grid axes" sensitivity --mu 'uniform(2,7)' --lambda 1,2
bad "--statistic|first_stick_duration|R, sticks_per_time" sensitivity --mu 'uniform(2,7)' --statistic first_stick_duration
bad "--statistic|no_such" sensitivity --mu 'uniform(2,7)' --statistic no_such
bad "--m|normal" sensitivity --m 'normal(mean=1,sd=0.1)'
bad "--statistic|''" sensitivity --mu 'uniform(2,7)' --statistic ''
bad "--mu|gamma(mean=5,cv=1e-200)|1e-5 <= C < 1e150" sensitivity --mu 'gamma(mean=5,cv=1e-200)'
# one range, not two ("C > 0" beside "1e-5 <= cv")
"$BIN" sensitivity --mu 'gamma(mean=5,cv=1e-6)' --samples 8 -o g6 >/dev/null 2>"$WORK/stderr"
grep -qF "C > 0" "$WORK/stderr" && fail "two ranges for gamma's cv: $(cat "$WORK/stderr")"
checks=$((checks + 1))
bad "--mu|beta" sensitivity --mu 'beta(mean=5,sd=1e-200,min=2,max=7)'
bad "--mu|beta|1e10" sensitivity --mu 'beta(min=1e-300,mean=1.3e-154,max=1e-61,sd=1.9e-183)'
bad "--max-samples|only with --target-halfwidth" sensitivity --mu 'uniform(2,7)' --max-samples 7
bad "--samples|--target-halfwidth" sensitivity --mu 'uniform(2,7)' --samples 10 --target-halfwidth 0.1
# one range for --samples (it said 1 .. 2^40, then >= 2 for 1); a default
# that does not fit is named as the default
bad "invalid --samples: '1'|from 2 to" sensitivity --mu 'uniform(2,7)' --samples 1
bad "invalid --samples: '0'|from 2 to" sensitivity --mu 'uniform(2,7)' --samples 0
bad "invalid --min-samples: '1000 (the default)'|give --min-samples too" \
  sensitivity --mu 'uniform(2,7)' --target-halfwidth 0.01 --max-samples 3

# Two rows: intervals wider than [0, 1] are warned of (a share of -5.8 was
# reported without a word); the figure is still drawn, summary.json records it
run_ok sensitivity --k 40 --mu 'uniform(2,7)' --lambda 'loguniform(0.5,10)' --samples 2 -o two_rows
grep -qF "warning: the Sobol' estimates of R from 2 rows say little: a 95 % interval is wider than [0, 1]" "$WORK/stderr" ||
  fail "no warning of 2 rows: $(cat "$WORK/stderr")"
grep -qF "no figure" "$WORK/stderr" && fail "2 rows: the figure was refused"
[[ -e two_rows/sensitivity.dat ]] || fail "2 rows: no figure data"
"$PY" -c 'import json; assert "say little" in json.load(open("two_rows/summary.json"))["warning"]' ||
  fail "2 rows: summary.json's warning"
# a narrow law (a parameter share of ~0.06): the mean response's indices are
# wide, magnified by ~1 / share, and the warning says why, not "few rows"
run_ok sensitivity --k 40 --mu 'uniform(3,3.05)' --samples 1000 --no-figure -o narrow
grep -qF "warning: the Sobol' indices of E[R | theta] have 95 % intervals wider than [0, 1]" "$WORK/stderr" &&
  grep -qF "which is small (below 1/4)" "$WORK/stderr" ||
  fail "a small parameter share: $(cat "$WORK/stderr")"
checks=$((checks + 1))
# an unreachable --target-halfwidth: the study stops at --max-samples and
# says so (exit 0 and no word before); summary.json records the target
run_ok sensitivity --k 40 --mu 'uniform(2,7)' --lambda 'loguniform(0.5,10)' \
  --target-halfwidth 0.005 --min-samples 256 --max-samples 512 --no-figure -o capped
grep -qE "^stickslip: warning: the target 95 % half-width 0.005 was not reached within --max-samples 512 rows: the largest is [0-9.]+; raise --max-samples$" "$WORK/stderr" ||
  fail "an unmet --target-halfwidth: $(cat "$WORK/stderr")"
"$PY" -c 'import json; d = json.load(open("capped/summary.json")); assert d["target_halfwidth"] == 0.005 and d["target_met"] is False and "not reached" in d["warning"], d' ||
  fail "capped/summary.json"
checks=$((checks + 1))
# a met target: target_met true, and no warning
run_ok sensitivity --k 40 --mu 'uniform(2,7)' --target-halfwidth 0.3 --min-samples 64 --no-figure -o met
grep -qF "warning" "$WORK/stderr" && fail "a met target warned: $(cat "$WORK/stderr")"
"$PY" -c 'import json; d = json.load(open("met/summary.json")); assert d["target_met"] is True and "warning" not in d, d' ||
  fail "met/summary.json"
# a missed target beside a small share: both are said (the share's note hid it)
run_ok sensitivity --k 40 --mu 'uniform(3,3.05)' --target-halfwidth 0.05 --min-samples 256 \
  --max-samples 512 --no-figure -o narrow_target
grep -qF "which is small (below 1/4)" "$WORK/stderr" &&
  grep -qF "; the target 95 % half-width 0.05 was not reached within --max-samples 512 rows" "$WORK/stderr" ||
  fail "a missed target beside a small share: $(cat "$WORK/stderr")"
# a target above 1/2 is refused: an interval wider than [0, 1] could meet it
"$BIN" sensitivity --mu 'uniform(2,7)' --target-halfwidth 0.7 -o wide_target >/dev/null 2>"$WORK/stderr"
grep -qF "0 < H <= 0.5" "$WORK/stderr" && [[ ! -e wide_target ]] ||
  fail "--target-halfwidth 0.7: $(cat "$WORK/stderr")"
checks=$((checks + 3))
# merged shards give the same warning (they said nothing)
for i in 0 1; do
  run_ok sensitivity --k 40 --mu 'uniform(2,7)' --lambda 'loguniform(0.5,10)' --samples 2 \
    --block-size 1 --shard $i/2 -o two_shard$i
done
# (one shard alone: the missing one is named with the study's command)
"$BIN" merge two_shard0 -o two_half >/dev/null 2>"$WORK/stderr"
grep -qF "run the missing shards (\`stickslip sensitivity ... --shard i/n --resume -o DIR\`)" "$WORK/stderr" ||
  fail "merge of half a study: $(cat "$WORK/stderr")"
checks=$((checks + 1))
run_ok merge two_shard0 two_shard1 -o two_merged
expect_eq "merge's line for a study" "$(grep -F merged "$WORK/stderr")" \
  "merged 2 units from 2 journals (a sensitivity study; its figure: \`stickslip plot two_merged\`) -> two_merged"
grep -qF "warning: the Sobol' estimates of R from 2 rows say little" "$WORK/stderr" ||
  fail "merge of a 2-row study: no warning: $(cat "$WORK/stderr")"
checks=$((checks + 1))
# a resume with other --samples names the design's rows, not "realizations"
"$BIN" sensitivity --k 40 --mu 'uniform(2,7)' --lambda 'loguniform(0.5,10)' --samples 4 -o two_rows \
  --resume >/dev/null 2>"$WORK/stderr"
grep -qF "design: 2 rows (--samples) vs 4 rows (--samples)" "$WORK/stderr" ||
  fail "a study's mismatch: $(cat "$WORK/stderr")"
"$BIN" sensitivity --k 40 --mu 'uniform(2,7)' --lambda 'loguniform(0.5,10)' --target-halfwidth 0.3 \
  --min-samples 2 --max-samples 16 -o two_rows --resume >/dev/null 2>"$WORK/stderr"
grep -qF "design: 2 rows (--samples) vs a target half-width 0.3 in 2 to 16 rows (--target-halfwidth, --min-samples, --max-samples)" "$WORK/stderr" ||
  fail "a study's mismatch with a stop rule: $(cat "$WORK/stderr")"
run_ok sensitivity --k 40 --mu 'uniform(2,7)' --lambda 'loguniform(0.5,10)' --samples 1000 -o many
grep -qF "warning" "$WORK/stderr" && fail "1000 rows warned: $(cat "$WORK/stderr")"
checks=$((checks + 1))

# A statistic constant over the design (no damping: damping_power is 0):
# its mean 0 and variance 0, undefined indices (NaN) with a warning, and no
# figure. (It reported a NaN mean, exit 0 without a word.)
run_ok sensitivity --k 40 --mu 'uniform(2,7)' --lambda 'loguniform(0.5,10)' \
  --statistic damping_power --samples 64 -o constant
grep -qF "warning: damping_power is constant over the design's 64 rows (mean 0, variance 0)" "$WORK/stderr" ||
  fail "no warning of a constant statistic: $(cat "$WORK/stderr")"
checks=$((checks + 1))
"$PY" - <<'PY' || fail "summary.json of a constant statistic"
import json, math
d = json.load(open("constant/summary.json"))
assert d["mean"] == 0 and d["variance"] == 0, (d["mean"], d["variance"])
assert "constant over the design" in d["warning"]
assert all(i["first_order"] is None for i in d["indices"])
# the fixed parameters beside the laws (k = 40 was only in the command line)
b = d["base"]
assert b["k"] == 40 and b["ta"] == 50 and b["c"] == 0, b
assert b["mu"] is None and b["mu_s"] is None and b["lambda"] is None, b
# resolved_config's realizations are the design's rows, and it says so
import xarray as xr
config = xr.open_dataset("constant/sensitivity.nc").attrs["resolved_config"]
assert "realizations = 64  # the design's rows (--samples), 5 realizations each" in config, config
PY
[[ -e constant/sensitivity.png || -e constant/sensitivity.dat ]] && fail "a figure of undefined indices"
# With --target-halfwidth it stops at --min-samples: no number of rows gives
# 0 / 0 a half-width (it ran to --max-samples, 10^6 rows by default).
run_ok sensitivity --k 40 --mu 'uniform(2,7)' --lambda 'loguniform(0.5,10)' \
  --statistic damping_power --target-halfwidth 0.01 --min-samples 64 --block-size 32 -o constant_target
grep -qF "constant over the design's 64 rows" "$WORK/stderr" ||
  fail "--target-halfwidth of a constant statistic: $(cat "$WORK/stderr")"
expect_eq "rows of a constant statistic under --target-halfwidth" \
  "$("$PY" -c 'import json; print(json.load(open("constant_target/summary.json"))["samples"])')" "64"
# --resume of the finished study: nothing runs, and the warning is given again
run_ok sensitivity --k 40 --mu 'uniform(2,7)' --lambda 'loguniform(0.5,10)' \
  --statistic damping_power --samples 64 -o constant --resume
grep -qF "already holds this study's complete results" "$WORK/stderr" &&
  grep -qF "warning: damping_power is constant over the design" "$WORK/stderr" ||
  fail "--resume of a finished constant study: $(cat "$WORK/stderr")"
"$BIN" plot constant -o constant_plot >/dev/null 2>"$WORK/stderr"
expect_eq "exit of plot of undefined indices" "$?" "2"
grep -qF "every value is NaN (undefined): damping_power is constant" "$WORK/stderr" ||
  fail "plot of undefined indices: $(cat "$WORK/stderr")"
[[ -e constant_plot ]] && fail "plot of undefined indices wrote constant_plot/"

# --overwrite leaves nothing of the earlier run beside the new one: a study's
# figure under --no-figure, a sweep's files under a study and the other way
# round (a new user found them left).
run_ok sensitivity --k 40 --mu 'uniform(2,7)' --samples 64 -o over
# a study overwritten with its figure: the figure is drawn again, and not
# named as removed (a review: the note named all four figure files)
run_ok sensitivity --k 40 --mu 'uniform(2,7)' --samples 48 --overwrite -o over
grep -qF "removed" "$WORK/stderr" && fail "a redrawn figure named as removed: $(cat "$WORK/stderr")"
checks=$((checks + 1))
[[ -e over/sensitivity.dat ]] || fail "no figure data in over/"
run_ok sensitivity --k 40 --mu 'uniform(2,7)' --samples 32 --no-figure --overwrite -o over
expect_eq "files after --overwrite --no-figure" "$(ls over | tr '\n' ' ')" "sensitivity.nc summary.json "
# and names what it removed (it did so without a word)
# (the .png and .svg only where gnuplot rendered them)
grep -qE "^stickslip: note: removed 'over/sensitivity.dat', 'over/sensitivity.gp'(, 'over/sensitivity.png', 'over/sensitivity.svg')?: they were an earlier run's, which this run does not write$" "$WORK/stderr" ||
  fail "the note of removed outputs: $(cat "$WORK/stderr")"
checks=$((checks + 1))
run_ok sweep --lambda 1 --realizations 10 --records --overwrite -o over
expect_eq "files after a sweep over a study" "$(ls over | tr '\n' ' ')" \
  "records.csv results.nc summary.csv summary.json "
expect_eq "the note of a removed study" "$(grep -F 'removed' "$WORK/stderr")" \
  "stickslip: note: removed 'over/sensitivity.nc': it was an earlier run's, which this run does not write"
run_ok sensitivity --k 40 --mu 'uniform(2,7)' --samples 32 --no-figure --overwrite -o over
expect_eq "files after a study over a sweep" "$(ls over | tr '\n' ' ')" "sensitivity.nc summary.json "
# the refusal names every output an --overwrite would replace or remove
run_ok sweep --lambda 1 --realizations 5 -o listed
"$BIN" sensitivity --k 40 --mu 'uniform(2,7)' --samples 8 -o listed >/dev/null 2>"$WORK/stderr"
expect_eq "exit of a study into a sweep's directory" "$?" "2"
grep -qF "'listed/results.nc' already exists (the results of an earlier run), and so do 'listed/summary.json', 'listed/summary.csv': add --overwrite" "$WORK/stderr" ||
  fail "the refusal does not list every output: $(cat "$WORK/stderr")"
[[ -e listed/results.nc && ! -e listed/sensitivity.nc ]] || fail "a refused study changed listed/"
# a file named like a study's figure, in a directory without a study, is not ours
mkdir mine && echo "my own figure" >mine/sensitivity.png
run_ok sweep --lambda 1 --realizations 10 -o mine
[[ -e mine/sensitivity.png ]] || fail "a sweep removed a sensitivity.png it had not written"

finish
