"""One table of derived estimates (include/stickslip/estimates.hpp): summary.json,
results.nc, summary.csv and Python's Dataset carry the same estimates. For
three sweeps that together reach every row (Poisson switching with common
random numbers and records; a two-level belt given its own rates; a
three-level belt given by its generator, with one q_ij = 0), the CLI's
summary.json, results.nc and summary.csv and stickslip.sweep()'s Dataset are
reduced to the same key set: (point, row, quantity, index, member), the
index being "" (none), r1/r2, the axis, or "i,j" of a generator entry, the
member "estimate" (the value with its interval) or the row's extra
(variance_reduction, pairs). An estimate present in one output and missing
from another fails."""
import csv
import json
import math
import re

import netCDF4
import numpy as np
import pytest

import stickslip
from stickslip import _stickslip

KINDS = _stickslip.estimate_kinds()
COMMON = dict(k=40.0, ta=10.0, realizations=60, block_size=20, seed=3, threads=1, records=True,
              common_random_numbers=True, statistics="all")
# (name, CLI arguments, stickslip.sweep() keywords)
SWEEPS = [
    ("poisson", ["--lambda", "1,2", "--mu", "5"], dict(lam=[1.0, 2.0], mu=5.0)),
    ("rates", ["--belt-levels", "1,-0.5", "--belt-rates", "1,2", "--mu", "3,4"],
     dict(belt_levels=[1.0, -0.5], belt_rates=[1.0, 2.0], mu=[3.0, 4.0])),
    ("generator", ["--belt-levels", "1,0,-0.5", "--belt-generator", "-2,1.2,0.8;1,-1,0;0.4,0.6,-1",
                   "--mu", "4,6"],
     dict(belt_levels=[1.0, 0.0, -0.5], belt_generator=[[-2, 1.2, 0.8], [1, -1, 0], [0.4, 0.6, -1]],
          mu=[4.0, 6.0])),
]


def cli_arguments(extra):
    c = COMMON
    return ["sweep", *extra, "--k", c["k"], "--ta", c["ta"], "--realizations", c["realizations"],
            "--block-size", c["block_size"], "--seed", c["seed"], "--threads", c["threads"],
            "--records", "--common-random-numbers", "--statistics", c["statistics"]]


def json_keys(points):
    """(point, row, quantity summary name, index, member) of every estimate in
    summary.json; member is "estimate" for the value with its error and
    interval, else the extra's name."""
    keys = set()

    def leaf(p, row, q, index, e):
        assert {row["value_member"], "std_error", "ci95"} <= e.keys(), (row["name"], e)
        if math.isfinite(e[row["value_member"]]):
            keys.add((p, row["name"], q, index, "estimate"))
        if row["extra"]:
            keys.add((p, row["name"], q, index, row["extra"]))

    names = {row["name"] for row in KINDS}
    for p, point in enumerate(points):
        for key in point:  # no estimate outside the table
            if key.startswith("dmean") or key in ("control_variate", "crn_slopes"):
                assert key in names, key
        for row in KINDS:
            by_q = point.get(row["name"], {})
            for first, inner in by_q.items():
                if row["index"] == "none":
                    leaf(p, row, first, "", inner)
                elif row["index"] == "belt_rate":
                    for r, e in inner.items():
                        leaf(p, row, first, r, e)
                elif row["index"] == "generator_entry":
                    for e in inner:
                        leaf(p, row, first, f"{e['from']},{e['to']}", e)
                else:  # axis first, then quantity
                    for q, e in inner.items():
                        leaf(p, row, q, first, e)
    return keys


