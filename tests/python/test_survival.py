"""stickslip.sweep(statistics=["survival"]): the survival group's variables
(docs/python.md), the same numbers as the CLI's results.nc, and bad group
names refused with the CLI's message."""
import netCDF4
import numpy as np
import pytest

import stickslip

ARGS = dict(lam=[0.5, 3.8], mu=5.0, k=40.0, ta=20.0, realizations=100, seed=4, survival_bins=30)
CLI = ["--lambda", "0.5,3.8", "--mu", "5", "--k", "40", "--ta", "20", "--realizations", "100",
       "--seed", "4", "--survival-bins", "30", "--statistics", "paper,survival"]
NAMES = ["survival", "survival_ci95_low", "survival_ci95_high", "at_risk", "restricted_mean"]


def test_survival_variables_equal_the_cli_results_nc(cli, tmp_path):
    ds = stickslip.sweep(statistics=["paper", "survival"], **ARGS)
    cli("sweep", *CLI, "-o", tmp_path / "cli")
    nc = netCDF4.Dataset(tmp_path / "cli" / "results.nc")
    assert ds.attrs["statistics"] == "paper,survival"
    for law in ("stick", "slip"):
        coordinate = law + "_duration"
        assert ds[coordinate].attrs["units"] == "s" and ds.sizes[coordinate] == 31
        np.testing.assert_array_equal(ds[coordinate].values, nc[coordinate][:])
        for name in NAMES:
            v = ds[f"{law}_{name}"]
            want = ("lam",) if name == "restricted_mean" else ("lam", coordinate)
            assert v.dims == want, (name, v.dims)
            assert v.values.tobytes() == np.asarray(nc[f"{law}_{name}"][:]).tobytes(), name
    s = ds["stick_survival"].sel(lam=3.8)
    assert s[0] == 1 and (np.diff(s.values) <= 0).all()


def test_a_single_name_and_all_select_it_too():
    one = stickslip.sweep(statistics="survival", **ARGS)
    every = stickslip.sweep(statistics=["default", "all"], **ARGS)
    assert one["stick_survival"].equals(every["stick_survival"])


def test_one_string_is_the_cli_comma_list():
    ds = stickslip.sweep(statistics="paper, survival", **ARGS)
    assert ds.attrs["statistics"] == "paper,survival" and "stick_survival" in ds


def test_off_by_default():
    ds = stickslip.sweep(**{k: v for k, v in ARGS.items() if k != "survival_bins"})
    assert ds.attrs["statistics"] == "paper"
    assert "stick_survival" not in ds and "stick_duration" not in ds.coords


def test_bad_names_raise_the_cli_error(cli):
    with pytest.raises(stickslip.Error) as e:
        stickslip.sweep(statistics=["survial"], **ARGS)
    assert e.value.exit_code == 2
    p = cli("sweep", "--lambda", "1", "--statistics", "survial", "-o", "none", check=False)
    assert p.returncode == 2
    # The same message but for the name of the setting (the keyword, not --statistics).
    assert str(e.value).startswith(
        "invalid statistics: 'survial' (allowed: a comma list of paper, family, derivatives, "
        "survival, default, all, or statistics by name (R, ")
    assert str(e.value).replace("invalid statistics", "invalid --statistics") in p.stderr
    with pytest.raises(stickslip.Error, match="invalid statistics: 3"):
        stickslip.sweep(statistics=[3], **ARGS)
