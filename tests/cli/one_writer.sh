#!/usr/bin/env bash
# One writer per output directory (io/output_lock.hpp). While a sweep runs
# in D, every second writer of D is refused at once with exit 2 and a message
# naming the first (its command and pid), and touches nothing: sweep,
# sweep --resume, merge -o D, reproduce -o D. A run killed with -9 leaves no
# lock behind: --resume continues it and gives the outputs of an
# uninterrupted run. Shards of one directory run side by side.
source "$(dirname "$0")/lib.sh" "$@"
LONG=(--lambda 1,2,3,4 --mu 1,2 --realizations 60000 --block-size 500 --seed 3 --threads 1
      --checkpoint-interval 0.2)

# start_long DIR: a long sweep into DIR in the background; waits until it
# holds the lock (its line is in the lock file). Sets $first.
start_long() {
  "$BIN" sweep "${LONG[@]}" -o "$1" >"$WORK/first.out" 2>"$WORK/first.err" &
  first=$!
  for _ in $(seq 1 200); do
    [[ -s $1/.stickslip.lock ]] && return 0
    sleep 0.05
  done
  fail "the first sweep never took the lock of $1"
}

# refused WHAT ARGS...: exits 2 at once, naming the first writer.
refused() {
  local what=$1
  shift
  local t0=$SECONDS
  "$BIN" "$@" >"$WORK/stdout" 2>"$WORK/stderr"
  expect_eq "exit code of $what" "$?" "2"
  checks=$((checks + 1))
  grep -qF "is in use by stickslip sweep (pid $first on host " "$WORK/stderr" ||
    fail "$what does not name the first writer (pid $first): $(cat "$WORK/stderr")"
  checks=$((checks + 1))
  ((SECONDS - t0 <= 5)) || fail "$what took $((SECONDS - t0)) s to be refused"
}

start_long d
refused "a second sweep" sweep --lambda 1 --realizations 10 --overwrite -o d
refused "a second sweep with --resume" sweep "${LONG[@]}" --resume -o d
refused "merge into the running sweep's directory" merge e -o d
refused "reproduce into the running sweep's directory" reproduce --quick --no-figures --overwrite -o d
checks=$((checks + 1))
kill -0 "$first" 2>/dev/null || fail "the first sweep died while others were refused"
[[ -d d/.journal ]] || fail "the first sweep's journal is gone"

# kill -9: the kernel releases the lock; --resume finishes the run.
sleep 0.5
kill -9 "$first"
wait "$first" 2>/dev/null
run_ok sweep "${LONG[@]}" --resume -o d
run_ok sweep "${LONG[@]}" -o solo
expect_eq "summary.csv after kill -9 and --resume" "$(cksum <d/summary.csv)" "$(cksum <solo/summary.csv)"

# Shards of one directory (as a job array with --resume writes them) do not
# block each other; a whole run beside them is refused, naming them.
SH=(--lambda 1,2,3,4 --mu 1,2 --realizations 60000 --block-size 500 --seed 3 --threads 1)
"$BIN" sweep "${SH[@]}" --shard 0/2 --resume -o s >"$WORK/s0.out" 2>"$WORK/s0.err" &
s0=$!
for _ in $(seq 1 200); do [[ -s s/.stickslip-shard-0-of-2.lock ]] && break; sleep 0.05; done
"$BIN" sweep "${SH[@]}" -o s --resume >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of a whole run beside a running shard" "$?" "2"
checks=$((checks + 1))
grep -qF -- "--shard 0/2 (pid $s0" "$WORK/stderr" || fail "the refusal does not name shard 0: $(cat "$WORK/stderr")"
checks=$((checks + 1))
kill -0 "$s0" 2>/dev/null || fail "shard 0 was not running when shard 1 started (too short to tell)"
run_ok sweep "${SH[@]}" --shard 1/2 --resume -o s
wait "$s0"
expect_eq "exit code of shard 0" "$?" "0"
run_ok merge s -o merged
run_ok sweep "${SH[@]}" -o whole
expect_eq "summary.csv of the shards run side by side" "$(cksum <merged/summary.csv)" "$(cksum <whole/summary.csv)"

finish
