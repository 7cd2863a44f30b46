# The precision flags of sweep: --common-random-numbers (recorded in summary.json,
# results.nc and the journal fingerprint; replayable with `simulate
# --common-random-numbers`) and --target-ci STAT:HALFWIDTH (every point meets
# the target; identical outputs for any thread count), and their bad input.
source "$(dirname "$0")/lib.sh"

grid=(--k 40 --mu 0.5,5 --lambda log:0.1:30:10)
for t in 1 2; do
  run_ok sweep "${grid[@]}" --target-ci R:0.002 --statistics paper,derivatives --threads "$t" \
    -o "tci$t"
done
cmp -s tci1/summary.csv tci2/summary.csv || fail "summary.csv differs between --threads 1 and 2"
grep -qF "did not reach the target" "$WORK/stderr" && fail "a met target warned: $(cat "$WORK/stderr")"
# An unreachable target: every point stops at its cap, and the run says so
# (it ended with exit 0 and no word), naming the widest point.
run_ok sweep --k 40 --lambda 1,10 --mu 2,5 --target-ci R:0.0001 --max-realizations 2000 \
  --min-realizations 100 -o unmet
grep -qE "^stickslip: warning: 4 of 4 grid points did not reach the target 95 % half-width 0.0001 of the mean of R within the cap of 2000 realizations per point \(the widest: [0-9.e-]+, at lambda = [0-9.]+, mu = [0-9.]+\); raise the cap, or read" "$WORK/stderr" ||
  fail "an unmet --target-ci: $(cat "$WORK/stderr")"
checks=$((checks + 1))
# The outputs keep the same text (results.nc's warning attribute,
# summary.json's "warning"), and a --resume that finds the run finished
# says it again (it said only "nothing to do"); a met target's outputs
# have none.
warned=$(grep '^stickslip: warning: ' "$WORK/stderr")
run_ok sweep --k 40 --lambda 1,10 --mu 2,5 --target-ci R:0.0001 --max-realizations 2000 \
  --min-realizations 100 -o unmet --resume
grep -qF "already holds the complete results" "$WORK/stderr" || fail "not a finished resume: $(cat "$WORK/stderr")"
[[ $(grep '^stickslip: warning: ' "$WORK/stderr") == "$warned" ]] ||
  fail "the finished --resume did not say the warning again: $(cat "$WORK/stderr")"
"$PY" - "${warned#stickslip: warning: }" <<'PY' || fail "the unmet target's warning in the outputs"
import json, sys, xarray as xr
note = sys.argv[1]
assert json.load(open("unmet/summary.json"))["warning"] == note
assert xr.open_dataset("unmet/results.nc").attrs["warning"] == note
assert "warning" not in json.load(open("tci1/summary.json"))
assert "warning" not in xr.open_dataset("tci1/results.nc").attrs
PY
"$PY" - <<'PY' || fail "target CI checks"
import json, sys
docs = [json.load(open(f"tci{t}/summary.json")) for t in (1, 2)]
assert docs[0]["points"] == docs[1]["points"], "points differ between --threads 1 and 2"
par = docs[0]["parameters"]
assert par["target_ci"] == {"statistic": "R", "halfwidth": 0.002, "min_realizations": 1000,
                            "max_realizations": 1000000}, par["target_ci"]
assert par["common_random_numbers"] is False
ns = set()
for p in docs[0]["points"]:
    lo, hi = p["R"]["ci95"]
    assert (hi - lo) / 2 <= 0.002, p
    assert 1000 <= p["realizations"] < 1000000 and p["realizations"] % 50 == 0, p
    ns.add(p["realizations"])
assert len(ns) > 3, f"the realizations are chosen per point: {sorted(ns)}"
PY
if command -v ncdump >/dev/null; then
  ncdump -h tci1/results.nc | grep -q 'target_ci_halfwidth = 0.002' || fail "nc lacks target_ci_halfwidth"
  ncdump -h tci1/results.nc | grep -q 'stick_fraction_dmean_dlambda(' || fail "nc lacks the score derivative"
fi

# Common random numbers: recorded, and a realization replays with the flag.
run_ok sweep --k 40 --mu 5 --lambda 1,3.8 --realizations 60 --records --seed 9 \
  --common-random-numbers -o crn
"$PY" - <<'PY' || fail "CRN records"
import csv, json
par = json.load(open("crn/summary.json"))["parameters"]
assert par["common_random_numbers"] is True, par
rows = list(csv.DictReader(open("crn/records.csv")))
by = {}
for r in rows:
    by.setdefault(r["realization"], set()).add((r["x0"], r["xdot0"], r["belt_start"]))
assert all(len(v) == 1 for v in by.values()), "points do not share the initial state"
PY
if command -v ncdump >/dev/null; then
  ncdump -h crn/results.nc | grep -q 'common_random_numbers = 1' || fail "nc lacks common_random_numbers"
