#!/usr/bin/env bash
# When stderr is on the disk that is full (a batch job's log beside its
# outputs), a failed write still exits with its own code (3), not with an
# abort (134) from the error message that cannot be printed. `ulimit -f 0`
# makes every write fail with EFBIG, stderr's included.
source "$(dirname "$0")/lib.sh" "$@"
(ulimit -f 0; exec "$BIN" sweep --lambda 1 --realizations 10 -o d) 2>"$WORK/err.txt"
expect_eq "exit code of a sweep whose outputs and stderr cannot be written" "$?" "3"
(ulimit -f 0; exec "$BIN" sweep --lambda -1 -o d2) 2>"$WORK/err2.txt"
expect_eq "exit code of bad input whose message cannot be printed" "$?" "2"
# Room for the journal's header but not for all its segments (one after
# every unit): the error says what the journal keeps and how to go on (a new
# user found no advice). Several limits, since the sizes may change.
advised=0
for limit in 3 4 5 6; do
  rm -rf "d$limit"
  (ulimit -f $limit; exec "$BIN" sweep --lambda log:0.1:30:40 --mu 0.5,5 --realizations 200 \
     --checkpoint-interval 0 -o "d$limit") 2>"$WORK/err$limit.txt"
  expect_eq "exit code of a sweep under ulimit -f $limit" "$?" "3"
  grep -q "\.journal/seg-.*File too large; the journal keeps the units of its earlier segments, if any: make room and rerun with --resume" \
    "$WORK/err$limit.txt" && advised=$((advised + 1))
done
expect_eq "limits at which a journal segment failed with the advice" "$((advised > 0))" "1"
finish
