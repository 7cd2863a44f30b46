#!/usr/bin/env bash
# A file flag of `simulate` without the output it names is refused (exit 2,
# naming both flags, nothing written) instead of silently ignored:
# --events-file without --events (or with --format json, where the events go
# into the JSON), --trajectory-file without --trajectory. With its flag, the
# file is written.
source "$(dirname "$0")/lib.sh" "$@"

# expect_refused PHRASE ARGS...: exit 2, PHRASE on stderr, no file and no stdout.
expect_refused() {
  local phrase=$1; shift
  "$BIN" "$@" >"$WORK/stdout" 2>"$WORK/stderr"
  local rc=$?
  checks=$((checks + 1))
  [[ $rc -eq 2 ]] || fail "'$*' -> exit $rc, expected 2: $(cat "$WORK/stderr")"
  grep -qF -- "$phrase" "$WORK/stderr" || fail "stderr of '$*' lacks '$phrase': $(cat "$WORK/stderr")"
  [[ ! -s $WORK/stdout ]] || fail "'$*' printed a table although refused"
  [[ -z $(ls "$WORK/out" 2>/dev/null) ]] || fail "'$*' wrote $(ls "$WORK/out")"
}

expect_refused "invalid --events-file: 'out/x.csv' (allowed: only together with --events" \
  simulate --ta 5 --events-file out/x.csv
[[ ! -e x.csv && ! -e events.csv ]] || fail "events written without --events"
expect_refused "invalid --events-file: 'out/x.csv' (allowed: only together with --events" \
  simulate --ta 5 --events-file out/x.csv -o out/ep.csv
expect_refused "invalid --events-file: 'out/x.csv' (allowed: only with --format csv" \
  simulate --ta 5 --events --format json --events-file out/x.csv -o out/ep.json
expect_refused "invalid --trajectory-file: 'out/t.csv' (allowed: only together with --trajectory" \
  simulate --ta 5 --trajectory-file out/t.csv -o out/ep.csv

# With their flags, the named files are written.
run_ok simulate --ta 5 --events --events-file out/x.csv --trajectory 0.5 --trajectory-file out/t.csv
expect_eq "events header" "$(head -1 out/x.csv 2>/dev/null)" "kind,time,x,xdot,v"
expect_eq "trajectory header" "$(head -1 out/t.csv 2>/dev/null)" "t,x,xdot,v,mode"
finish
