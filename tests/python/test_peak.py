"""stickslip.peak() against the CLI's `peak --format json`: the same numbers,
bit for bit, for every method; bad input raises stickslip.Error; Ctrl-C
stops a long search with KeyboardInterrupt."""
import json
import subprocess
import sys
import textwrap
import time

import pytest

import stickslip

ARGS = dict(mu=5, k=40, ta=10, range=(0.3, 30), target_halfwidth=0.3, initial_realizations=200)
CLI = ["peak", "--mu", "5", "--k", "40", "--ta", "10", "--range", "0.3:30",
       "--target-halfwidth", "0.3", "--initial-realizations", "200", "--format", "json"]


@pytest.mark.parametrize("method", ["common", "score", "independent"])
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
    with pytest.raises(stickslip.Error, match="lambda with the score method"):
        stickslip.peak(over="mu", range=(1, 9), target_halfwidth=0.1, method="score")


LONG_SEARCH = textwrap.dedent("""
    import sys, time, stickslip
    print("started", flush=True)
    t0 = time.monotonic()
    try:
        stickslip.peak(mu=0.5, k=40, range=(0.1, 30), target_halfwidth=0.001, threads=1)
    except KeyboardInterrupt:
        print("KeyboardInterrupt after %.1f s" % (time.monotonic() - t0), flush=True)
        sys.exit(42)
    sys.exit(0)
""")


def test_ctrl_c_stops_a_peak_search(ctrl_c):
    # The search (mu = 0.5 to a half-width of 0.001: hours) runs on a worker
    # thread without the GIL; Ctrl-C must reach it: no new sweep unit, and
    # KeyboardInterrupt once the units in flight are done.
    p = subprocess.Popen([sys.executable, "-c", LONG_SEARCH], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "started"
    time.sleep(2.0)  # inside the search (the import is done)
    assert p.poll() is None, p.stderr.read()
    sent = time.monotonic()
    ctrl_c(p, "stickslip.peak()")
    assert time.monotonic() - sent < 30
