#!/usr/bin/env bash
# `--resume` on a directory that holds finished outputs and
# no journal never replaces them. Another configuration's results are refused
# (exit 2, naming the directory, saying it holds a finished run of another
# configuration and what to do); this configuration's are "already complete"
# and left byte-identical with their modification times; --overwrite still
# replaces; a directory with no outputs starts afresh.
source "$(dirname "$0")/lib.sh" "$@"
A=(--lambda 3,4,5 --mu 1,2 --seed 5 --ta 5 --realizations 20 --block-size 10 --threads 1)
B=(--lambda 1,2 --seed 9 --ta 5 --realizations 20 --block-size 10 --threads 1)

snapshot() {  # contents and mtimes of every file in $1
  (cd "$1" && for f in *; do printf '%s %s %s\n' "$f" "$(stat -c %Y.%y "$f")" "$(cksum <"$f")"; done)
}

run_ok sweep "${A[@]}" -o d
[[ ! -e d/.journal ]] || fail "a finished sweep left its journal"
before=$(snapshot d)
sleep 1.1  # so that a rewrite would change the modification times

# Another configuration with --resume: refused, nothing touched.
"$BIN" sweep "${B[@]}" -o d --resume >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of --resume onto another configuration's finished run" "$?" "2"
for phrase in "'d'" "finished run of another configuration" "grid axes: 2 vs 1" "--overwrite" \
              "another -o DIR"; do
  checks=$((checks + 1))
  grep -qF -- "$phrase" "$WORK/stderr" || fail "stderr lacks '$phrase': $(cat "$WORK/stderr")"
done
checks=$((checks + 1))
grep -qF "starting from the beginning" "$WORK/stderr" && fail "it still says it starts afresh"
expect_eq "d after the refused --resume" "$(snapshot d)" "$before"
[[ ! -e d/.journal ]] || fail "the refused --resume left a journal"

# A change that only the seed makes is another configuration too.
"$BIN" sweep "${A[@]}" --seed 6 -o d --resume >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of --resume with another seed" "$?" "2"
checks=$((checks + 1))
grep -qF "seed" "$WORK/stderr" || fail "the refusal does not name the seed: $(cat "$WORK/stderr")"

# The same configuration with --resume: already complete, untouched. Flags
# that do not change results (threads, engine) do not matter.
run_ok sweep "${A[@]}" -o d --resume
checks=$((checks + 1))
grep -qF "already holds the complete results of this configuration" "$WORK/stderr" ||
  fail "no 'already complete' report: $(cat "$WORK/stderr")"
expect_eq "d after --resume of the finished configuration" "$(snapshot d)" "$before"
run_ok sweep "${A[@]:0:${#A[@]}-2}" --threads 2 --engine reference -o d --resume
expect_eq "d after --resume with other threads and engine" "$(snapshot d)" "$before"
[[ ! -e d/.journal ]] || fail "--resume of a finished run left a journal"

# The same configuration, but the set is not whole: refused, not recomputed.
cp -p -r d partial && rm partial/summary.csv
"$BIN" sweep "${A[@]}" -o partial --resume >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of --resume onto an incomplete set" "$?" "2"
checks=$((checks + 1))
grep -qF "summary.csv' is missing" "$WORK/stderr" || fail "incomplete set: $(cat "$WORK/stderr")"

# Outputs whose configuration cannot be read (no results.nc): refused.
mkdir other && echo "lambda,R" >other/summary.csv
"$BIN" sweep "${B[@]}" -o other --resume >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of --resume onto unidentifiable outputs" "$?" "2"
expect_eq "other/summary.csv after the refusal" "$(cat other/summary.csv)" "lambda,R"

# --overwrite with --resume replaces them, as asked.
run_ok sweep "${B[@]}" -o d --resume --overwrite
checks=$((checks + 1))
[[ "$(snapshot d)" != "$before" ]] || fail "--resume --overwrite did not replace the results"

# No outputs and no journal: --resume starts from the beginning.
run_ok sweep "${B[@]}" -o fresh --resume
[[ -s fresh/results.nc ]] || fail "--resume into an empty directory wrote no results"
checks=$((checks + 1))
grep -qF "starting from the beginning" "$WORK/stderr" || fail "no note: $(cat "$WORK/stderr")"

# A shard resumed into a finished run of another configuration: refused too.
"$BIN" sweep "${B[@]}" --shard 0/2 -o fresh2 >/dev/null 2>&1
"$BIN" sweep "${A[@]}" --shard 0/2 -o d --resume >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of a shard --resume onto another configuration's run" "$?" "2"
[[ ! -e d/.journal ]] || fail "the refused shard left a journal"
finish
