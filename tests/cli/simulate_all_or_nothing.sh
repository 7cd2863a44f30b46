#!/usr/bin/env bash
# `simulate` writes all of its files or none, never replaces an
# earlier output silently (--overwrite to allow it), reports the system's
# reason for an unwritable path, and accepts --lambda 0 with given switch
# times (lambda plays no role then).
source "$(dirname "$0")/lib.sh" "$@"

# expect_code CODE ARGS...: exit code CODE (stderr kept in $WORK/stderr).
expect_code() {
  local code=$1; shift
  "$BIN" "$@" >"$WORK/stdout" 2>"$WORK/stderr"
  local rc=$?
  checks=$((checks + 1))
  [[ $rc -eq $code ]] || fail "'$*' -> exit $rc, expected $code: $(cat "$WORK/stderr")"
}
expect_stderr() {
  checks=$((checks + 1))
  grep -qF -- "$1" "$WORK/stderr" || fail "stderr lacks '$1': $(cat "$WORK/stderr")"
}

# A directory as --events-file: refused before anything is written.
expect_code 2 simulate --events --events-file /tmp -o ef/ep.csv
expect_stderr "--events-file: '/tmp'"
[[ ! -e ef ]] || fail "events-file=/tmp left ef/ behind: $(ls -R ef)"

# An unwritable trajectory file: the episode table is not left behind.
expect_code 3 simulate --trajectory 0.1 --trajectory-file /proc/nope/t.csv -o tf/ep.csv
expect_stderr "No such file or directory"
[[ ! -e tf ]] || fail "trajectory-file in /proc left tf/ behind: $(ls -R tf)"

# Unwritable -o: the system's reason, exit 3.
expect_code 3 simulate -o /proc/stickslip-nope.csv
expect_stderr "No such file or directory"
expect_code 3 simulate -o /proc/stickslip-nope/ep.csv
expect_stderr "No such file or directory"

# Two outputs on one path.
expect_code 2 simulate --events --events-file same.csv -o same.csv
expect_stderr "a file other than the one -o names"
[[ ! -e same.csv ]] || fail "same.csv written"

# No silent overwrite: -o, the events file next to stdout, the trajectory.
run_ok simulate --seed 3 -o keep/ep.csv
cp keep/ep.csv first.csv
expect_code 2 simulate --seed 4 -o keep/ep.csv
expect_stderr "'keep/ep.csv' already exists"
expect_stderr "--overwrite"
cmp -s keep/ep.csv first.csv || fail "refused run changed keep/ep.csv"
run_ok simulate --seed 4 -o keep/ep.csv --overwrite
cmp -s keep/ep.csv first.csv && fail "--overwrite did not replace keep/ep.csv"

run_ok simulate --events
[[ -s events.csv ]] || fail "simulate --events wrote no ./events.csv"
cp events.csv events.first
expect_code 2 simulate --events --seed 9
expect_stderr "'events.csv' already exists"
[[ ! -s stdout ]] || fail "refused run printed the table"
cmp -s events.csv events.first || fail "refused run changed ./events.csv"

run_ok simulate --trajectory 0.5 --trajectory-file tr.csv -o t1.csv
expect_code 2 simulate --trajectory 0.5 --trajectory-file tr.csv -o t2.csv
expect_stderr "'tr.csv' already exists"
[[ ! -e t2.csv ]] || fail "refused run wrote t2.csv"

# --lambda 0 with given switch times: accepted, lambda kept as given.
run_ok simulate --switch-times 1,2.5 --lambda 0 --format json
"$PY" - "$WORK/stdout" <<'PYEOF' || fail "lambda 0 with switch times"
import json, sys
doc = json.load(open(sys.argv[1]))
assert doc["parameters"]["lambda"] == 0, doc["parameters"]
assert doc["switch_times"] == "given"
assert doc["event_counts"]["belt_switch"] == 2, doc["event_counts"]
PYEOF
# ... and still refused without them.
expect_code 2 simulate --lambda 0
expect_stderr "lambda"

# Missing input files: exit 2, "does not exist".
expect_code 2 simulate --switch-times-file nope.txt
expect_stderr "'nope.txt' does not exist"
expect_code 2 sweep --config nope.toml -o o
expect_stderr "'nope.toml' does not exist"
[[ ! -e o ]] || fail "sweep with a missing config created o/"
finish
