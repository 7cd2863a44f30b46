#!/usr/bin/env bash
# `mpirun -np P stickslip sweep` (P = 1, 2, 4; oversubscribed; loopback and
# shared memory only; root-safe) must write the same results as the plain
# single-process run, also when resuming a journal under MPI.
#   mpi_cli.sh MPIRUN STICKSLIP WORKDIR
set -uo pipefail
mpirun=$1; bin=$2; work=$3
here=$(cd "$(dirname "$0")" && pwd)
compare="/usr/bin/python3 $here/../resume/compare_outputs.py"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
launch=("$mpirun" --oversubscribe --mca btl self,vader --mca btl_vader_single_copy_mechanism none)
fail() { echo "mpi_cli: FAILED: $*" >&2; exit 1; }
# Runs `mpirun -np 2 stickslip ARGS --threads 1 -o DIR` (stderr in DIR.err),
# sends SIGUSR1 once its journal has a first segment, and fails unless the
# run ended early; its exit status is left in $rc. A watchdog ends a hung run.
usr1_mid_run() {
  local dir=$1 what=$2; shift 2
  "${launch[@]}" -np 2 "$bin" "$@" --threads 1 -o "$dir" 2>"$dir.err" & local pid=$!
  ( sleep 120; kill -KILL $pid ) >/dev/null 2>&1 & local watchdog=$!
  for _ in $(seq 300); do  # signal once the first journal segment is written
    compgen -G "$dir/.journal/seg-*" >/dev/null && break
    sleep 0.05
  done
  kill -USR1 $pid
  wait $pid; rc=$?
  pkill -P $watchdog 2>/dev/null; kill $watchdog 2>/dev/null  # and its sleep
  ((rc != 0)) || fail "$what: the sweep finished before the signal (make it longer)"
}
rm -rf "$work"; mkdir -p "$work"
args=(sweep --lambda log:0.05:30:5 --mu 0.5,3 --ta 30 --realizations 90 --block-size 8 --records --seed 3)

"$bin" "${args[@]}" --threads 1 -o "$work/single" 2>/dev/null || fail "single-process run"
for np in 1 2 4; do
  for t in 1 2; do
    "${launch[@]}" -np $np "$bin" "${args[@]}" --threads $t -o "$work/np$np-t$t" 2>"$work/np$np.err" \
      || { cat "$work/np$np.err"; fail "mpirun -np $np --threads $t"; }
    $compare "$work/single" "$work/np$np-t$t" >/dev/null || fail "-np $np --threads $t differs"
    grep -q "\"ranks\": $np," "$work/np$np-t$t/summary.json" || fail "-np $np: summary.json does not record $np ranks"
  done
  echo "mpi_cli: mpirun -np $np (1 and 2 threads per rank) == single process"
done
# Resume under MPI: half the units journaled by a shard, the rest by 3 ranks.
"$bin" "${args[@]}" --threads 1 --shard 1/2 -o "$work/resume" 2>/dev/null || fail "shard"
"${launch[@]}" -np 3 "$bin" "${args[@]}" --threads 1 --resume -o "$work/resume" 2>/dev/null \
  || fail "mpirun --resume"
$compare "$work/single" "$work/resume" >/dev/null || fail "MPI resume differs"
echo "mpi_cli: mpirun -np 3 --resume of a half-journaled sweep == single process"
# Adaptive sampling (--target-ci) under mpirun: the stop rule runs in block
# order, so the realizations chosen per point and every output equal the
# single-process run for any number of ranks, and after a resume under MPI.
tci=(sweep --k 40 --mu 0.5,5 --lambda log:0.3:20:4 --target-ci R:0.0025 --seed 11)
"$bin" "${tci[@]}" --threads 2 -o "$work/tci-single" 2>/dev/null || fail "single-process --target-ci"
for np in 2 3; do
  "${launch[@]}" -np $np "$bin" "${tci[@]}" --threads 1 -o "$work/tci-np$np" 2>"$work/tci.err" \
    || { cat "$work/tci.err"; fail "mpirun -np $np --target-ci"; }
  $compare "$work/tci-single" "$work/tci-np$np" >/dev/null || fail "--target-ci: -np $np differs"
done
/usr/bin/python3 - "$work/tci-single/summary.json" <<'PY' || fail "--target-ci: the target is not met per point"
import json, sys
points = json.load(open(sys.argv[1]))["points"]
ns = {p["realizations"] for p in points}
assert all((p["R"]["ci95"][1] - p["R"]["ci95"][0]) / 2 <= 0.0025 for p in points), points
assert len(ns) > 2, f"realizations chosen per point: {sorted(ns)}"
PY
# Resume: shards are refused with --target-ci, so stop a run under mpirun
# with SIGUSR1 once its journal has a segment, and resume it with 3 ranks.
tlong=(sweep --k 40 --mu 0.5,5 --lambda log:0.3:20:4 --target-ci R:0.0005 --seed 12
       --checkpoint-interval 0)
"$bin" "${tlong[@]}" --threads 2 -o "$work/tlong-single" 2>/dev/null || fail "single-process long --target-ci"
usr1_mid_run "$work/tci-usr1" "--target-ci SIGUSR1" "${tlong[@]}"
"${launch[@]}" -np 3 "$bin" "${tlong[@]}" --threads 1 --resume -o "$work/tci-usr1" 2>/dev/null \
  || fail "mpirun -np 3 --resume --target-ci"
