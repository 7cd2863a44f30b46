#!/usr/bin/env bash
# `stickslip plot DIR` (docs/plot.md): every figure kind from a small sweep,
# a sensitivity study, a NetCDF file with time-resolved and survival
# variables written here, and real sweeps with --statistics survival and
# --observe-times. Each PNG must start with the PNG signature and not
# be trivially small, each SVG must parse as XML and carry its axis labels
# with units. The oracle: the numbers in the .dat files are the values of
# results.nc / sensitivity.nc (read with netCDF4), bit for bit. Then the
# refusals: unknown names, --at off the grid, no results, no gnuplot, a
# figure that exists, a directory held by a running writer; each exits 2
# and writes nothing.
source "$(dirname "$0")/lib.sh" "$@"

run_ok sweep --lambda log:0.5:10:5 --mu 2,5 --k 40 --realizations 200 --seed 1 -o sw

# blocks(PATH): the rows of numbers of each block (gnuplot index) of a .dat.
cat >datfile.py <<'PY'
def blocks(path):
    text = open(path).read().split("\n\n\n")
    return [[[float(v) for v in line.split()] for line in b.splitlines()
             if line and not line.startswith("#")] for b in text if b.strip()]
PY

# check_figure STEM LABEL...: stdout lists STEM's four files, one line each;
# STEM.png and STEM.svg look like images and the SVG holds every LABEL (axis
# labels with units).
check_figure() {
  local stem=$1
  shift
  expect_eq "files printed for $stem" "$(cat "$WORK/stdout")" \
    "$(printf '%s\n' "$stem.dat" "$stem.gp" "$stem.png" "$stem.svg")"
  checks=$((checks + 1))
  "$PY" - "$stem" "$@" <<'PY' || fail "images of $stem"
import sys, xml.etree.ElementTree as E
stem, labels = sys.argv[1], sys.argv[2:]
png = open(stem + ".png", "rb").read()
assert png[:8] == b"\x89PNG\r\n\x1a\n", "no PNG signature"
assert len(png) > 10000, f"PNG of {len(png)} bytes"
root = E.parse(stem + ".svg").getroot()
text = " ".join(t for t in root.itertext())
for label in labels:
    assert label in text, f"SVG lacks '{label}'"
PY
}

# Curves with bands: the oracle compares each curve with results.nc.
run_ok plot sw --y R --x lambda --by mu
check_figure sw/plots/R_vs_lambda_by_mu "switch rate lambda (1/s)" "mean stick fraction (1)" "mu = 5"
grep -q "set logscale x" sw/plots/R_vs_lambda_by_mu.gp || fail "log:a:b:n lambda is not drawn on a log axis"
checks=$((checks + 1))
"$PY" - <<'PY' || fail "the curves' .dat differ from results.nc"
import netCDF4
from datfile import blocks
ds = netCDF4.Dataset("sw/results.nc")
rows = blocks("sw/plots/R_vs_lambda_by_mu.dat")
assert len(rows) == 2, len(rows)
for j in range(2):  # mu = 2, 5
    got = list(zip(*rows[j]))
    want = [ds["lambda"][:], ds["stick_fraction_mean"][:, j], ds["stick_fraction_ci95_low"][:, j],
            ds["stick_fraction_ci95_high"][:, j]]
    for g, w in zip(got, want):
        assert list(g) == [float(x) for x in w], (j, g, list(w))
PY

run_ok plot sw --y stick_duration --x mu --at lambda=10
check_figure sw/plots/stick_duration_vs_mu_at_lambda10 "friction coefficient mu (1)" "mean stick duration (s)" "at lambda = 10"
if grep -q "set logscale x" sw/plots/stick_duration_vs_mu_at_lambda10.gp; then
  fail "two mu values are drawn on a log axis"
fi

# Heat map: every cell's value is results.nc's.
run_ok plot sw --map --y R --x lambda --by mu
check_figure sw/plots/R_map_lambda_mu "switch rate lambda (1/s)" "friction coefficient mu (1)"
checks=$((checks + 1))
"$PY" - <<'PY' || fail "the map's .dat differs from results.nc"
import netCDF4
ds = netCDF4.Dataset("sw/results.nc")
R = ds["stick_fraction_mean"][:]
rows = [[float(v) for v in l.split()] for l in open("sw/plots/R_map_lambda_mu.dat")
        if l.strip() and not l.startswith("#")]
