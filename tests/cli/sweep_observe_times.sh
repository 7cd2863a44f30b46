# sweep --observe-times GRID (docs/outputs.md, "Observe times"): the ensemble
# at chosen times. Bit-identical (every results.nc variable, summary.json's
# points, summary.csv; compare_outputs.py) for --threads 1 and 2, --engine
# reference, a TOML config (grid text and array), the resolved config, a run
# killed with kill -9 and completed with --resume, shards merged, and
# `mpirun -np 2` (when given); a --resume with other times is refused.
# results.nc has the coordinate `time` after the grid dimensions and the
# variables over (grid, time[, belt_level | quantile]); summary.json has
# each point's `observed` object with the stick probability and its std
# error. Bad times (descending, beyond t_a, NaN, negative, with laws) exit 2
# naming the setting and the value, and write nothing.
#   sweep_observe_times.sh STICKSLIP [MPIRUN]
here=$(cd "$(dirname "$0")" && pwd)
source "$here/lib.sh"
MPIRUN=${2:-}
compare="$PY $here/../resume/compare_outputs.py"
A0=(sweep --preset paper-figures --lambda 0.5,3.8 --mu 2,5 --ta 20 --realizations 400
    --block-size 20 --seed 3)
A=("${A0[@]}" --observe-times lin:0:20:21)

same() {  # same WHAT DIR: DIR's outputs equal the one-thread run's, bit for bit
  checks=$((checks + 1))
  $compare t1 "$2" >/dev/null 2>"$WORK/compare.err" || fail "$1 differs: $(cat "$WORK/compare.err")"
}

run_ok "${A[@]}" --threads 1 -o t1 || finish
run_ok "${A[@]}" --threads 2 -o t2 && same "--threads 2" t2
run_ok "${A[@]}" --engine reference -o ref && same "--engine reference" ref

# The layout and the values: dimensions, units, ranges; summary.json = results.nc.
"$PY" - <<'PY' || fail "the variables of results.nc and summary.json"
import json, netCDF4, numpy as np
ds = netCDF4.Dataset("t1/results.nc")
t = ds["time"]
assert t.dimensions == ("time",) and t.units == "s" and t.long_name == "observation time"
assert list(t[:]) == [float(i) for i in range(21)], list(t[:])
assert list(ds["quantile"][:]) == [0.05, 0.25, 0.5, 0.75, 0.95]
grid = ("lambda", "mu")
one = ["stick_probability", "stick_probability_std_error"] + [
    f"{x}_{s}" for x in ("position", "velocity", "relative_velocity", "energy")
    for s in ("mean", "variance", "ci95_half_width")]
for name in one:
    v = ds[name]
    assert v.dimensions == grid + ("time",), (name, v.dimensions)
    assert v.units and v.long_name and v.description, name
    assert np.isfinite(v[:]).all(), name
assert ds["level_occupancy"].dimensions == grid + ("time", "belt_level")
for name in ("position_quantile", "velocity_quantile"):
    assert ds[name].dimensions == grid + ("time", "quantile"), name
assert ds["position_mean"].units == "m" and ds["position_variance"].units == "m2"
assert ds["energy_mean"].units == "J" and ds["velocity_mean"].units == "m/s"
p, se = ds["stick_probability"][:], ds["stick_probability_std_error"][:]
n = 400
assert ((p >= 0) & (p <= 1)).all()
assert np.allclose(se, np.sqrt(p * (1 - p) / n), rtol=0, atol=1e-15)
assert np.allclose(ds["level_occupancy"][:].sum(axis=-1), 1, rtol=0, atol=1e-12)
q = ds["position_quantile"][:]
assert (np.diff(q, axis=-1) >= 0).all(), "quantiles decrease over the quantile levels"
half = ds["position_ci95_half_width"][:]
assert np.allclose(half, 1.959963984540054 * np.sqrt(ds["position_variance"][:] / n), rtol=1e-12)
assert (ds["energy_mean"][:] > 0).all()
# The uniform start: x0 over [-1, 1] at t = 0 (the mean near 0, within 4 SE).
assert (abs(ds["position_mean"][:, :, 0]) < 4 * half[:, :, 0] / 1.96).all()
# Sticks do happen at mu = 5 (a stick can start once the slip meets the band).
assert p[:, 1, 1:].max() > 0.2, p[:, 1, :]
summary = json.load(open("t1/summary.json"))
for k, point in enumerate(summary["points"]):
    i, j = divmod(k, 2)
    o = point["observed"]
    # summary.json: the stick probability and its std error; the rest in results.nc
    assert sorted(o) == ["stick_probability", "stick_probability_std_error", "time"], sorted(o)
    assert o["time"] == list(map(float, t[:]))
    for name in ("stick_probability", "stick_probability_std_error"):
        assert o[name] == [float(x) for x in ds[name][i, j, :]], (k, name)
assert "results.nc" in summary["parameters"]["observed"]
PY
checks=$((checks + 1))

# TOML: the grid's text and an array of numbers; the resolved config reruns.
cat >ot.toml <<'TOML'
[model]
k = 40
ta = 20
[grid]
lambda = [0.5, 3.8]
mu = [2, 5]
[sweep]
realizations = 400
block_size = 20
seed = 3
observe_times = "lin:0:20:21"
TOML
run_ok sweep --config ot.toml -o toml && same "the TOML config (grid text)" toml
sed 's/^observe_times = .*/observe_times = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20.0]/' \
  ot.toml >array.toml
run_ok sweep --config array.toml -o array && same "the TOML config (array)" array
"$PY" -c "import netCDF4; print(netCDF4.Dataset('t1/results.nc').resolved_config)" >resolved.toml
checks=$((checks + 1))
grep -qx "observe_times = \[0.0, 1.0, 2.0, .*, 20.0\]" resolved.toml ||
  fail "resolved_config lacks observe_times: $(grep observe resolved.toml)"
