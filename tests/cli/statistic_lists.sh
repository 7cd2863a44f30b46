#!/usr/bin/env bash
# The statistics a precision tool accepts are one list
# from the schema, with the same names in every command's help and errors
# (`sweep --target-ci`, `peak --statistic`); every name in it is accepted;
# and a refused --shard is named as the user typed it.
source "$(dirname "$0")/lib.sh" "$@"

# The list after "$1" up to the closing ")" of the line.
list_in() { sed -n "s/.*$1\(.*\)).*/\1/p" | head -1; }

"$BIN" sweep --help >help_sweep 2>&1
"$BIN" peak --help >help_peak 2>&1
"$BIN" sweep --target-ci nosuch:0.1 -o x 2>err_sweep
"$BIN" peak --statistic nosuch 2>err_peak
sweep_help=$(grep -- '--target-ci' help_sweep | sed -n 's/.*mean of STAT (\(.*\)) is <= HALFWIDTH.*/\1/p')
peak_help=$(grep -- '--statistic' help_peak | sed -n 's/.*whose mean is maximized: \(.*\) (default R).*/\1/p')
sweep_err=$(list_in 'one value per realization: ' <err_sweep)
peak_err=$(list_in 'one value per realization: ' <err_peak)

checks=$((checks + 1))
[[ -n $sweep_err && $sweep_err == *R*sticks_per_time* ]] || fail "no list in: $(cat err_sweep)"
expect_eq "sweep --target-ci: help against error" "$sweep_help" "$sweep_err"
expect_eq "peak --statistic: help against error" "$peak_help" "$peak_err"
expect_eq "peak --statistic against sweep --target-ci" "$peak_err" "$sweep_err"

# Every listed name is accepted by both (a cheap run each).
IFS=', ' read -r -a names <<<"$sweep_err"
for s in "${names[@]}"; do
  run_ok sweep --lambda 1 --ta 5 --target-ci "$s:1e9" --min-realizations 20 \
    --max-realizations 40 --block-size 20 --threads 1 --statistics "$s" -o "t_$s"
  "$BIN" peak --statistic "$s" --range 0.5:2 --initial-realizations 20 --max-realizations 100 \
    --ta 2 --threads 1 >/dev/null 2>peak_err
  checks=$((checks + 1))
  grep -q "invalid --statistic" peak_err && fail "peak refuses listed statistic $s: $(cat peak_err)"
done

# --shard is named as typed, not by its internal journal tag.
"$BIN" sweep --target-ci R:0.1 --shard 0/2 -o sh >/dev/null 2>err_shard
expect_eq "exit code of --shard with --target-ci" "$?" "2"
checks=$((checks + 1))
grep -qF -- "--shard: '0/2'" err_shard || fail "the shard is not named as typed: $(cat err_shard)"
grep -qF "shard-0-of-2" err_shard && fail "the internal shard tag is shown: $(cat err_shard)"
finish