assert len(rows) == 10, len(rows)
lam, mu = list(ds["lambda"][:]), list(ds["mu"][:])
for x, y, *_, z in rows:
    assert z == float(R[lam.index(x), mu.index(y)]), (x, y, z)
PY

# --by defaults to the one dimension left open (plot.md), for a histogram
# too (a new user found --time and --survival asking for it).
run_ok plot sw --histogram D --at mu=5
check_figure sw/plots/D_histogram_by_lambda_at_mu5 "stick duration (s)" "density of D (1/s)" \
  "lambda = 10"

# Histograms at two points; the nearest grid lambda to 3.8 is 4.729.
run_ok plot sw --histogram D --at lambda=3.8,mu=5 --at lambda=0.5,mu=5
stem=sw/plots/D_histogram_at_lambda4.729_mu5_at_lambda0.5_mu5
check_figure $stem "stick duration (s)" "density of D (1/s)" "lambda = 4.729 (nearest to 3.8), mu = 5"
checks=$((checks + 1))
"$PY" - $stem.dat <<'PY' || fail "the histogram's .dat differs from results.nc"
import sys, netCDF4
from datfile import blocks
ds = netCDF4.Dataset("sw/results.nc")
for rows, i in zip(blocks(sys.argv[1]), [3, 0]):  # lambda index 3 (4.729) and 0 (0.5), mu = 5
    assert [r[0] for r in rows] == [float(v) for v in ds["stick_duration_bin"][i, 1, :]]
    assert [r[1] for r in rows] == [float(v) for v in ds["stick_duration_density"][i, 1, :]]
PY

# --format json lists the same files.
run_ok plot sw --y R --x lambda --by mu -o js --format json
checks=$((checks + 1))
"$PY" -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["files"] == ["js/R_vs_lambda_by_mu." + e for e in ("dat","gp","png","svg")], d; assert "95 %" in d["caption"]' \
  "$WORK/stdout" || fail "--format json: $(cat "$WORK/stdout")"

# Sensitivity: bars of the first- and total-order indices with their CIs.
run_ok sensitivity --k 40 --mu 'uniform(2,7)' --lambda 'uniform(0.5,5)' --samples 1000 --seed 1 --no-figure -o sens
run_ok plot sens
check_figure sens/plots/sensitivity_first_order_total_order "uncertain model parameter" "index (1)" "first order"
checks=$((checks + 1))
"$PY" - <<'PY' || fail "the bars' .dat differ from sensitivity.nc"
import netCDF4, shlex
ds = netCDF4.Dataset("sens/sensitivity.nc")
rows = [shlex.split(l) for l in open("sens/plots/sensitivity_first_order_total_order.dat")
        if l.strip() and not l.startswith("#")]
assert [r[0] for r in rows] == list(ds["input"][:]), rows
for i, r in enumerate(rows):
    want = [ds[n][i] for n in ("first_order", "first_order_ci95_low", "first_order_ci95_high",
                               "total_order", "total_order_ci95_low", "total_order_ci95_high")]
    assert [float(v) for v in r[1:]] == [float(w) for w in want], (r, want)
PY

# Time-resolved and survival curves from a file that has them.
mkdir tm
"$PY" - tm/results.nc <<'PY' || fail "writing the time/survival file"
import sys, numpy as np, netCDF4
d = netCDF4.Dataset(sys.argv[1], "w")
for name, n in [("lambda", 3), ("mu", 2), ("time", 11), ("stick_duration", 6)]:
    d.createDimension(name, n)
def coord(name, values, units, long_name):
    v = d.createVariable(name, "f8", (name,)); v[:] = values; v.units = units; v.long_name = long_name
coord("lambda", [0.5, 3.8, 10], "1/s", "switch rate lambda")
coord("mu", [2, 5], "1", "friction coefficient mu")
coord("time", np.linspace(0, 50, 11), "s", "observation time")
coord("stick_duration", np.linspace(0, 2.5, 6), "s", "stick duration")
def var(name, dims, values, long_name):
    v = d.createVariable(name, "f8", dims, fill_value=np.nan); v[:] = values; v.units = "1"; v.long_name = long_name