run_ok sweep --config resolved.toml -o rerun && same "the resolved config" rerun

# kill -9 once the journal has grown by a segment, then --resume to the end.
segments() { compgen -G "killed/.journal/seg-*" | wc -l; }
"$BIN" "${A[@]}" --threads 2 --checkpoint-interval 0 -o killed \
  >/dev/null 2>"$WORK/kill.log" &
pid=$!
for _ in $(seq 400); do
  (($(segments) > 0)) && break
  kill -0 $pid 2>/dev/null || break
  sleep 0.01
done
kill -9 $pid 2>/dev/null
wait $pid 2>/dev/null
killed=$?
run_ok "${A[@]}" --threads 2 -o killed --resume && same "kill -9 and --resume" killed
[[ $killed == 137 ]] || echo "note: the run finished before kill -9 (exit $killed)"

# Half of the units journaled (a shard), then --resume; other times cannot
# continue that journal (exit 5).
"$BIN" "${A[@]}" --shard 0/2 -o resumed >/dev/null 2>&1 || fail "the shard run"
"$BIN" "${A0[@]}" --observe-times 0,10,20 -o resumed --resume >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of --resume with other --observe-times" "$?" "5"
checks=$((checks + 1))
grep -qF "observe" "$WORK/stderr" || fail "the refused resume does not name the times: $(cat "$WORK/stderr")"
"$BIN" "${A0[@]}" -o resumed --resume >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of --resume without --observe-times" "$?" "5"
run_ok "${A[@]}" -o resumed --resume && same "a shard then --resume" resumed
for i in 0 1; do run_ok "${A[@]}" --threads 1 --shard $i/2 -o shard$i; done
run_ok merge -o merged shard0 shard1 && same "2 shards merged" merged

if [[ -n $MPIRUN ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  checks=$((checks + 1))
  "$MPIRUN" --oversubscribe --mca btl self,vader --mca btl_vader_single_copy_mechanism none \
    -np 2 "$BIN" "${A[@]}" --threads 1 -o mpi >/dev/null 2>"$WORK/mpi.err" ||
    fail "mpirun -np 2: $(cat "$WORK/mpi.err")"
  same "mpirun -np 2" mpi
fi

# Without --observe-times nothing of it is written.
run_ok sweep --lambda 1 --ta 5 --realizations 20 -o plain
"$PY" - <<'PY' || fail "a sweep without --observe-times has observe-time outputs"
import json, netCDF4
ds = netCDF4.Dataset("plain/results.nc")
assert "time" not in ds.dimensions and "stick_probability" not in ds.variables
assert "quantile" not in ds.dimensions and "observe_times" not in ds.resolved_config
assert "observed" not in json.load(open("plain/summary.json"))["points"][0]
PY
checks=$((checks + 1))

# Bad times: exit 2, the setting and the value named, nothing written.
B=(sweep --lambda 1 --ta 20 --realizations 10)
bad() {  # bad "PHRASE|..." ARGS...: exit 2 with every phrase, no output directory
  local phrases=$1
  shift
  expect_fail "$phrases" "${B[@]}" "$@"
  "$BIN" "${B[@]}" "$@" -o code >/dev/null 2>&1
  expect_eq "exit code of $*" "$?" "2"
  [[ -e code ]] && fail "$* wrote code/" && rm -rf code
}
bad "invalid observe_times: 2|increasing order|follows 5" --observe-times 5,2
bad "invalid observe_times: 3|increasing order, each once" --observe-times 1,3,3
bad "invalid observe_times: 25|0 <= t <= t_a = 20" --observe-times 0,25
bad "invalid observe_times: 30|0 <= t <= t_a = 20" --observe-times lin:0:30:4
expect_fail "invalid observe_times: 16|t_a = 15 (the shortest window" sweep --lambda 1 --ta 40,15 --realizations 10 --observe-times 0,16
bad "invalid --observe-times: 'nan'|not finite" --observe-times nan
bad "invalid --observe-times: '0,inf'|not finite" --observe-times 0,inf
bad "invalid --observe-times: '-1,2'|>= 0" --observe-times -1,2
bad "invalid --observe-times: ''|at least one value" --observe-times ''
bad "invalid --observe-times: 'lin:20:0'|4 fields" --observe-times lin:20:0
# every refusal of a range states the times' domain, >= 0 (n's said "> 0")
bad "invalid --observe-times: 'lin:0:50:0'|n >= 1|of finite values >= 0)" --observe-times lin:0:50:0
bad "invalid --observe-times: 'lin:0:50:x'|n a whole number|of finite values >= 0)" --observe-times lin:0:50:x
bad "invalid observe_times: 10|increasing order" --observe-times lin:20:0:3
expect_fail "invalid observe_times: 25|t_a = 20 (the low end of the support of t_a's law uniform(min=20,max=30))" \
  sweep --lambda 1 --ta 'uniform(20,30)' --realizations 10 --observe-times 0,25
printf '[model]\nta = 10\n[sweep]\nobserve_times = [0, 11]\n' >bad1.toml
expect_fail "invalid observe_times: 11|t_a = 10" sweep --config bad1.toml
printf '[sweep]\nobserve_times = "ten"\n' >bad2.toml
expect_fail "sweep.observe_times|'ten'" sweep --config bad2.toml
printf '[sweep]\nobserve_times = [1, "a"]\n' >bad3.toml
expect_fail "sweep.observe_times[1]" sweep --config bad3.toml
printf '[sweep]\nobserve_times = [-1]\n' >bad4.toml
expect_fail "sweep.observe_times[0]|>= 0" sweep --config bad4.toml

finish
