#!/usr/bin/env bash
# --help shows the values of --belt-start, no "Excludes:" squeezed
# onto a metavar line, named metavars for `reproduce` (no TEXT/UINT), the
# summary line says "1 thread" (not "1 threads"), and `reproduce --quick` is
# announced as a demo.
source "$(dirname "$0")/lib.sh" "$@"

run_ok simulate --help
checks=$((checks + 1))
grep -qE -- '--belt-start LEVEL .*stationary' "$WORK/stdout" || fail "--belt-start help lacks stationary"
checks=$((checks + 1))
grep -q "Excludes:" "$WORK/stdout" && fail "simulate --help has an Excludes: text: $(grep Excludes "$WORK/stdout")"

run_ok reproduce --help
checks=$((checks + 1))
grep -qE '\b(TEXT|UINT)\b' "$WORK/stdout" && fail "reproduce --help has generic metavars: $(grep -E 'TEXT|UINT' "$WORK/stdout")"
for m in "-o,--output DIR" "--realizations N" "--seed S" "--threads T" "DEMO"; do
  checks=$((checks + 1))
  grep -qF -- "$m" "$WORK/stdout" || fail "reproduce --help lacks '$m'"
done

run_ok sweep --lambda 1 --realizations 10 --ta 5 --threads 1 -o one
checks=$((checks + 1))
grep -q "1 thread)" "$WORK/stderr" || fail "summary line: $(cat "$WORK/stderr")"
checks=$((checks + 1))
grep -q "1 threads" "$WORK/stderr" && fail "summary says '1 threads': $(cat "$WORK/stderr")"
finish