i, j, t = np.meshgrid(np.arange(3), np.arange(2), np.arange(11), indexing="ij")
var("stick_probability", ("lambda", "mu", "time"), 0.1 * i + 0.05 * j + 0.013 * t, "stick probability")
var("stick_probability_std_error", ("lambda", "mu", "time"), 0.01 + 0.001 * t, "its standard error")
i, j, k = np.meshgrid(np.arange(3), np.arange(2), np.arange(6), indexing="ij")
s = np.exp(-(k + 1) * 0.3 * (i + 1) / (j + 1))
var("stick_survival", ("lambda", "mu", "stick_duration"), s, "stick survival probability")
var("stick_survival_ci95_low", ("lambda", "mu", "stick_duration"), 0.9 * s, "lower 95% CI")
var("stick_survival_ci95_high", ("lambda", "mu", "stick_duration"), np.minimum(1.1 * s, 1), "upper 95% CI")
d.close()
PY
run_ok plot tm --time --at lambda=3.8,mu=5 --at lambda=0.5,mu=2
stem=tm/plots/stick_probability_vs_time_at_lambda3.8_mu5_at_lambda0.5_mu2
check_figure $stem "observation time (s)" "stick probability (1)" "lambda = 3.8, mu = 5"
checks=$((checks + 1))
"$PY" - $stem.dat <<'PY' || fail "the time curves' .dat differ from the file"
import sys, netCDF4
from datfile import blocks
ds = netCDF4.Dataset("tm/results.nc")
for rows, (i, j) in zip(blocks(sys.argv[1]), [(1, 1), (0, 0)]):
    p, se = ds["stick_probability"][i, j, :], ds["stick_probability_std_error"][i, j, :]
    z = 1.959963984540054
    assert [r[1] for r in rows] == [float(v) for v in p]
    assert [r[2] for r in rows] == [float(a) - z * float(b) for a, b in zip(p, se)]
    assert [r[3] for r in rows] == [float(a) + z * float(b) for a, b in zip(p, se)]
PY
run_ok plot tm --survival stick --at mu=5 --by lambda
check_figure tm/plots/stick_survival_by_lambda_at_mu5 "stick duration (s)" "stick survival probability (1)" "lambda = 10"

# Survival curves from a real sweep with --statistics survival (the names
# the sweep writes are the ones plot reads): the .dat equals results.nc.
run_ok sweep --preset paper-figures --lambda 0.5,3.8 --mu 5 --ta 20 --realizations 100 --seed 2 \
  --statistics survival --survival-bins 20 -o sv
run_ok plot sv --survival stick --by lambda
check_figure sv/plots/stick_survival_by_lambda "stick duration (s)" "stick survival probability (1)" \
  "lambda = 3.8"
run_ok plot sv --survival slip -o sv/default_by
check_figure sv/default_by/slip_survival_by_lambda "slip duration (s)" \
  "slip survival probability (1)" "lambda = 3.8"
run_ok plot sv --survival slip --at lambda=0.5
check_figure sv/plots/slip_survival_at_lambda0.5 "slip duration (s)" "slip survival probability (1)"
checks=$((checks + 1))
"$PY" - <<'PY' || fail "the survival curves' .dat differ from results.nc"
import netCDF4
from datfile import blocks
ds = netCDF4.Dataset("sv/results.nc")
rows = blocks("sv/plots/stick_survival_by_lambda.dat")
assert len(rows) == 2, len(rows)
for i in range(2):  # steps: (e_0, S_0), then (e_j, S_j-1), (e_j, S_j) for each edge
    got = list(zip(*rows[i][0::2]))
    want = [ds["stick_duration"][:], ds["stick_survival"][i, :], ds["stick_survival_ci95_low"][i, :],
            ds["stick_survival_ci95_high"][i, :]]
    for g, w in zip(got, want):
        assert list(g) == [float(v) for v in w], (g, w)
PY

# Time-resolved curves from a real sweep with --observe-times (the names the
# sweep writes are the ones plot reads): the stick probability with its
# binomial band, a mean with its ci95_half_width band, the level occupancy
# per level and the quantiles per level q; the .dat equals results.nc.
run_ok sweep --preset paper-figures --lambda 0.5,3.8 --mu 5 --ta 20 --realizations 100 --seed 2 \
  --observe-times lin:0:20:41 -o ot
run_ok plot ot --time --by lambda
check_figure ot/plots/stick_probability_vs_time_by_lambda "observation time (s)" \
  "stick probability (1)" "lambda = 3.8"
run_ok plot ot --time -o ot/default_by
check_figure ot/default_by/stick_probability_vs_time_by_lambda "observation time (s)" \
  "stick probability (1)" "lambda = 3.8"
run_ok plot ot --time --y position --at lambda=3.8
check_figure ot/plots/position_vs_time_at_lambda3.8 "observation time (s)" "mean position (m)"
run_ok plot ot --time --y level_occupancy --at lambda=0.5 --by belt_level
check_figure ot/plots/level_occupancy_vs_time_by_belt_level_at_lambda0.5 "observation time (s)" \
  "belt level occupancy (1)"
