"""stickslip.peak() against the CLI's `peak --format json`: the same numbers,
bit for bit, for both methods; bad input raises stickslip.Error."""
import json

import pytest

import stickslip

ARGS = dict(mu=5, k=40, ta=10, range=(0.3, 30), target_halfwidth=0.3, initial_realizations=200)
CLI = ["peak", "--mu", "5", "--k", "40", "--ta", "10", "--range", "0.3:30",
       "--target-halfwidth", "0.3", "--initial-realizations", "200", "--format", "json"]


@pytest.mark.parametrize("method", ["common", "independent"])
def test_peak_equals_the_cli(cli, method):
    ours = stickslip.peak(**ARGS, method=method, threads=2)
    theirs = json.loads(cli(*CLI, "--method", method, "--threads", "1").stdout)
    for key in ("argmax", "argmax_sampling_halfwidth", "argmax_model_bias", "max",
                "realizations", "stages", "target_met", "method", "statistic", "over"):
        assert ours[key] == theirs[key], key
    assert list(ours["argmax_ci95"]) == theirs["argmax_ci95"]
    lo, hi = ours["argmax_ci95"]
    assert lo <= ours["argmax"] <= hi and (hi - lo) / 2 <= 0.3 * (1 + 1e-12)


def test_peak_bad_input_raises_error():
    with pytest.raises(stickslip.Error, match="statistic"):
        stickslip.peak(**{**ARGS, "statistic": "D"})
    with pytest.raises(stickslip.Error, match="range"):
        stickslip.peak(mu=5, over="mu", target_halfwidth=0.1)
    with pytest.raises(stickslip.Error, match="lambda"):
        stickslip.peak(mu=5, lam=2, range=(0.3, 30))
    with pytest.raises(stickslip.Error, match="method"):
        stickslip.peak(**ARGS, method="magic")
