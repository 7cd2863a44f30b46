# The survival group (--statistics survival, docs/outputs.md "Survival"):
# its variables in results.nc and summary.json only when selected, the same
# numbers in both; bit-identical for --threads 1 and 2, --engine fast and
# reference, and a run interrupted (a shard's journal) then completed with
# --resume; a --resume with another selection is refused naming it; alone
# (--statistics survival) the same curves without the paper statistics; bad
# names exit 2 naming the value and the allowed names.
source "$(dirname "$0")/lib.sh"

A=(sweep --preset paper-figures --lambda 0.1,3.8 --mu 2,5 --ta 20 --realizations 120
   --block-size 20 --seed 3 --survival-bins 40)
run_ok "${A[@]}" --statistics paper,survival --threads 1 -o t1
run_ok "${A[@]}" --statistics survival,default --threads 2 -o t2
run_ok "${A[@]}" --statistics " survival , paper" --threads 2 --engine reference -o ref
run_ok "${A[@]}" --statistics survival -o alone
run_ok sweep --preset paper-figures --lambda 0.1,3.8 --mu 2,5 --ta 20 --realizations 120 \
  --block-size 20 --seed 3 -o plain

variables() { ncdump "$1" | sed '/^\/\/ global attributes:/,/^data:/{/^data:/!d}' | grep -v 'engine = '; }
variables t1/results.nc >v1
for d in t2 ref; do
  variables "$d/results.nc" >"v$d"
  cmp -s v1 "v$d" || fail "results.nc of $d differs from --threads 1: $(diff v1 "v$d" | head -5)"
  checks=$((checks + 1))
done

# Interrupted: half of the units journaled (a shard), then --resume.
"$BIN" "${A[@]}" --statistics paper,survival --shard 0/2 -o resumed >/dev/null 2>&1 ||
  fail "the shard run"
# Another selection cannot continue that journal: exit 5, the difference named.
"$BIN" "${A[@]:0:${#A[@]}-2}" -o resumed --resume >"$WORK/stdout" 2>"$WORK/stderr"
expect_eq "exit code of --resume with another --statistics" "$?" "5"
checks=$((checks + 1))
grep -qF "statistics: paper,survival vs paper" "$WORK/stderr" ||
  fail "the refused resume does not name the statistics: $(cat "$WORK/stderr")"
run_ok "${A[@]}" --statistics paper,survival -o resumed --resume
variables resumed/results.nc >vresumed
cmp -s v1 vresumed || fail "the resumed run differs: $(diff v1 vresumed | head -5)"
checks=$((checks + 1))

"$PY" - <<'PY' || fail "survival variables or summary.json"
import json, math, netCDF4
ds = netCDF4.Dataset("t1/results.nc")
assert ds.statistics == "paper,survival", ds.statistics
assert ds.survival_bins == 40
assert netCDF4.Dataset("plain/results.nc").statistics == "paper"
# The survival group alone: its curves and the counters, no paper statistics.
alone = netCDF4.Dataset("alone/results.nc")
assert alone.statistics == "survival" and "stick_survival" in alone.variables
assert "stick_fraction_mean" not in alone.variables and "no_stick_count" in alone.variables
assert (alone["stick_survival"][:] == ds["stick_survival"][:]).all()
plain = netCDF4.Dataset("plain/results.nc").variables
for law in ("stick", "slip"):
    d = ds[law + "_duration"]
    assert d.units == "s" and len(d) == 41 and d[0] == 0, law
    for name in ("_survival", "_survival_ci95_low", "_survival_ci95_high", "_at_risk"):
        v = ds[law + name]
        assert v.dimensions == ("lambda", "mu", law + "_duration"), (name, v.dimensions)
        assert law + name not in plain
    s = ds[law + "_survival"][:]
    assert (s[..., 0] == 1).all() and (s[..., 1:] <= s[..., :-1] + 1e-15).all(), law
    assert (ds[law + "_survival_ci95_low"][:] <= s + 1e-15).all()
    assert (ds[law + "_survival_ci95_high"][:] >= s - 1e-15).all()
    assert ds[law + "_restricted_mean"].dimensions == ("lambda", "mu")
# The stick duration grid: [0, d_max] of the largest mu (5): 2 mu g / (k V).
assert abs(ds["stick_duration"][-1] - 2 * 5 * 9.81 / 40) < 1e-12
assert ds["slip_duration"][-1] == 20
# Every stick is at risk at 0.
assert (ds["stick_at_risk"][:, :, 0] == ds["stick_duration_count"][:]).all()
summary = json.load(open("t1/summary.json"))
assert summary["parameters"]["statistics"] == ["paper", "survival"]
assert summary["parameters"]["survival"]["stick_duration"] == [float(x) for x in ds["stick_duration"][:]]
p = summary["points"][3]  # lambda = 3.8, mu = 5
for name in ("stick_survival", "stick_survival_ci95_low", "slip_survival_ci95_high", "slip_at_risk"):
    assert p[name] == [float(x) if not hasattr(x, "dtype") or x.dtype.kind == "f" else int(x)
                       for x in ds[name][1, 1, :]], name
assert p["stick_restricted_mean"] == float(ds["stick_restricted_mean"][1, 1])
assert "stick_survival" not in json.load(open("plain/summary.json"))["points"][0]
PY
checks=$((checks + 1))

expect_fail "invalid --statistics: 'survial' (allowed: a comma list of paper, family, derivatives, survival, default, all, or statistics by name (R, " \
  sweep --lambda 1 --statistics survial
expect_fail "invalid --statistics: '' (allowed: a comma list of paper," \
  sweep --lambda 1 --statistics survival,
expect_fail "invalid --survival-bins: '40'|only with the survival statistics" \
  sweep --lambda 1 --survival-bins 40
expect_fail "invalid --survival-bins: '0'" sweep --lambda 1 --statistics survival --survival-bins 0
printf '[sweep]\nstatistics = ["survival"]\n[survival]\nbins = 30\n' >s.toml
run_ok sweep --lambda 1 --mu 5 --ta 5 --realizations 20 --config s.toml -o toml
"$PY" -c '
import netCDF4; d = netCDF4.Dataset("toml/results.nc")
assert d.statistics == "survival" and len(d["stick_duration"]) == 31' ||
  fail "[sweep] statistics = [\"survival\"] in TOML"
checks=$((checks + 1))
# One string is the CLI's comma list.
printf '[sweep]\nstatistics = "paper, survival"\n[survival]\nbins = 30\n' >s2.toml
run_ok sweep --lambda 1 --mu 5 --ta 5 --realizations 20 --config s2.toml -o toml2
"$PY" -c '
import netCDF4; d = netCDF4.Dataset("toml2/results.nc")
assert d.statistics == "paper,survival"' || fail "[sweep] statistics = \"paper, survival\" in TOML"
checks=$((checks + 1))
printf '[sweep]\nstatistics = ["survival", "papers"]\n' >bad.toml
expect_fail "invalid sweep.statistics: 'papers' (allowed: a comma list of paper, family," \
  sweep --lambda 1 --config bad.toml
finish
