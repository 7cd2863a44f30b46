#!/usr/bin/env bash
# results.nc and summary.json hold the parameters that
# define the model swept and nothing meaningless for it, and no variable that
# does not apply to it (no all-NaN variable). Checked with netCDF4.
source "$(dirname "$0")/lib.sh" "$@"
C=(--realizations 60 --block-size 20 --threads 1 --ta 10 --statistics paper,family,derivatives)

run_ok sweep --lambda 1,2 --mu 4,6 "${C[@]}" -o paper
run_ok sweep --lambda 1,2 --mu-s 4,6 --mu-k 4 "${C[@]}" -o split
run_ok sweep --belt-levels 1,-0.5 --belt-rates 1,2 --mu 3,4 "${C[@]}" -o rates
run_ok sweep --c 0,0.5 --mu-s 6 --mu-k 4 --belt-levels 1,-0.5,0 \
  --belt-generator '-2,1.5,0.5;0.25,-0.75,0.5;1,2,-3' "${C[@]}" -o generator
run_ok sweep --lambda 1,2 --mu-s 2 --mu-k 2 --c 0 --belt-levels 1,-1 "${C[@]}" -o spelled
run_ok sweep --lambda 1 --mu 4 --realizations 20 -o default_selection

"$PY" - <<'PYEOF' || fail "see the lines above"
import json, sys
import netCDF4, numpy as np

bad = []
def check(cond, what):
    if not cond:
        bad.append(what)

def data_vars(path):
    ds = netCDF4.Dataset(path)
    return ds, {n: v for n, v in ds.variables.items() if n not in ds.dimensions}

def all_nan(ds, vars):
    out = []
    for n, v in vars.items():
        if v.dtype.kind == "f" and np.all(np.isnan(np.ma.filled(v[:], np.nan))):
            out.append(n)
    return out

def points(d):
    return json.load(open(d + "/summary.json"))["points"]

for d in ("paper", "split", "rates", "generator", "spelled"):
    ds, v = data_vars(d + "/results.nc")
    check(all_nan(ds, v) == [], f"{d}/results.nc: all-NaN variables {all_nan(ds, v)}")

# The paper's model: mu, V, lambda and the lambda derivatives; no r1/r2 ones.
ds, v = data_vars("paper/results.nc")
for n in ("friction_coefficient", "belt_speed", "switch_rate", "stick_fraction_dmean_dlambda",
          "stick_fraction_cv_mean"):
    check(n in v, f"paper: no {n}")
check(not any("_dmean_dr" in n for n in v), "paper: r1/r2 derivatives written")
p = points("paper")[0]
check("dmean_dlambda" in p and "control_variate" in p and "dmean_drates" not in p,
      f"paper summary.json point: {sorted(p)}")

# A swept mu: mu_s and mu_k resolve to it, point by point. They have no one
# value: no global attribute, null in summary.json's base (a new user found
# the first point's mu_s = 4 in both), their variables over the grid.
ds, v = data_vars("paper/results.nc")
check("mu_s" not in ds.ncattrs() and "mu_k" not in ds.ncattrs(),
      f"paper: mu_s/mu_k attributes {[a for a in ds.ncattrs() if a.startswith('mu')]}")
check(sorted(set(v["static_friction"][:].ravel().tolist())) == [4.0, 6.0], "paper: mu_s values")
base = json.load(open("paper/summary.json"))["parameters"]["base"]
check(base["mu_s"] is None and base["mu_k"] is None and base["mu"] is None, f"paper: base {base}")

# The file's comment names what it holds: a default sweep's paper statistics,
# not the family's X, W_f, W_c it does not write (a new user read them there).
ds, v = data_vars("default_selection/results.nc")
comment = ds.getncattr("comment")
check("95% CI of R, S_T/t_a, S_L/t_a, D, D_1, H;" in comment and "W_f" not in comment,
      f"default_selection: comment {comment[:160]}")
check("X_mean" not in v and "friction_power_mean" not in v, "default_selection: family written")

# mu_s/mu_k: "mu" is no parameter of this model: no variable, attribute,
# JSON member or CSV column; mu_s and mu_k are.
ds, v = data_vars("split/results.nc")
check("friction_coefficient" not in v, "split: a friction_coefficient variable")
check("mu" not in ds.ncattrs(), "split: a mu attribute")
check("static_friction" in v and ds.getncattr("mu_k") == 4.0, "split: mu_s / mu_k missing")
check(list(v["static_friction"][:].ravel()) == [4.0, 6.0, 4.0, 6.0] or
      sorted(set(v["static_friction"][:].ravel().tolist())) == [4.0, 6.0], "split: mu_s values")
sj = json.load(open("split/summary.json"))
check("mu" not in sj["parameters"]["base"], f"split: summary.json base {sj['parameters']['base']}")
check(all("mu" not in q for q in sj["points"]), "split: summary.json points carry mu")
header = open("split/summary.csv").readline().split(",")
check("mu" not in header and "mu_s" in header, f"split: summary.csv columns {header[:4]}")

# A two-level belt given its own rates: r1/r2 derivatives, no lambda.
ds, v = data_vars("rates/results.nc")
for n in ("stick_fraction_dmean_dr1", "stick_fraction_dmean_dr2",
          "sticks_per_time_dmean_dr1_ci95_low"):
    check(n in v, f"rates: no {n}")
check("switch_rate" not in v and "lambda" not in ds.ncattrs(), "rates: lambda written")
check("belt_speed" not in v, "rates: V written for a belt with its own levels")
check(not any("_dmean_dlambda" in n or "_cv_" in n for n in v), "rates: lambda derivatives")
p = points("rates")[0]
check("dmean_drates" in p and "dmean_dlambda" not in p and "control_variate" not in p and
      "lambda" not in p, f"rates summary.json point: {sorted(p)}")

# A belt given by its generator: the q_ij derivatives.
ds, v = data_vars("generator/results.nc")
check("stick_fraction_dmean_dgenerator" in v, "generator: no dmean_dgenerator")
check(not any(n in v for n in ("friction_coefficient", "belt_speed", "switch_rate")),
      "generator: mu, V or lambda written")
check("dmean_dgenerator" in points("generator")[0], "generator: summary.json")

# The paper's model spelled as a family member: mu is its value (2), not
# the unused default.
ds, v = data_vars("spelled/results.nc")
check(ds.getncattr("mu") == 2.0, f"spelled: mu attribute {ds.ncattrs() and ds.__dict__.get('mu')}")
check(json.load(open("spelled/summary.json"))["parameters"]["base"]["mu"] == 2,
      "spelled: summary.json base mu")

for b in bad:
    print("FAIL:", b, file=sys.stderr)
sys.exit(1 if bad else 0)
PYEOF
checks=$((checks + 1))
finish
