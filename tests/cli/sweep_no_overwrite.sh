#!/usr/bin/env bash
# `sweep -o DIR` on a folder that holds finished results refuses to
# replace them (naming the file and the ways on: --overwrite, --resume, another
# -o), leaves them untouched, and replaces them with --overwrite.
source "$(dirname "$0")/lib.sh" "$@"
A=(--lambda 0.5,2 --mu 5 --ta 5 --realizations 20 --block-size 10 --threads 1)

run_ok sweep "${A[@]}" -o out
cp out/summary.csv first.csv
"$BIN" sweep "${A[@]}" --seed 2 -o out >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of a sweep onto finished results" "$?" "2"
for phrase in "out/results.nc' already exists" "--overwrite" "--resume"; do
  checks=$((checks + 1))
  grep -qF -- "$phrase" "$WORK/stderr" || fail "stderr lacks '$phrase': $(cat "$WORK/stderr")"
done
cmp -s out/summary.csv first.csv || fail "the refused sweep changed out/summary.csv"
[[ ! -e out/.journal ]] || fail "the refused sweep left a journal"

run_ok sweep "${A[@]}" --seed 2 -o out --overwrite
cmp -s out/summary.csv first.csv && fail "--overwrite did not replace the results"
grep -qF "removed" "$WORK/stderr" && fail "a note of removed outputs where none was: $(cat "$WORK/stderr")"
# records.csv of an earlier --records run goes, and is named
run_ok sweep "${A[@]}" --records -o out --overwrite
run_ok sweep "${A[@]}" -o out --overwrite
[[ -e out/records.csv ]] && fail "--overwrite without --records left the earlier records.csv"
expect_eq "the note of a removed records.csv" "$(grep -F 'removed' "$WORK/stderr")" \
  "stickslip: note: removed 'out/records.csv': it was an earlier run's, which this run does not write"

# A folder with other files but no results is fine.
mkdir other && touch other/notes.txt
run_ok sweep "${A[@]}" -o other
[[ -s other/summary.csv && -e other/notes.txt ]] || fail "sweep into a folder with other files"

# Duplicate grid values are refused.
expect_fail "grid axis lambda|each value once|#1 and #2" sweep --lambda 1,1 --realizations 10
expect_fail "grid axis mu|#1 and #3" sweep --mu 5,7,5 --realizations 10
finish
