#!/usr/bin/env bash
# Limit messages state the real limits (2^40 realizations, 100000
# bins), TOML errors carry file:line and shortest-form numbers, and the
# memory estimate is printed with a sensible number of digits.
source "$(dirname "$0")/lib.sh" "$@"

expect_fail "--realizations|1 to 2^40 = 1099511627776" sweep --realizations 1e9
expect_fail "--realizations|1 to 2^40" sweep --realizations 1099511627777
expect_fail "--bins|'0'|1 to 100000" sweep --bins 0
expect_fail "--bins|1 to 100000" sweep --bins 100001
expect_fail "--block-size|1 to 2^24 = 16777216" sweep --block-size 0

printf '[sweep]\nrealizations = 100.5\n' >r.toml
expect_fail "sweep.realizations at r.toml:2:|1 to 2^40" sweep --config r.toml
printf '[sweep]\nrealizations = 0\n' >r0.toml
expect_fail "sweep.realizations at r0.toml:2:|1 to 2^40" sweep --config r0.toml
printf '[initial]\nx0 = [1.0, -1.0]\n' >x0.toml
expect_fail "initial.x0 at x0.toml:2:|lo = 1 > hi = -1" sweep --config x0.toml
checks=$((checks + 1))
grep -qE '[0-9]\.[0-9]{6}' "$WORK/stderr" && fail "a %f-style number: $(cat "$WORK/stderr")"

# The memory estimate: at most 3 significant digits.
expect_fail "estimated memory" sweep --lambda lin:0.1:10:3000 --mu lin:0.1:10:3000 --realizations 1 --statistics all
checks=$((checks + 1))
grep -qE '[0-9]\.[0-9]{4,}' "$WORK/stderr" && fail "memory estimate with many digits: $(cat "$WORK/stderr")"

# reproduce: numbers are checked like sweep's, not wrapped ("-5" was read as
# 18446744073709551611 realizations).
expect_fail "--realizations|'-5'|2 to 2^40" reproduce --realizations -5 -o rp
expect_fail "--threads|'x'" reproduce --threads x -o rp
[[ ! -e rp ]] || fail "a refused reproduce created rp/"

# One realization on one point is said in the singular (a new user read
# "1 realizations").
run_ok sweep --lambda 1 --mu 5 --realizations 1 -o one
grep -qE '^1 realization in [0-9.e+-]+ s \(1 grid point, ' "$WORK/stderr" ||
  fail "the singular: $(cat "$WORK/stderr")"
finish
