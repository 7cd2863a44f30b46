# A sweep with an uncertain parameter (laws and grid axes combined)
# is bit-identical for 1 and 2 threads, from a TOML config and from flags,
# after kill -9 and --resume, from 3 merged shards, and under `mpirun -np 2`; --resume on its
# finished outputs recognizes them (the resolved config, laws included,
# reads back exactly); and every realization replays alone with `simulate
# --realization r`, drawing the same value as its record.
#   sweep_laws_reproducible.sh STICKSLIP [REALIZATIONS [MPIRUN]]
# ctest runs it with few realizations; the full reproducibility case
# (20000 realizations, MPI included) is
#   bash tests/cli/sweep_laws_reproducible.sh build/apps/stickslip/stickslip 20000 mpirun
here=$(cd "$(dirname "$0")" && pwd)
source "$here/lib.sh"
N=${2:-3000}
MPIRUN=${3:-}
compare="$PY $here/../resume/compare_outputs.py"
args=(sweep --k 40 --lambda 1,3.8 --mu 'gamma(mean=5,cv=0.2)' --realizations "$N" --records
      --seed 7)

same() {  # same WHAT DIR: DIR's outputs equal the one-thread run's, bit for bit
  checks=$((checks + 1))
  $compare t1 "$2" >/dev/null 2>"$WORK/compare.err" || fail "$1 differs: $(cat "$WORK/compare.err")"
}

run_ok "${args[@]}" --threads 1 -o t1 || finish
run_ok "${args[@]}" --threads 2 -o t2 && same "--threads 2" t2

# The same sweep from a TOML file: the law as a [model] key.
cat >laws.toml <<'TOML'
[model]
k = 40
mu = "gamma(mean = 5, cv = 0.2)"
[grid]
lambda = [1, 3.8]
TOML
run_ok sweep --config laws.toml --realizations "$N" --records --seed 7 --threads 2 -o toml &&
  same "--config laws.toml" toml

# --resume on finished outputs: nothing to do (their resolved config, with the
# law in canonical text, identifies them).
run_ok "${args[@]}" --threads 2 -o t2 --resume &&
  { grep -qF "already holds the complete results" "$WORK/stderr" ||
      fail "--resume did not recognize finished outputs: $(cat "$WORK/stderr")"; }

# kill -9 once the journal has grown by a segment (then after a random
# further delay), and --resume, three times; then --resume to the end.
segments() { compgen -G "killed/.journal/seg-*" | wc -l; }
kills=0
for cycle in 1 2 3; do
  resume=(); ((cycle > 1)) && resume=(--resume)
  before=$(segments)
  "$BIN" "${args[@]}" --threads 2 --checkpoint-interval 0 -o killed "${resume[@]}" \
    >/dev/null 2>>"$WORK/kill.log" &
  pid=$!
  for _ in $(seq 400); do
    (($(segments) > before)) && break
    kill -0 $pid 2>/dev/null || break
    sleep 0.01
  done
  sleep "$("$PY" -c "import random; print(round(random.uniform(0, 0.05), 3))")"
  kill -9 $pid 2>/dev/null
  wait $pid 2>/dev/null
  (($? == 137)) && kills=$((kills + 1))  # killed, not finished
  [[ -f killed/results.nc && ! -d killed/.journal ]] && break
done
if [[ ! -f killed/results.nc || -d killed/.journal ]]; then
  run_ok "${args[@]}" --threads 2 -o killed --resume
fi
same "kill -9 ($kills kills) and --resume" killed
((kills > 0)) || fail "no run was killed before it finished (give more realizations)"
echo "kill -9 / --resume: $kills kills"

# Shards merged with `stickslip merge`.
for i in 0 1 2; do
  run_ok "${args[@]}" --threads 1 --shard $i/3 -o shard$i
done
run_ok merge -o merged shard0 shard1 shard2 && same "3 shards merged" merged

