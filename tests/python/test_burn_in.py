"""stickslip.sweep(burn_in=T): every statistic over [T, t_a] (docs/python.md),
the same numbers as the CLI's `sweep --burn-in`, the attribute burn_in only
with a burn-in, burn_in=0 the sweep without it, and bad values refused with
the CLI's message (exit code 2)."""
import netCDF4
import numpy as np
import pytest

import stickslip

ARGS = dict(lam=[0.5, 3.8], mu=5.0, k=40.0, ta=20.0, realizations=100, seed=4, statistics="all")
CLI = ["--lambda", "0.5,3.8", "--mu", "5", "--k", "40", "--ta", "20", "--realizations", "100",
       "--seed", "4", "--statistics", "all"]


def test_equals_the_cli_results_nc(cli, tmp_path):
    ds = stickslip.sweep(burn_in=7.5, **ARGS)
    cli("sweep", *CLI, "--burn-in", "7.5", "-o", tmp_path / "cli")
    nc = netCDF4.Dataset(tmp_path / "cli" / "results.nc")
    assert ds.attrs["burn_in"] == 7.5 == nc.burn_in
    assert "burn_in = 7.5" in ds.attrs["resolved_config"].splitlines()
    for name in ("stick_fraction_mean", "sticks_per_time_std", "first_stick_duration_mean",
                 "stick_duration_counts", "belt_level_fraction_mean", "friction_power_mean",
                 "stick_survival", "no_stick_count"):
        assert ds[name].values.tobytes() == np.asarray(nc[name][:]).tobytes(), name


def test_zero_is_no_burn_in_and_the_window_is_shorter():
    plain = stickslip.sweep(**ARGS)
    zero = stickslip.sweep(burn_in=0, **ARGS)
    assert "burn_in" not in plain.attrs and "burn_in" not in zero.attrs
    for name in plain.data_vars:
        assert plain[name].equals(zero[name]), name
    late = stickslip.sweep(burn_in=10.0, **ARGS)
    # The level fractions of [T, t_a] still sum to 1; R changes at lambda = 0.5.
    np.testing.assert_allclose(late.belt_level_fraction_mean.sum("belt_level"), 1.0, rtol=1e-12)
    assert abs(float(late.stick_fraction_mean.sel(lam=0.5) - plain.stick_fraction_mean.sel(lam=0.5))) > 1e-3


@pytest.mark.parametrize("value, message", [
    (-1.0, "invalid burn_in: -1 (allowed: 0 <= burn_in < t_a = 20 (the shortest window"),
    (20.0, "invalid burn_in: 20 (allowed: 0 <= burn_in < t_a = 20"),
    (35, "invalid burn_in: 35 (allowed: 0 <= burn_in < t_a = 20"),
    (float("nan"), "invalid burn_in: nan (allowed: a finite number)"),
    ("ten", "invalid burn_in: 'ten' (allowed: a finite number; got text, not a number)"),
    (True, "invalid burn_in: True (allowed: a finite number; a bool is not a number)"),
])
def test_bad_values_raise_the_cli_error(cli, value, message):
    with pytest.raises(stickslip.Error) as e:
        stickslip.sweep(burn_in=value, **ARGS)
    assert e.value.exit_code == 2
    assert str(e.value).startswith(message), str(e.value)


def test_out_of_range_is_the_cli_message(cli, tmp_path):
    with pytest.raises(stickslip.Error) as e:
        stickslip.sweep(burn_in=20.0, output=tmp_path / "py", **ARGS)
    p = cli("sweep", *CLI, "--burn-in", "20", "-o", tmp_path / "cli", check=False)
    assert p.returncode == 2 == e.value.exit_code
    assert str(e.value) in p.stderr
    assert not (tmp_path / "py").exists() and not (tmp_path / "cli").exists()


@pytest.mark.parametrize("law", [None, "uniform(4,6)"])
def test_simulate_replays_the_sweeps_record_with_the_burn_in(tmp_path, law):
    """simulate(realization=r, burn_in=T).record is row r of the sweep's
    records.csv with burn_in=T, bit for bit; without burn_in it differs."""
    import csv
    mu = law or 5.0
    stickslip.sweep(lam=3.8, mu=mu, k=40.0, ta=20.0, realizations=40, seed=4, records=True,
                    burn_in=7.5, output=tmp_path / "out")
    rows = list(csv.DictReader(open(tmp_path / "out" / "records.csv")))
    for r in (0, 17, 39):
        sim = stickslip.simulate(lam=3.8, mu=mu, k=40.0, ta=20.0, seed=4, realization=r,
                                 burn_in=7.5).record
        row = rows[r]
        assert int(row["realization"]) == r
        assert (sim["S_T"], sim["S_L"]) == (int(row["sticks"]), int(row["slips"]))
        assert sim["R"] == float(row["stick_fraction"])
        whole = stickslip.simulate(lam=3.8, mu=mu, k=40.0, ta=20.0, seed=4, realization=r).record
        assert whole["R"] != sim["R"]
    with pytest.raises(stickslip.Error) as e:
        stickslip.simulate(lam=3.8, mu=mu, ta=20.0, realization=0, burn_in=20.0)
    assert str(e.value).startswith("invalid burn_in: 20 (allowed: 0 <= burn_in < t_a = 20")
