#!/usr/bin/env bash
# The reproducibility check of laws for uncertain parameters, at full size: the random-parameter
# sweep
#   stickslip sweep --k 40 --lambda 1,3.8 --mu 'gamma(mean=5,cv=0.2)' --realizations 20000
# run every way a user may run it, each compared bit for bit with the
# one-thread run (tests/resume/compare_outputs.py: every results.nc variable,
# summary.json's points, summary.csv, records.csv):
#   --threads 2; kill -9 at random points and --resume until it completes;
#   mpirun -np 2 (skipped without mpirun); 3 shards merged; the same sweep
#   from a TOML file; and every realization replayed alone (Python's
#   stickslip.simulate(realization=r), the CLI's `simulate --realization r`
#   for a sample), drawing its record's mu and giving its record.
# Prints one line per way (MATCH or DIFFER, with the wall time) and exits 1
# if any differed. ctest runs the same checks small
# (tests/cli/sweep_laws_reproducible.sh); this is the one-off full run.
#   scripts/reproducibility_laws.sh [STICKSLIP [REALIZATIONS [WORKDIR]]]
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=$(realpath "${1:-$root/build/apps/stickslip/stickslip}")
n=${2:-20000}
work=${3:-$(mktemp -d "${TMPDIR:-/tmp}/stickslip-laws.XXXXXX")}
py=/usr/bin/python3
law='gamma(mean=5,cv=0.2)'
args=(sweep --k 40 --lambda 1,3.8 --mu "$law" --realizations "$n" --records --seed 7)
mkdir -p "$work" && cd "$work" || exit 1
rm -rf t1 t2 killed mpi shard0 shard1 shard2 merged toml
echo "work directory: $work"
echo "command: stickslip sweep --k 40 --lambda 1,3.8 --mu '$law' --realizations $n --records --seed 7"
differed=0

now() { date +%s.%N; }
seconds() { "$py" -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.1f}')" "$1" "$(now)"; }
report() {  # report WHAT START DIR: compare DIR with t1 and print the verdict
  local took
  took=$(seconds "$2")
  if "$py" "$root/tests/resume/compare_outputs.py" t1 "$3" >/dev/null 2>compare.err; then
    printf 'MATCH   %-42s %8s s\n' "$1" "$took"
  else
    printf 'DIFFER  %-42s %8s s   %s\n' "$1" "$took" "$(tr '\n' ' ' <compare.err)"
    differed=1
  fi
}
run() { "$bin" "$@" >/dev/null 2>>run.log || { echo "failed: stickslip $* (run.log)"; exit 1; }; }

start=$(now); run "${args[@]}" --threads 1 -o t1
printf 'REF     %-42s %8s s\n' "--threads 1" "$(seconds "$start")"

start=$(now); run "${args[@]}" --threads 2 -o t2
report "--threads 2" "$start" t2

# kill -9 after a random fraction of the two-thread run's time, then --resume
# (killed again while it runs) until a run completes.
full=$(seconds "$start")
start=$(now); kills=0
for cycle in $(seq 1 40); do
  resume=(); ((cycle > 1)) && resume=(--resume)
  "$bin" "${args[@]}" --threads 2 --checkpoint-interval 0 -o killed "${resume[@]}" \
    >/dev/null 2>>kill.log &
  pid=$!
  sleep "$("$py" -c "import random, sys; print(round(random.uniform(0.1, 0.5) * float(sys.argv[1]), 3))" "$full")"
  kill -9 $pid 2>/dev/null && kills=$((kills + 1))
  wait $pid 2>/dev/null
  [[ -f killed/results.nc && ! -d killed/.journal ]] && break
  ((kills >= 5)) && break
done
[[ -f killed/results.nc && ! -d killed/.journal ]] || run "${args[@]}" --threads 2 -o killed --resume
report "kill -9 ($kills kills) and --resume" "$start" killed

if command -v mpirun >/dev/null; then
  start=$(now)
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \
    mpirun --oversubscribe --mca btl self,vader --mca btl_vader_single_copy_mechanism none \
    -np 2 "$bin" "${args[@]}" --threads 1 -o mpi >/dev/null 2>>run.log ||
    { echo "failed: mpirun -np 2 (run.log)"; exit 1; }
  report "mpirun -np 2 --threads 1" "$start" mpi
else
  echo "SKIPPED mpirun -np 2 (no mpirun on PATH)"
fi

start=$(now)
for i in 0 1 2; do run "${args[@]}" --threads 2 --shard $i/3 -o shard$i; done
run merge -o merged shard0 shard1 shard2
report "3 shards, merged" "$start" merged

cat >laws.toml <<TOML
[model]
k = 40
mu = "gamma(mean = 5, cv = 0.2)"
[grid]
lambda = [1, 3.8]
[sweep]
realizations = $n
seed = 7
keep_records = true
TOML
start=$(now); run sweep --config laws.toml --threads 2 -o toml
report "--config laws.toml" "$start" toml

# Every realization replays alone.
start=$(now)
if PYTHONPATH=$root/build/python "$py" - t1/records.csv "$law" "$bin" <<'PYEOF'; then
import csv, json, random, subprocess, sys
import stickslip
path, law, binary = sys.argv[1:4]
rows = list(csv.DictReader(open(path)))
def check(row, drawn, record):
    want = (float(row["mu"]), int(row["sticks"]), float(row["stick_fraction"]),
            int(row["belt_switches"]))
    assert (drawn, *record) == want, (row["point"], row["realization"], drawn, record, want)
for row in rows:  # all of them, in process
    r = stickslip.simulate(k=40, lam=float(row["lambda"]), mu=law, seed=7,
                           realization=int(row["realization"]))
    check(row, r.drawn["mu"], (r.record["S_T"], r.record["R"], r.record["belt_switches"]))
for row in random.Random(7).sample(rows, 100):  # and a sample through the CLI
    d = json.loads(subprocess.run(
        [binary, "simulate", "--k", "40", "--lambda", row["lambda"], "--mu", law, "--seed", "7",
         "--realization", row["realization"], "--format", "json"],
        check=True, capture_output=True, text=True).stdout)
    check(row, d["drawn"]["mu"], (d["statistics"]["sticks"], d["statistics"]["stick_fraction"],
                                  d["event_counts"]["belt_switch"]))
print(f"replayed {len(rows)} records in Python and 100 through the CLI", file=sys.stderr)
PYEOF
  printf 'MATCH   %-42s %8s s\n' "every record replayed alone" "$(seconds "$start")"
else
  printf 'DIFFER  %-42s %8s s\n' "every record replayed alone" "$(seconds "$start")"
  differed=1
fi
exit $differed
