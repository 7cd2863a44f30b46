"""stickslip.sweep(observe_times=...): the ensemble at chosen times
(docs/python.md), the same numbers as the CLI's `sweep --observe-times`
results.nc, as a grid's text or a sequence of times; the Dataset has the
coordinate `time` after the grid dimensions; bad times raise the CLI's
message (exit code 2)."""
import netCDF4
import numpy as np
import pytest

import stickslip

ARGS = dict(lam=[0.5, 3.8], mu=5.0, k=40.0, ta=20.0, realizations=200, seed=4)
CLI = ["--lambda", "0.5,3.8", "--mu", "5", "--k", "40", "--ta", "20", "--realizations", "200",
       "--seed", "4"]
OBSERVED = ["stick_probability", "stick_probability_std_error", "level_occupancy",
            "position_quantile", "velocity_quantile"] + [
    f"{x}_{s}" for x in ("position", "velocity", "relative_velocity", "energy")
    for s in ("mean", "variance", "ci95_half_width")]


def test_equals_the_cli_results_nc(cli, tmp_path):
    ds = stickslip.sweep(observe_times="lin:0:20:41", **ARGS)
    cli("sweep", *CLI, "--observe-times", "lin:0:20:41", "-o", tmp_path / "cli")
    nc = netCDF4.Dataset(tmp_path / "cli" / "results.nc")
    assert ds["time"].attrs["units"] == "s" and ds.sizes["time"] == 41
    np.testing.assert_array_equal(ds["time"].values, np.linspace(0, 20, 41))
    np.testing.assert_array_equal(ds["quantile"].values, [0.05, 0.25, 0.5, 0.75, 0.95])
    assert ds["stick_probability"].dims == ("lam", "time")
    assert ds["level_occupancy"].dims == ("lam", "time", "belt_level")
    assert ds["position_quantile"].dims == ("lam", "time", "quantile")
    for name in OBSERVED:
        assert ds[name].values.tobytes() == np.asarray(nc[name][:]).tobytes(), name
        assert ds[name].attrs["long_name"] and ds[name].attrs["units"], name
    # The ordinary statistics are those of the same sweep without observe times.
    plain = stickslip.sweep(**ARGS)
    for name in plain.data_vars:
        assert plain[name].equals(ds[name]), name
    assert "time" not in plain.dims and "stick_probability" not in plain


def test_a_sequence_is_the_same_as_its_text():
    times = np.linspace(0, 20, 5)
    a = stickslip.sweep(observe_times=times, **ARGS)
    b = stickslip.sweep(observe_times="0,5,10,15,20", **ARGS)
    c = stickslip.sweep(observe_times=[0, 5.0, 10, 15, 20], **ARGS)
    for name in OBSERVED:
        assert a[name].equals(b[name]) and a[name].equals(c[name]), name
    p = a["stick_probability"].sel(lam=3.8)
    assert ((p >= 0) & (p <= 1)).all() and float(p.max()) > 0
    np.testing.assert_allclose(a["level_occupancy"].sum("belt_level"), 1.0, rtol=0, atol=1e-12)


@pytest.mark.parametrize("value, message", [
    ("lin:0:30:4", "observe_times"),
    ([5.0, 2.0], "observe_times"),
    ([0, 25], "observe_times"),
    ("nan", "invalid observe_times: 'nan'"),
    ([0, float("nan")], "invalid observe_times entry #2: nan (allowed: a finite number)"),
    ("-1,2", "invalid observe_times: '-1,2'"),
    ([], "invalid observe_times: '' (allowed: at least one value"),
    (3.0, "invalid observe_times: 3.0 (allowed: a grid's text such as 'lin:0:50:501' or a 1-D "
          "sequence of finite times)"),
    ([[0, 1]], "invalid observe_times entry #1: [0, 1]"),
])
def test_bad_times_raise(value, message):
    with pytest.raises(stickslip.Error) as e:
        stickslip.sweep(observe_times=value, **ARGS)
    assert e.value.exit_code == 2
    assert message in str(e.value), str(e.value)


def test_beyond_t_a_is_the_cli_message(cli, tmp_path):
    with pytest.raises(stickslip.Error) as e:
        stickslip.sweep(observe_times="0,25", output=tmp_path / "py", **ARGS)
    p = cli("sweep", *CLI, "--observe-times", "0,25", "-o", tmp_path / "cli", check=False)
    assert p.returncode == 2 == e.value.exit_code
    assert str(e.value) in p.stderr
    assert not (tmp_path / "py").exists() and not (tmp_path / "cli").exists()
