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
finish