def dataset_keys(variables, axes):
    """The same keys from results.nc's (or the Dataset's) variables, each
    flattened over the grid in point order: an estimate where its value and
    both interval ends exist (not NaN), an extra where its variable exists
    (pairs > 0)."""
    keys = set()
    for row in KINDS:
        indices = {"none": [""], "belt_rate": ["r1", "r2"], "generator_entry": ["q_ij"],
                   "axis": axes}[row["index"]]
        for name, summary_name in row["quantities"]:
            for index in indices:
                stem = row["variable"].format(q=name, i=index)
                value = stem + row["value_suffix"]
                if value not in variables:
                    for v in (stem + "_ci95_low", stem + "_ci95_high", f"{stem}_{row['extra']}"):
                        assert v not in variables, f"{v} without {value}"
                    continue
                ends = [np.asarray(variables[v]) for v in (value, stem + "_ci95_low",
                                                           stem + "_ci95_high")]
                if row["index"] == "generator_entry":
                    n = ends[0].shape[-1]
                    flat = [e.reshape(-1, n * n) for e in ends]
                    for p in range(flat[0].shape[0]):
                        for ij in range(n * n):
                            if all(np.isfinite(f[p, ij]) for f in flat):
                                keys.add((p, row["name"], summary_name, f"{ij // n + 1},{ij % n + 1}",
                                          "estimate"))
                    continue
                flat = [e.reshape(-1) for e in ends]
                extra = variables.get(f"{stem}_{row['extra']}") if row["extra"] else None
                if extra is not None:
                    extra = np.asarray(extra).reshape(-1)
                for p in range(flat[0].shape[0]):
                    if all(np.isfinite(f[p]) for f in flat):
                        keys.add((p, row["name"], summary_name, index, "estimate"))
                    if extra is not None and (row["extra"] != "pairs" or extra[p] > 0):
                        keys.add((p, row["name"], summary_name, index, row["extra"]))
    return keys


def csv_keys(path, axes):
    """The same keys from summary.csv's columns (named like results.nc's
    variables, by the summary name; a generator's entries one by one as
    <stem>_<i>_<j>)."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    header = rows[0].keys()
    keys = set()

    def add(row, summary_name, index, stem):
        for p, r in enumerate(rows):
            ends = [float(r[c]) for c in (stem + row["value_suffix"], stem + "_ci95_low",
                                          stem + "_ci95_high")]
            if all(math.isfinite(e) for e in ends):
                keys.add((p, row["name"], summary_name, index, "estimate"))
            extra = r.get(f"{stem}_{row['extra']}") if row["extra"] else None
            if extra is not None and (row["extra"] != "pairs" or int(extra) > 0):
                keys.add((p, row["name"], summary_name, index, row["extra"]))

    for row in KINDS:
        for _, summary_name in row["quantities"]:
            if row["index"] == "generator_entry":
                stem = row["variable"].format(q=summary_name, i="")
                for column in header:
                    m = re.fullmatch(re.escape(stem) + r"_(\d+)_(\d+)", column)
                    if m:
                        add(row, summary_name, f"{m[1]},{m[2]}", column)
                continue
            indices = {"none": [""], "belt_rate": ["r1", "r2"], "axis": axes}[row["index"]]
            for index in indices:
                stem = row["variable"].format(q=summary_name, i=index)
                if stem + row["value_suffix"] in header:
                    add(row, summary_name, index, stem)
    return keys


def test_every_row_is_reached():
    """The sweeps below exercise every row of the table."""
    assert {row["name"] for row in KINDS} == {
        "dmean_dlambda", "dmean_dlambda_causal", "control_variate", "dmean_drates",
        "dmean_dgenerator", "crn_slopes"}


@pytest.mark.parametrize("name,flags,keywords", SWEEPS, ids=[s[0] for s in SWEEPS])
def test_json_netcdf_and_python_carry_the_same_estimates(tmp_path, cli, name, flags, keywords):
    out = tmp_path / name
    cli(*cli_arguments(flags), "-o", out)
    points = json.loads((out / "summary.json").read_text())["points"]
    from_json = json_keys(points)
    with netCDF4.Dataset(out / "results.nc") as f:
        f.set_auto_mask(False)
        axes = f.getncattr("swept_parameters").split()
        from_netcdf = dataset_keys({v: f.variables[v][...] for v in f.variables}, axes)
    from_csv = csv_keys(out / "summary.csv", axes)
    ds = stickslip.sweep(**COMMON, **keywords)
    from_python = dataset_keys({v: ds[v].values for v in ds.variables}, axes)
    rows = {k[1] for k in from_json}
    expected = {"poisson": {"dmean_dlambda", "dmean_dlambda_causal", "control_variate",
                            "crn_slopes"},
                "rates": {"dmean_drates", "crn_slopes"},
                "generator": {"dmean_dgenerator", "crn_slopes"}}[name]
    assert rows == expected, rows
    assert from_json == from_netcdf, (sorted(from_json - from_netcdf), sorted(from_netcdf - from_json))
    assert from_python == from_netcdf, (sorted(from_python ^ from_netcdf))
    assert from_csv == from_netcdf, (sorted(from_csv - from_netcdf), sorted(from_netcdf - from_csv))
