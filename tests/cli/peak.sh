# `stickslip peak`: the JSON fields, the same result for any thread count,
# and bad input (exit 2, the flag, the value and the allowed range, nothing
# on stdout).
source "$(dirname "$0")/lib.sh"

# A small problem (t_a = 10, a coarse target) so that it runs in a second.
args=(peak --mu 5 --k 40 --ta 10 --range 0.3:30 --target-halfwidth 0.3
      --initial-realizations 200 --format json)
run_ok "${args[@]}" --threads 1 && cp "$WORK/stdout" one.json
run_ok "${args[@]}" --threads 2 && cp "$WORK/stdout" two.json
"$PY" - one.json two.json <<'PY' || fail "peak JSON"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for key in ("argmax", "argmax_ci95", "max", "max_ci95", "realizations", "elapsed_seconds",
            "target_met", "statistic", "over"):
    assert key in a, key
lo, hi = a["argmax_ci95"]
assert lo <= a["argmax"] <= hi, a
assert (hi - lo) / 2 <= 0.3 * (1 + 1e-12) and a["target_met"] is True, a
mlo, mhi = a["max_ci95"]
assert mlo <= a["max"] <= mhi and 0 < a["max"] < 1, a
assert isinstance(a["realizations"], int) and a["realizations"] > 0, a
assert a["statistic"] == "R" and a["over"] == "lambda", a
assert a["method"] == "score", a  # the default (auto): score, as over lambda for R
# Any thread count: the same numbers, bit for bit (only the timings differ).
for key in a:
    if key not in ("elapsed_seconds", "cpu_seconds"):
        assert a[key] == b[key], (key, a[key], b[key])
PY
pass

# --progress: one line per stage on stderr with the window, the realizations
# and the estimate; stdout (the JSON) is the same as without it.
"$BIN" "${args[@]}" --threads 2 --progress >prog.json 2>prog.err || fail "peak --progress"
grep -qE "^peak: stage 1: lambda in \[[0-9.]+, [0-9.]+\] at 3 points, \+[0-9.e+]+ realizations" prog.err \
  || fail "peak --progress stage line: $(head -c 300 prog.err)"
grep -qE "lambda\* = [0-9.]+ \+- [0-9.e-]+ \(sampling" prog.err || fail "peak --progress estimate: $(cat prog.err)"
"$PY" - one.json prog.json <<'PY' || fail "peak --progress changed the result"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
assert all(a[k] == b[k] for k in a if k not in ("elapsed_seconds", "cpu_seconds")), (a, b)
PY
"$BIN" "${args[@]}" --threads 2 >/dev/null 2>quiet.err
[[ ! -s quiet.err ]] || fail "peak without --progress and no terminal wrote to stderr: $(cat quiet.err)"
pass

# The earlier method (independent streams per point) is still there.
run_ok "${args[@]}" --method independent --threads 2 && cp "$WORK/stdout" ind.json
"$PY" - ind.json <<'PY' || fail "peak --method independent"
import json, sys
a = json.load(open(sys.argv[1]))
assert a["method"] == "independent" and a["target_met"] is True, a
lo, hi = a["argmax_ci95"]
assert lo <= a["argmax"] <= hi and (hi - lo) / 2 <= 0.3 * (1 + 1e-12), a
PY

# --method score (the root of the causal score derivative, 3 points per
# stage; the default here): the same result for any thread count and as
# the default's, the interval around the estimate and within the target,
# and the same peak as --method common's.
run_ok "${args[@]}" --method common --threads 2 && cp "$WORK/stdout" common.json
run_ok "${args[@]}" --method score --threads 1 && cp "$WORK/stdout" score1.json
"$BIN" "${args[@]}" --method score --threads 2 --progress >score2.json 2>score.err \
  || fail "peak --method score --progress"
grep -qE "^peak: stage 1: lambda in \[[0-9.]+, [0-9.]+\] at 3 points" score.err \
  || fail "peak --method score --progress: $(head -c 300 score.err)"
"$PY" - score1.json score2.json common.json one.json <<'PY' || fail "peak --method score"
import json, sys
a, b, common, default = (json.load(open(p)) for p in sys.argv[1:5])
assert common["method"] == "common" and common["target_met"] is True, common
assert a["method"] == "score" and a["target_met"] is True, a
lo, hi = a["argmax_ci95"]
assert lo <= a["argmax"] <= hi and (hi - lo) / 2 <= 0.3 * (1 + 1e-12), a
for key in a:
    if key not in ("elapsed_seconds", "cpu_seconds"):
        assert a[key] == b[key] == default[key], (key, a[key], b[key], default[key])
# The same peak as the common method's, within both intervals.
clo, chi = common["argmax_ci95"]
assert max(lo, clo) <= min(hi, chi), (a["argmax_ci95"], common["argmax_ci95"])
PY
pass

# Bad input: exit 2, the flag, the value, the allowed values; nothing on stdout.
expect_peak_error() {
  local phrases=$1
  shift
  expect_fail "$phrases" peak "$@"
  "$BIN" peak "$@" >"$WORK/stdout" 2>/dev/null
  expect_eq "exit status of peak $*" "$?" 2
  expect_eq "stdout of failed peak $*" "$(cat "$WORK/stdout")" ""
}
expect_peak_error "--target-halfwidth|-1|> 0" --target-halfwidth -1
expect_peak_error "--target-halfwidth|'abc'" --target-halfwidth abc
expect_peak_error "--range (upper end)|1|> the lower end 5" --range 5:1
expect_peak_error "--range (lower end)|0|> 0" --range 0:5
expect_peak_error "--range|'3'|LO:HI" --range 3
expect_peak_error "--statistic|'D'|R, sticks_per_time" --statistic D
expect_peak_error "--over|'omega'|lambda" --over omega
expect_peak_error "--range|required unless --over lambda" --over mu
expect_peak_error "--lambda|'2'|--over lambda" --lambda 2
expect_peak_error "--initial-realizations|'1'" --initial-realizations 1
expect_peak_error "mu (friction coefficient)|0|> 0" --mu 0
expect_peak_error "upper end|widen the range" --mu 5 --k 40 --ta 10 --range 0.05:0.3 \
  --initial-realizations 200
expect_peak_error "--method|newton|auto,score,common,independent" --method newton
expect_peak_error "over|'mu'|lambda with the score method" --method score --over mu --range 1:9
expect_peak_error "statistic|'sticks_per_time'|R with the score method" --method score \
  --statistic sticks_per_time
expect_peak_error "method|'score'|Poisson switching" --method score --belt-rates 1,2

finish
