# sweep --burn-in T (docs/outputs.md, "Burn-in"): every statistic over
# [T, t_a]. Bit-identical for --threads 1 and 2, --engine reference, a TOML
# config (burn_in in [sweep]), a run interrupted (a shard's journal) then
# completed with --resume, and `mpirun -np 2` (when given); a --resume with
# another burn-in is refused naming both; --burn-in 0 is the sweep without
# it, to the byte (no attribute, no column, the same resolved config);
# recorded in results.nc (attribute burn_in), summary.json
# (parameters.burn_in), summary.csv (column burn_in) and the resolved
# config; out-of-range values exit 2 naming burn_in, the value and the range,
# and write nothing. With laws (t_a drawn too) and observe times, the same
# bits for threads, resume and MPI; T below the low end of t_a's law.
#   sweep_burn_in.sh STICKSLIP [MPIRUN]
here=$(cd "$(dirname "$0")" && pwd)
source "$here/lib.sh"
MPIRUN=${2:-}
compare="$PY $here/../resume/compare_outputs.py"
A=(sweep --preset paper-figures --lambda 0.5,3.8 --mu 2,5 --ta 20 --realizations 160
   --block-size 20 --seed 3 --statistics all --survival-bins 40 --records)

same() {  # same WHAT DIR: DIR's outputs equal the one-thread run's, bit for bit
  checks=$((checks + 1))
  $compare t1 "$2" >/dev/null 2>"$WORK/compare.err" || fail "$1 differs: $(cat "$WORK/compare.err")"
}

run_ok "${A[@]}" --burn-in 7.5 --threads 1 -o t1 || finish
run_ok "${A[@]}" --burn-in 7.5 --threads 2 -o t2 && same "--threads 2" t2
run_ok "${A[@]}" --burn-in 7.5 --engine reference -o ref && same "--engine reference" ref

cat >burn.toml <<'TOML'
[model]
k = 40
ta = 20
[grid]
lambda = [0.5, 3.8]
mu = [2, 5]
[sweep]
realizations = 160
block_size = 20
seed = 3
keep_records = true
statistics = ["all"]
burn_in = 7.5
[survival]
bins = 40
TOML
run_ok sweep --config burn.toml -o toml && same "the TOML config" toml
# The resolved config carries it and reruns to the same results.
"$PY" -c "import netCDF4; print(netCDF4.Dataset('t1/results.nc').resolved_config)" >resolved.toml
grep -qx "burn_in = 7.5" resolved.toml || fail "resolved_config lacks burn_in = 7.5"
run_ok sweep --config resolved.toml -o rerun && same "the resolved config" rerun

# Interrupted: half of the units journaled (a shard), then --resume; another
# burn-in cannot continue that journal (exit 5, both values named).
"$BIN" "${A[@]}" --burn-in 7.5 --shard 0/2 -o resumed >/dev/null 2>&1 || fail "the shard run"
"$BIN" "${A[@]}" --burn-in 5 -o resumed --resume >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of --resume with another --burn-in" "$?" "5"
grep -qF "burn-in: 7.5 s vs 5 s" "$WORK/stderr" ||
  fail "the refused resume does not name the burn-in: $(cat "$WORK/stderr")"
"$BIN" "${A[@]}" -o resumed --resume >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of --resume without the --burn-in" "$?" "5"
run_ok "${A[@]}" --burn-in 7.5 -o resumed --resume && same "--resume" resumed