fi
r_sweep=$("$PY" -c '
import csv
rows = [r for r in csv.DictReader(open("crn/records.csv")) if r["realization"] == "17" and float(r["lambda"]) == 3.8]
print(float(rows[0]["stick_fraction"]))')
run_ok simulate --k 40 --mu 5 --lambda 3.8 --seed 9 --realization 17 --common-random-numbers \
  --format json -o one.json
r_one=$("$PY" -c 'import json; print(float(json.load(open("one.json"))["statistics"]["stick_fraction"]))')
expect_eq "R of realization 17 replayed with --common-random-numbers" "$r_one" "$r_sweep"
run_ok simulate --k 40 --mu 5 --lambda 3.8 --seed 9 --realization 17 --format json -o own.json
r_own=$("$PY" -c 'import json; print(float(json.load(open("own.json"))["statistics"]["stick_fraction"]))')
[[ $r_own != "$r_sweep" ]] || fail "without the flag the point's own streams give another realization"

# The flag is part of the journal's identity: resuming without it is refused.
"$BIN" sweep --k 40 --mu 5 --lambda 1,3.8 --realizations 60 --seed 9 --common-random-numbers \
  --keep-journal -o kept >/dev/null 2>&1 || fail "sweep --keep-journal"
"$BIN" sweep --k 40 --mu 5 --lambda 1,3.8 --realizations 60 --seed 9 --resume -o kept \
  >/dev/null 2>stderr && fail "resume without --common-random-numbers was accepted"
grep -qi "common random numbers" stderr || fail "resume refusal does not name the flag: $(cat stderr)"

# The CRN slopes follow the selection: R's only with --statistics R,derivatives.
run_ok sweep --k 40 --mu 5 --lambda 1,3.8 --realizations 60 --seed 9 --common-random-numbers \
  --records --statistics R,derivatives -o crn_r
vars=$(ncdump -h crn_r/results.nc)
grep -q 'stick_fraction_dmean_dlambda_crn(' <<<"$vars" || fail "no CRN slope of R"
grep -q 'sticks_per_time_dmean_dlambda_crn(' <<<"$vars" && fail "a CRN slope of an unselected mean"
"$PY" -c '
import json; p = json.load(open("crn_r/summary.json"))["points"][0]
assert list(p["crn_slopes"]["lambda"]) == ["R"], p["crn_slopes"]' || fail "summary.json CRN slopes"
checks=$((checks + 1))

expect_fail "--target-ci|STAT:HALFWIDTH" sweep --mu 5 --lambda 1 --target-ci R
expect_fail "--target-ci|stick_duration" sweep --mu 5 --lambda 1 --target-ci stick_duration:0.1
expect_fail "--target-ci|> 0" sweep --mu 5 --lambda 1 --target-ci R:-1
expect_fail "--max-realizations|--target-ci" sweep --mu 5 --lambda 1 --max-realizations 100
expect_fail "--realizations|--max-realizations" sweep --mu 5 --lambda 1 --target-ci R:0.01 --realizations 100
# A cap below the default minimum names the default and the flag to give.
expect_fail "invalid --min-realizations: '1000 (the default)'|2 .. --max-realizations (500): give --min-realizations too" \
  sweep --mu 5 --lambda 1 --target-ci R:0.01 --max-realizations 500
expect_fail "invalid --min-realizations: '600'|2 .. --max-realizations (500))" \
  sweep --mu 5 --lambda 1 --target-ci R:0.01 --max-realizations 500 --min-realizations 600
run_ok sweep --mu 5 --lambda 1 --target-ci R:0.01 --max-realizations 500 --min-realizations 400 \
  --threads 1 -o "$WORK/capped_min"
expect_fail "invalid --min-realizations: '1000 (the default)'|2 .. --max-realizations (1): raise --max-realizations" \
  sweep --mu 5 --lambda 1 --target-ci R:0.01 --max-realizations 1
# A cap from the configuration is named as such (the review: it was called
# --max-realizations, which the user never gave).
printf '[model]\nmu = 5.0\n\n[sweep]\nrealizations = 400\n' >"$WORK/cap400.toml"
expect_fail "invalid --min-realizations: '1000 (the default)'|2 .. the configuration's realizations (400): give --min-realizations too" \
  sweep --config "$WORK/cap400.toml" --target-ci R:0.01
printf '[model]\nmu = 5.0\n\n[sweep]\nrealizations = 400\ntarget_ci = "R:0.01"\n' >"$WORK/target400.toml"
expect_fail "invalid min_realizations: '1000'|lower min_realizations (1000 unless given) or raise the maximum" \
  sweep --config "$WORK/target400.toml"

finish