run_ok plot ot --time --y velocity_quantile --at lambda=3.8 --by quantile
check_figure ot/plots/velocity_quantile_vs_time_by_quantile_at_lambda3.8 "observation time (s)" \
  "quantiles of velocity (m/s)"
checks=$((checks + 1))
"$PY" - <<'PY' || fail "the time curves' .dat differ from results.nc"
import netCDF4
from datfile import blocks
ds = netCDF4.Dataset("ot/results.nc")
t, z = [float(v) for v in ds["time"][:]], 1.959963984540054
rows = blocks("ot/plots/stick_probability_vs_time_by_lambda.dat")
assert len(rows) == 2, len(rows)
for i in range(2):
    p, se = ds["stick_probability"][i, :], ds["stick_probability_std_error"][i, :]
    assert [r[0] for r in rows[i]] == t
    assert [r[1] for r in rows[i]] == [float(v) for v in p]
    assert [r[2] for r in rows[i]] == [float(a) - z * float(b) for a, b in zip(p, se)]
    assert [r[3] for r in rows[i]] == [float(a) + z * float(b) for a, b in zip(p, se)]
(rows,) = blocks("ot/plots/position_vs_time_at_lambda3.8.dat")
m, h = ds["position_mean"][1, :], ds["position_ci95_half_width"][1, :]
assert [r[1:] for r in rows] == [[float(a), float(a) - float(b), float(a) + float(b)]
                                 for a, b in zip(m, h)]
rows = blocks("ot/plots/level_occupancy_vs_time_by_belt_level_at_lambda0.5.dat")
assert [[r[1] for r in b] for b in rows] == ds["level_occupancy"][0, :, :].T.tolist()
rows = blocks("ot/plots/velocity_quantile_vs_time_by_quantile_at_lambda3.8.dat")
assert [[r[1] for r in b] for b in rows] == ds["velocity_quantile"][1, :, :].T.tolist()
PY

# Refusals: exit 2, the message, and no OUT.
# refused "PHRASE|..." ARGS...: `plot ARGS -o none` exits 2 naming every
# phrase and creates nothing.
refused() {
  local phrases=$1
  shift
  "$BIN" plot "$@" -o none >"$WORK/stdout" 2>"$WORK/stderr"
  expect_eq "exit code of plot $*" "$?" "2"
  local phrase
  IFS='|' read -r -a list <<<"$phrases"
  for phrase in "${list[@]}"; do
    checks=$((checks + 1))
    grep -qF -- "$phrase" "$WORK/stderr" || fail "plot $*: stderr lacks '$phrase': $(cat "$WORK/stderr")"
  done
  checks=$((checks + 1))
  [[ ! -e none ]] || fail "plot $* failed but created none/"
}
refused "invalid --y: 'RR'|stick_fraction (R)|stick_duration (D)" sw --y RR --x lambda
refused "invalid --x: 'lamda'|lambda, mu" sw --y R --x lamda
refused "invalid --by: 'k'|lambda, mu" sw --y R --x lambda --by k
refused "invalid --histogram: 'Q'|stick_duration (D)" sw --histogram Q --at lambda=1,mu=5
refused "invalid --at: 'lambda=20'|within the grid's range [0.5, 10]" sw --histogram D --at lambda=20,mu=5
refused "invalid --at: 'lambda=0.1'|[0.5, 10]" sw --y R --x mu --at lambda=0.1
refused "invalid --at: 'k=40'|lambda, mu" sw --y R --x lambda --at k=40
refused "varies over lambda|--by lambda|--at lambda=VALUE" sw --histogram D
refused "invalid --at: 'lambda3'|NAME=VALUE" sw --y R --x mu --at lambda3
refused "invalid --histogram: '--histogram D with --map'|one figure kind at a time" sw --map --histogram D
refused "no 'time' dimension|stickslip sweep --observe-times" sw --time --at lambda=1,mu=5
refused "no 'stick_survival' variable|--statistics survival" sw --survival stick --at lambda=1,mu=5
refused "invalid --survival: 'slip'|stick" tm --survival slip --at lambda=1,mu=5
# a misspelt time-resolved statistic: the ones over time, and the nearest
refused "invalid --y: 'stick_probabilty'|over time: stick_probability, position, velocity|level_occupancy|did you mean stick_probability?" \
  ot --time --y stick_probabilty