$compare "$work/tlong-single" "$work/tci-usr1" >/dev/null || fail "--target-ci: MPI resume differs"
echo "mpi_cli: --target-ci under mpirun -np 2 and 3, and stopped and resumed under MPI, == single process"
# reproduce under mpirun: the ranks share every sweep of the study (rank 0
# coordinates, the others serve), the report records 2 ranks, and it equals
# the single-process reproduction.
rargs=(reproduce --quick --no-figures --realizations 300 --refine-realizations 300 --seed 5)
"$bin" "${rargs[@]}" --threads 1 -o "$work/repro-single" 2>/dev/null || fail "single-process reproduce"
"${launch[@]}" -np 2 "$bin" "${rargs[@]}" --threads 1 -o "$work/repro-np2" 2>"$work/repro.err" \
  || { cat "$work/repro.err"; fail "mpirun -np 2 reproduce"; }
/usr/bin/python3 "$here/../resume/compare_reproductions.py" "$work/repro-single" "$work/repro-np2" \
  >/dev/null || fail "mpirun -np 2 reproduce differs from the single-process reproduction"
grep -q "^| MPI ranks | 2 |" "$work/repro-np2/report.md" || fail "the report does not record 2 MPI ranks"
(($(grep -c "study done" "$work/repro.err") == 1)) || fail "the study ran more than once under mpirun"
echo "mpi_cli: mpirun -np 2 reproduce == single process, 2 ranks recorded, the study ran once"
# A bad configuration is reported by rank 0 and every rank exits.
timeout 60 "${launch[@]}" -np 2 "$bin" sweep --lambda 0.1,nan --realizations 10 -o "$work/bad" \
  2>"$work/bad.err"; rc=$?
((rc == 2)) || fail "bad input under mpirun: exit $rc, expected 2"
[[ -e $work/bad ]] && fail "bad input under mpirun wrote $work/bad"
# A unit over the event bound on some rank ends all ranks with exit 4.
timeout 60 "${launch[@]}" -np 3 "$bin" sweep --lambda 0.05,0.1 --mu 0.5,3 --ta 30 --realizations 90 \
  --block-size 8 --threads 1 --max-events 10 -o "$work/bound" \
  2>"$work/bound.err"; rc=$?
((rc == 4)) || fail "work bound under mpirun: exit $rc, expected 4"
[[ -e $work/bound ]] && fail "work bound under mpirun left $work/bound"
echo "mpi_cli: errors under mpirun: exit 2 (bad input) and 4 (work bound), no hang"
# SIGUSR1 to mpirun (mpirun forwards it to every rank; under srun,
# `#SBATCH --signal=USR1@...` sends it to every task): rank 0 hands out no
# more units, the units in flight are journaled, every rank exits, and
# --resume completes the same results. A watchdog ends a hung run.
long=(sweep --lambda log:0.1:30:40 --mu 0.5,5 --realizations 4000 --checkpoint-interval 0)
"$bin" "${long[@]}" --threads 2 -o "$work/long-single" 2>/dev/null || fail "single-process long run"
usr1_mid_run "$work/usr1" "SIGUSR1 under mpirun" "${long[@]}"
grep -q "^stickslip: stopped: interrupted by signal 10 (SIGUSR1): " "$work/usr1.err" || { cat "$work/usr1.err"; fail "SIGUSR1: no interruption report (exit $rc)"; }
"${launch[@]}" -np 2 "$bin" "${long[@]}" --threads 1 --resume -o "$work/usr1" 2>/dev/null \
  || fail "resume after SIGUSR1"
$compare "$work/long-single" "$work/usr1" >/dev/null || fail "resume after SIGUSR1 differs"
echo "mpi_cli: SIGUSR1 to mpirun stops all ranks, journaled; --resume == single process"
# A grid larger than a window (1,800 points; 60 lambda slabs of 30 points:
# two windows, 32 and 28 slabs, as its outputs are streamed:
# streamed_window_points) under mpirun: each window is a spec of its
# own for the serving ranks, with the same outputs as one process. The first
# journal segment is written when the first window ends (a checkpoint
# interval of an hour writes no other before), so SIGUSR1 sent then stops
# the run in its second window; --resume under MPI completes the same
# results.
wide=(sweep --lambda log:0.1:30:60 --mu lin:0.5:7:30 --realizations 120 --seed 9
      --checkpoint-interval 3600)
"$bin" "${wide[@]}" --threads 2 -o "$work/wide-single" 2>/dev/null || fail "single-process windowed grid"
"${launch[@]}" -np 2 "$bin" "${wide[@]}" --threads 1 -o "$work/wide-np2" 2>"$work/wide.err" \
  || { cat "$work/wide.err"; fail "mpirun -np 2 windowed grid"; }
$compare "$work/wide-single" "$work/wide-np2" >/dev/null || fail "windowed grid: -np 2 differs"
usr1_mid_run "$work/wide-usr1" "SIGUSR1 in the second window" "${wide[@]}"
grep -q "^stickslip: stopped: interrupted by signal 10 (SIGUSR1): " "$work/wide-usr1.err" || { cat "$work/wide-usr1.err"; fail "windowed grid: no interruption report (exit $rc)"; }
# It stopped in the second window: the first window's 960 points x 3
# blocks were journaled, not all 5,400 units (the signal is sent anyway
# after 15 s, which on a loaded machine could fall in the first window).
kept=$(sed -n 's/.*: \([0-9]*\) finished units are journaled.*/\1/p' "$work/wide-usr1.err")
((kept >= 2880 && kept < 5400)) || fail "windowed grid: stopped with $kept units journaled, not in the second window (2880 .. 5399)"
"${launch[@]}" -np 2 "$bin" "${wide[@]}" --threads 1 --resume -o "$work/wide-usr1" 2>/dev/null \
  || fail "windowed grid: resume under mpirun"
$compare "$work/wide-single" "$work/wide-usr1" >/dev/null || fail "windowed grid: MPI resume differs"
echo "mpi_cli: a grid of two windows under mpirun -np 2, and stopped in its second window and resumed, == single process"
rm -rf "$work"