if [[ -n $MPIRUN ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  checks=$((checks + 1))
  "$MPIRUN" --oversubscribe --mca btl self,vader --mca btl_vader_single_copy_mechanism none \
    -np 2 "$BIN" "${A[@]}" --burn-in 7.5 --threads 1 -o mpi >/dev/null 2>"$WORK/mpi.err" ||
    fail "mpirun -np 2: $(cat "$WORK/mpi.err")"
  same "mpirun -np 2" mpi
fi

# With laws (mu and t_a drawn per realization), a burn-in and observe times:
# the same bits for 1 and 2 threads, a shard then --resume, and mpirun.
L=(sweep --lambda 0.5,3.8 --mu 'uniform(4,6)' --ta 'uniform(20,30)' --realizations 120
   --block-size 20 --seed 3 --burn-in 5 --observe-times lin:0:20:5 --records)
same_laws() {  # same_laws WHAT DIR: DIR's outputs equal law1's
  checks=$((checks + 1))
  $compare law1 "$2" >/dev/null 2>"$WORK/compare.err" || fail "laws, $1 differs: $(cat "$WORK/compare.err")"
}
run_ok "${L[@]}" --threads 1 -o law1
run_ok "${L[@]}" --threads 2 -o law2 && same_laws "--threads 2" law2
"$BIN" "${L[@]}" --shard 1/2 -o lawres >/dev/null 2>&1 || fail "the laws' shard run"
run_ok "${L[@]}" -o lawres --resume && same_laws "--resume" lawres
if [[ -n $MPIRUN ]]; then
  checks=$((checks + 1))
  "$MPIRUN" --oversubscribe --mca btl self,vader --mca btl_vader_single_copy_mechanism none \
    -np 2 "$BIN" "${L[@]}" --threads 1 -o lawmpi >/dev/null 2>"$WORK/mpi.err" ||
    fail "laws, mpirun -np 2: $(cat "$WORK/mpi.err")"
  same_laws "mpirun -np 2" lawmpi
fi
"$PY" - <<'PY' || fail "laws: burn_in and the observe times recorded"
import netCDF4
ds = netCDF4.Dataset("law1/results.nc")
assert ds.burn_in == 5.0, ds.burn_in
p = ds["stick_probability"][:]
assert p.shape == (2, 5), p.shape
assert (p[:, 0] == 0).all() and (p[:, 1:] > 0).all(), p
PY
checks=$((checks + 1))

# simulate --realization R --burn-in T replays record R of the sweep: the
# same S_T, S_L, R and D_1, bit for bit (the paper model and a law on mu).
for case in "paper t1 --lambda 3.8 --mu 5" "law law1 --lambda 3.8 --mu uniform(4,6) --ta uniform(20,30)"; do
  read -r what dir rest <<<"$case"
  # shellcheck disable=SC2086
  for r in 3 77; do
    "$BIN" simulate $([[ $what == paper ]] && echo --preset paper-figures --ta 20) $rest --seed 3 \
      --realization $r --burn-in $([[ $what == paper ]] && echo 7.5 || echo 5) --format json \
      -o "sim_${what}_$r.json" 2>/dev/null || fail "simulate --burn-in ($what, realization $r)"
  done
done
"$PY" - <<'PY' || fail "simulate --burn-in does not replay the sweep's records"
import csv, json
for what, d, point in (("paper", "t1", None), ("law", "law1", 1)):
    rows = list(csv.DictReader(open(d + "/records.csv")))
    for r in (3, 77):
        sim = json.load(open(f"sim_{what}_{r}.json"))
        assert sim["burn_in"] == (7.5 if what == "paper" else 5.0), sim["burn_in"]
        want = [x for x in rows if int(x["realization"]) == r and float(x["lambda"]) == 3.8
                and (point is None or int(x["point"]) == point)]
        if what == "paper":
            want = [x for x in want if float(x["mu"]) == 5.0]
        assert len(want) == 1, (what, r, len(want))
        st = sim["statistics"]
        for k in ("sticks", "slips"):
            assert int(want[0][k]) == st[k], (what, r, k, want[0][k], st[k])
        for k in ("stick_fraction", "first_stick_start", "first_stick_duration"):
            a, b = float(want[0][k]), st[k]
            assert (a != a and b is None) or a == b, (what, r, k, a, b)
PY
checks=$((checks + 1))

# --burn-in 0 is no burn-in: the same outputs, attributes and config.
run_ok "${A[@]}" -o plain
run_ok "${A[@]}" --burn-in 0 -o zero
checks=$((checks + 1))
$compare plain zero >/dev/null 2>"$WORK/compare.err" || fail "--burn-in 0 differs: $(cat "$WORK/compare.err")"

"$PY" - <<'PY' || fail "burn_in recorded in results.nc, summary.json, summary.csv"
import csv, json, netCDF4
ds = netCDF4.Dataset("t1/results.nc")
assert ds.burn_in == 7.5, ds.burn_in
for d in ("plain", "zero"):
    z = netCDF4.Dataset(d + "/results.nc")
    assert "burn_in" not in z.ncattrs(), d
    assert "burn_in" not in json.load(open(d + "/summary.json"))["parameters"], d
    assert "burn_in" not in open(d + "/summary.csv").readline().split(","), d
    assert "burn_in" not in z.resolved_config, d
assert netCDF4.Dataset("plain/results.nc").resolved_config == netCDF4.Dataset("zero/results.nc").resolved_config
summary = json.load(open("t1/summary.json"))
assert summary["parameters"]["burn_in"] == 7.5
rows = list(csv.DictReader(open("t1/summary.csv")))
assert all(float(r["burn_in"]) == 7.5 for r in rows) and len(rows) == 4
# Records: R over t_a - T = 12.5 s, so the stick time R * 12.5 <= 12.5.
records = list(csv.DictReader(open("t1/records.csv")))
assert len(records) == 640 and all(0 <= float(r["stick_fraction"]) <= 1 for r in records)
ref = netCDF4.Dataset("plain/results.nc")
# The burn-in changes the statistics (a transient at lambda = 0.5 from the uniform start).
assert abs(ds["stick_fraction_mean"][0, 1] - ref["stick_fraction_mean"][0, 1]) > 1e-3
level = ds["belt_level_fraction_mean"][:]
assert abs(level.sum(axis=-1) - 1).max() < 1e-12
PY
checks=$((checks + 1))

# Out of range: exit 2, burn_in, the value and the range named, nothing written.
for bad in -1 20 25; do
  expect_fail "invalid burn_in: $bad (allowed: 0 <= burn_in < t_a = 20" \
    sweep --lambda 1 --ta 20 --realizations 10 --burn-in "$bad"
  "$BIN" sweep --lambda 1 --ta 20 --realizations 10 --burn-in "$bad" -o "code$bad" >/dev/null 2>&1
  expect_eq "exit code of --burn-in $bad" "$?" "2"
  [[ -e code$bad ]] && fail "--burn-in $bad wrote code$bad"
done
expect_fail "invalid burn_in: 15 (allowed: 0 <= burn_in < t_a = 15 (the shortest window" \
  sweep --lambda 1 --ta 40,15 --realizations 10 --burn-in 15
expect_fail "invalid --burn-in: 'ten' (allowed: a finite number" \
  sweep --lambda 1 --realizations 10 --burn-in ten
expect_fail "invalid --burn-in: 'inf' (allowed: a finite number" \
  sweep --lambda 1 --realizations 10 --burn-in inf
# With laws every draw of t_a must exceed T: the low end of t_a's law.
expect_fail "invalid burn_in: 20 (allowed: 0 <= burn_in < t_a = 20 (the low end of the support of t_a's law uniform(min=20,max=30)" \
  sweep --lambda 1 --ta 'uniform(20,30)' --realizations 10 --burn-in 20
printf '[model]\nta = 10\n[sweep]\nburn_in = 10\n' >bad1.toml
expect_fail "invalid burn_in: 10 (allowed: 0 <= burn_in < t_a = 10" sweep --config bad1.toml
printf '[sweep]\nburn_in = "ten"\n' >bad2.toml
expect_fail "sweep.burn_in" sweep --config bad2.toml

finish