refused "invalid --y: 'stick_fractoin'|did you mean stick_fraction?" sw --y stick_fractoin
# a statistic of the schema the sweep did not select is named so, not taken
# for a typo of another (a review found W_f "near" D_1 and X "near" R)
refused "invalid --y: 'W_f'|W_f is a statistic this sweep did not select|--statistics paper,W_f" \
  sw --y W_f
checks=$((checks + 1))
"$BIN" plot sw --y X -o none 2>"$WORK/stderr" && fail "plot --y X ran"
grep -q "did you mean" "$WORK/stderr" && fail "a one-letter --y X got a suggestion: $(cat "$WORK/stderr")"
checks=$((checks + 1))  # Q is no statistic at all: the short-word rule, not the schema, decides
"$BIN" plot sw --y Q -o none 2>"$WORK/stderr" && fail "plot --y Q ran"
grep -q "did you mean" "$WORK/stderr" && fail "a one-letter --y Q got a suggestion: $(cat "$WORK/stderr")"
grep -q "is a statistic this sweep did not select" "$WORK/stderr" && fail "--y Q was taken for a statistic: $(cat "$WORK/stderr")"
refused "invalid --histogram: 'DD'|did you mean D?" sw --histogram DD
refused "invalid --at: 'k=40'|none: k is not an axis of stick_fraction_mean" sw --y R --x lambda --by mu --at k=40
# --at of an axis that is drawn, when no axis is left to fix
refused "invalid --at: 'lambda=3.8'|none: every axis of stick_survival is drawn (stick_duration, lambda)" \
  sv --survival stick --at lambda=3.8 --by lambda
refused "invalid --x: 'lambda'|sensitivity result" sens --x lambda
refused "invalid DIR: 'nowhere'|results.nc|sensitivity.nc" nowhere
mkdir empty
refused "invalid DIR: 'empty'" empty
mkdir -p unfinished/.journal  # what an interrupted sweep leaves: say so
refused "invalid DIR: 'unfinished'|holds the journal of an unfinished run|--resume" unfinished
env PATH=/nonexistent "$BIN" plot sw --y R --x lambda -o none >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code without gnuplot" "$?" "2"
checks=$((checks + 1))
grep -qF "gnuplot (with pngcairo and svg) not found" "$WORK/stderr" || fail "no gnuplot: $(cat "$WORK/stderr")"
[[ ! -e none ]] || fail "plot without gnuplot created none/"
# ... and --scripts-only writes the data and script alone.
env PATH=/nonexistent "$BIN" plot sw --y R --x lambda -o scripts --scripts-only >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of --scripts-only without gnuplot" "$?" "0"
expect_eq "files of --scripts-only" "$(ls scripts)" "$(printf '%s\n' R_vs_lambda_by_mu.dat R_vs_lambda_by_mu.gp)"

# A figure that exists is not replaced without --overwrite.
"$BIN" plot sw --y R --x lambda --by mu >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of a repeated plot" "$?" "2"
checks=$((checks + 1))
grep -qF "R_vs_lambda_by_mu.dat' already exists" "$WORK/stderr" || fail "repeat: $(cat "$WORK/stderr")"
run_ok plot sw --y R --x lambda --by mu --overwrite

# A directory held by a running writer is neither read nor written.
mkdir busy && cp sw/results.nc sw/summary.json sw/summary.csv busy/
"$BIN" sweep --lambda 1,2,3,4 --mu 1,2 --realizations 60000 --block-size 500 --seed 3 --threads 1 \
  --overwrite -o busy >"$WORK/busy.out" 2>"$WORK/busy.err" &
writer=$!
for _ in $(seq 1 200); do
  [[ -s busy/.stickslip.lock ]] && break
  sleep 0.05
done
refused "output directory 'busy' is in use by stickslip sweep (pid $writer" busy
"$BIN" plot sw --y R --x lambda --by mu -o busy >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of plot into a running sweep's directory" "$?" "2"
checks=$((checks + 1))
grep -qF "is in use by stickslip sweep (pid $writer" "$WORK/stderr" || fail "-o busy: $(cat "$WORK/stderr")"
checks=$((checks + 1))
kill -0 "$writer" 2>/dev/null || fail "the writer finished before plot was refused (too short to tell)"
[[ ! -e busy/plots && ! -e busy/R_vs_lambda_by_mu.dat ]] || fail "plot wrote into a running sweep's directory"
kill "$writer"
wait "$writer" 2>/dev/null

finish
