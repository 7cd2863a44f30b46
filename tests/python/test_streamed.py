"""A `sweep` of more than 1,024 points writes its outputs window by window as
it runs (docs/outputs.md); stickslip.sweep keeps every point and writes them
at the end. The two sets of files are the same: summary.csv byte for byte,
summary.json's points and parameters line for line, results.nc's variables
and their attributes value for value."""
import json

import netCDF4
import numpy as np
import xarray as xr

import stickslip

LAM = np.geomspace(0.1, 30, 60)  # 60 x 20 = 1,200 points: windows of 32 and 28 lambda rows
MU = np.linspace(0.5, 7, 20)
CLI = ["--lambda", ",".join(repr(float(x)) for x in LAM), "--mu", ",".join(repr(float(x)) for x in MU),
       "--ta", "10", "--realizations", "10", "--block-size", "5", "--seed", "3"]


def test_the_streamed_cli_files_are_pythons(cli, tmp_path):
    cli("sweep", *CLI, "-o", tmp_path / "cli")
    stickslip.sweep(lam=LAM, mu=MU, ta=10.0, realizations=10, block_size=5, seed=3,
                    output=tmp_path / "py")
    a, b = tmp_path / "cli", tmp_path / "py"
    assert (a / "summary.csv").read_bytes() == (b / "summary.csv").read_bytes()
    ja, jb = (json.loads((d / "summary.json").read_text()) for d in (a, b))
    assert ja["points"] == jb["points"]
    run_keys = {"command_line", "created_utc", "threads", "git_revision", "version", "config"}
    assert {k: v for k, v in ja["parameters"].items() if k not in run_keys} == \
        {k: v for k, v in jb["parameters"].items() if k not in run_keys}
    with xr.open_dataset(a / "results.nc") as da, xr.open_dataset(b / "results.nc") as db:
        run_attrs = {"source", "history", "git_revision", "command_line", "created_utc",
                     "resolved_config", "elapsed_seconds", "threads", "version"}
        assert {k: str(v) for k, v in da.attrs.items() if k not in run_attrs} == \
            {k: str(v) for k, v in db.attrs.items() if k not in run_attrs}
        assert sorted(da.variables) == sorted(db.variables)
        for name in db.variables:
            assert da[name].dims == db[name].dims, name
            assert da[name].attrs == db[name].attrs, name
            assert da[name].values.tobytes() == db[name].values.tobytes(), name
    # The windows' rows bound the streamed file's chunks: 32 rows (1,024 / 20 = 51, rounded down to a power of two).
    with netCDF4.Dataset(a / "results.nc") as nc:
        chunks = [v.chunking() for v in nc.variables.values()]
    assert any(c != "contiguous" and c[0] == 32 for c in chunks), chunks
    assert sorted(p.name for p in a.iterdir() if not p.name.startswith(".")) == \
        ["results.nc", "summary.csv", "summary.json"]
