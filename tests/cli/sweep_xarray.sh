# results.nc and summary.json as a new user reads them with xarray:
#  - each histogram has a bin coordinate <X>_bin with CF bounds <X>_bin_bounds,
#    and plots against it (the plotted x values are the bin centres, the bounds
#    are the bin edges also stored as <X>_bin_low/<X>_bin_high);
#  - every integer variable of the file stays an integer in xarray;
#  - every long_name fits one line of xarray's plot label (its own
#    label_from_attrs wraps at 30 characters);
#  - metadata: ranks and threads; the belt start law by name ("stationary", "-1");
#    swept parameters are null in parameters.base and listed in "swept".
source "$(dirname "$0")/lib.sh"

run_ok sweep --lambda 0.5,3 --mu 1,5 --k 4,40 --realizations 60 --bins 12 --seed 3 --threads 2 -o nc
printf '[initial]\nbelt_start = "-1"\n' >minus.toml
run_ok sweep --config minus.toml --lambda 2 --realizations 20 --seed 3 --threads 1 -o minus

MPLBACKEND=Agg "$PY" - nc minus <<'EOF' || fail "xarray checks (see above)"
import json
import sys

import matplotlib
matplotlib.use("Agg")
import netCDF4
import numpy as np
import xarray as xr
from xarray.plot.utils import label_from_attrs

main, minus = sys.argv[1], sys.argv[2]
problems = []
def check(ok, what):
    if not ok:
        problems.append(what)

raw = netCDF4.Dataset(f"{main}/results.nc")
ds = xr.open_dataset(f"{main}/results.nc", decode_coords="all")
point = {"lambda": 3.0, "mu": 5.0, "k": 40.0}
for x in ["stick_fraction", "stick_duration", "first_stick_duration", "slip_duration"]:
    try:
        da = ds[f"{x}_density"].sel(point)
        check(f"{x}_bin" in da.coords, f"{x}_density has no coordinate {x}_bin")
        centre = ds[f"{x}_bin"]
        check(raw[f"{x}_bin"].bounds == f"{x}_bin_bounds", f"{x}_bin bounds attribute")
        check(f"{x}_bin_bounds" in ds.coords, f"xarray does not take {x}_bin_bounds as bounds")
        bounds = ds[f"{x}_bin_bounds"].sel(point).values
        low, high = ds[f"{x}_bin_low"].sel(point).values, ds[f"{x}_bin_high"].sel(point).values
        check(bounds.shape == (12, 2), f"{x}_bin_bounds shape {bounds.shape}")
        check(np.array_equal(bounds[:, 0], low) and np.array_equal(bounds[:, 1], high),
              f"{x}_bin_bounds differ from {x}_bin_low/high")
        check(np.array_equal(low[1:], high[:-1]), f"{x} bins do not tile")
        check(np.allclose(centre.sel(point).values, (low + high) / 2, rtol=1e-15, atol=0),
              f"{x}_bin is not the bin centre")
        # The histogram plots against its bins with no edges rebuilt by hand.
        lines = da.plot.step(x=f"{x}_bin", where="mid")
        check(np.allclose(lines[0].get_xdata(), (low + high) / 2, rtol=1e-15, atol=0),
              f"{x} plot is not against the bin centres")
        matplotlib.pyplot.close("all")
    except Exception as e:  # report, and go on with the other checks
        check(False, f"{x}: {type(e).__name__}: {e}")

for name, var in raw.variables.items():
    if np.issubdtype(var.dtype, np.integer):
        check(np.issubdtype(ds[name].dtype, np.integer),
              f"{name} is {var.dtype} in the file but {ds[name].dtype} in xarray")
    label = label_from_attrs(ds[name])
    check("\n" not in label, f"{name}: plot label wraps: {label!r}")
check(int(getattr(raw, "ranks", -1)) == 1 and int(raw.threads) == 2, "nc ranks/threads")
check(raw.initial_belt_start == "stationary", f"initial_belt_start {raw.initial_belt_start!r}")
check(netCDF4.Dataset(f"{minus}/results.nc").initial_belt_start == "-1", "belt start -1 in nc")

par = json.load(open(f"{main}/summary.json"))["parameters"]
check(par.get("ranks") == 1 and par["threads"] == 2, "summary ranks/threads")
check(par["initial_conditions"]["belt_start"] == "stationary", "summary belt_start")
check(par.get("swept") == ["lambda", "mu", "k"], "summary lists the swept parameters")
check(all(par["base"][s] is None for s in ("lambda", "mu", "k")), f"base {par['base']}")
check(par["base"]["m"] == 1 and par["base"]["V"] == 1 and par["base"]["ta"] == 50, f"base {par['base']}")
par = json.load(open(f"{minus}/summary.json"))["parameters"]
check(par["initial_conditions"]["belt_start"] == "-1", "summary belt_start -1")
check(par.get("swept") == [] and par["base"]["mu"] == 5 and par["base"]["lambda"] == 2,
      f"nothing swept: {par['base']}")

for p in problems:
    print("xarray check:", p, file=sys.stderr)
sys.exit(1 if problems else 0)
EOF
pass
finish