if [[ -n $MPIRUN ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  checks=$((checks + 1))
  "$MPIRUN" --oversubscribe --mca btl self,vader --mca btl_vader_single_copy_mechanism none \
    -np 2 "$BIN" "${args[@]}" --threads 1 -o mpi >/dev/null 2>"$WORK/mpi.err" ||
    fail "mpirun -np 2: $(cat "$WORK/mpi.err")"
  same "mpirun -np 2" mpi
fi

# Every realization replays alone: simulate --realization r draws the record's
# values and gives its record. replay SWEEP_DIR AXIS LAWS_JSON FLAGS...
# (AXIS: the records.csv column of the swept parameter; FLAGS: the sweep's
# model flags without that axis).
replay() {
  checks=$((checks + 1))
  "$PY" - "$BIN" "$@" <<'PYEOF' || fail "simulate does not replay the records of $1"
import csv, json, subprocess, sys
binary, folder, axis, laws, flags = sys.argv[1], sys.argv[2], sys.argv[3], json.loads(sys.argv[4]), sys.argv[5:]
rows = list(csv.DictReader(open(folder + "/records.csv")))
step = max(1, len(rows) // 16)
for row in rows[::step]:
    out = subprocess.run(
        [binary, "simulate", *flags, "--" + axis, row[axis], "--realization", row["realization"],
         "--format", "json"], check=True, capture_output=True, text=True).stdout
    d = json.loads(out)
    assert d["laws"] == laws, d["laws"]
    for sym in laws:
        assert d["drawn"][sym] == float(row[sym]), (row["point"], row["realization"], d["drawn"])
        assert d["parameters"][sym] == float(row[sym])
    ic, st, ev = d["initial_conditions"], d["statistics"], d["event_counts"]
    pairs = [("x0", ic["x0"], float(row["x0"])), ("xdot0", ic["xdot0"], float(row["xdot0"])),
             ("belt_start", ic["belt_start"], int(row["belt_start"])),
             ("sticks", st["sticks"], int(row["sticks"])), ("slips", st["slips"], int(row["slips"])),
             ("stick_fraction", st["stick_fraction"], float(row["stick_fraction"])),
             ("belt_switches", ev["belt_switch"], int(row["belt_switches"])),
             ("stick_onsets", ev["stick_onset"], int(row["stick_onsets"])),
             ("stick_breaks", ev["stick_break"], int(row["stick_breaks"])),
             ("slip_reversals", ev["slip_reversal"], int(row["slip_reversals"]))]
    if int(row["sticks"]) > 0:
        pairs.append(("first_stick_duration", st["first_stick_duration"],
                      float(row["first_stick_duration"])))
    for name, got, want in pairs:
        assert got == want, (row["point"], row["realization"], name, got, want)
PYEOF
}
replay t1 lambda '{"mu": "gamma(mean=5,cv=0.2)"}' --k 40 --mu 'gamma(mean=5,cv=0.2)' --seed 7
# The model family's engine: damped, mu_s > mu_k, with laws for c and mu_k.
run_ok sweep --k 40 --mu-s 5 --c 'gamma(mean=0.2,cv=0.5)' --mu-k 'uniform(2,4)' --lambda 1,3.8 \
  --ta 20 --realizations 40 --records --seed 2 -o family
replay family lambda '{"c": "gamma(mean=0.2,cv=0.5)", "mu_k": "uniform(min=2,max=4)"}' \
  --k 40 --mu-s 5 --c 'gamma(mean=0.2,cv=0.5)' --mu-k 'uniform(2,4)' --ta 20 --seed 2

# With common random numbers realization r of every point draws the same
# value, and simulate --common-random-numbers replays it.
run_ok sweep --k 40 --lambda 1,3.8 --mu 'uniform(2,7)' --realizations 30 --seed 5 --records \
  --common-random-numbers -o crn
first=$(awk -F, '$1 == 0 && $4 == 7 {print $3}' crn/records.csv)
second=$(awk -F, '$1 == 1 && $4 == 7 {print $3 "," $8}' crn/records.csv)
expect_eq "realization 7 draws the same mu at both points" "$first" "${second%,*}"
run_ok simulate --k 40 --lambda 3.8 --mu 'uniform(2,7)' --seed 5 --realization 7 \
  --common-random-numbers --format json
"$PY" -c 'import json, sys; d = json.load(open(sys.argv[1])); print(repr(d["drawn"]["mu"]) + "," + str(d["statistics"]["sticks"]))' \
  "$WORK/stdout" >crn.replay
expect_eq "simulate --common-random-numbers replays realization 7" "$(cat crn.replay)" "$second"
finish
