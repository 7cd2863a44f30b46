"""stickslip.sweep() against the CLI's `sweep`: the same Dataset as its
results.nc, the statistics of summary.json, output=DIR, resume, Ctrl-C,
progress, the GIL, errors."""
import json
import os
import re
import subprocess
import sys
import textwrap
import threading
import time

import numpy as np
import pytest
import xarray as xr

import stickslip

HERE = os.path.dirname(os.path.abspath(__file__))
COMPARE = os.path.join(HERE, "..", "resume", "compare_outputs.py")
# Global attributes that name the run rather than its results.
RUN_ATTRIBUTES = {"history", "command_line", "created_utc", "elapsed_seconds", "threads", "ranks"}

GRID = dict(lam=[0.1, 0.9, 3.8, 30.0], mu=[0.5, 5.0], k=40.0)
CLI_GRID = ["--lambda", "0.1,0.9,3.8,30", "--mu", "0.5,5", "--k", "40"]


def as_results_nc(ds):
    """A Dataset as results.nc names it: Python names the lambda dimension
    `lam` (with the coordinate `lambda` along it); the file names it lambda."""
    if "lam" in ds.dims:
        assert ds["lam"].values.tobytes() == ds["lambda"].values.tobytes()
        assert ds["lam"].attrs == ds["lambda"].attrs
        ds = ds.swap_dims({"lam": "lambda"}).drop_vars("lam")
    return ds


def assert_same_dataset(a, b):
    a, b = as_results_nc(a), as_results_nc(b)
    assert list(a.dims) == list(b.dims) and dict(a.sizes) == dict(b.sizes)
    assert set(a.coords) == set(b.coords)
    assert set(a.data_vars) == set(b.data_vars)
    for name in list(a.coords) + list(a.data_vars):
        va, vb = a[name], b[name]
        assert va.dims == vb.dims, name
        assert va.dtype == vb.dtype, name
        assert va.values.tobytes() == vb.values.tobytes(), name
        assert va.attrs == vb.attrs, name
    ka = {k: v for k, v in a.attrs.items() if k not in RUN_ATTRIBUTES}
    kb = {k: v for k, v in b.attrs.items() if k not in RUN_ATTRIBUTES}
    assert ka.keys() == kb.keys()
    for k in ka:
        assert np.array_equal(np.asarray(ka[k]), np.asarray(kb[k])), k


@pytest.fixture(scope="module")
def cli_sweep(tmp_path_factory, cli):
    out = tmp_path_factory.mktemp("cli") / "sweep"
    cli("sweep", *CLI_GRID, "--realizations", 300, "--seed", 7, "--records", "-o", out)
    return out


def test_dataset_equals_the_cli_results_nc(cli_sweep):
    ours = stickslip.sweep(**GRID, realizations=300, seed=7, records=True)
    with xr.open_dataset(cli_sweep / "results.nc") as theirs:
        assert_same_dataset(ours, theirs.load())
    assert list(ours.dims)[:2] == ["lam", "mu"]  # the CLI's order; lambda is named lam


def test_statistics_equal_summary_json(cli_sweep):
    ours = stickslip.sweep(**GRID, realizations=300, seed=7)
    summary = json.load(open(cli_sweep / "summary.json"))
    checked = 0
    for p in summary["points"]:
        sel = ours.sel(lam=p["lambda"], mu=p["mu"])
        for key, value in p.items():
            if isinstance(value, dict) and "mean" in value:
                name = "stick_fraction" if key == "R" else key
                assert float(sel[name + "_mean"]) == value["mean"], key
                assert float(sel[name + "_std"]) == value["std"], key
                checked += 1
    assert checked == 6 * len(summary["points"])  # the 6 quantities of the paper group (default)


def test_open_reads_results_nc(cli_sweep):
    ds = stickslip.open(cli_sweep)
    with xr.open_dataset(cli_sweep / "results.nc") as theirs:
        assert_same_dataset(ds, theirs.load())
    with pytest.raises(stickslip.Error, match="does not exist"):
        stickslip.open(cli_sweep / "nope.nc")


def test_output_dir_writes_the_cli_files(cli_sweep, tmp_path):
    out = tmp_path / "py"
    stickslip.sweep(**GRID, realizations=300, seed=7, records=True, output=str(out))
    for f in ("results.nc", "summary.json", "summary.csv", "records.csv"):
        assert (out / f).exists(), f
    assert not (out / ".journal").exists()
    p = subprocess.run(["/usr/bin/python3", COMPARE, str(cli_sweep), str(out)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr


def test_bad_input_raises_error_with_the_cli_message(cli, tmp_path):
    p = cli("sweep", "--lambda", "-2", "--mu", "0.5,5", "--realizations", 10, "-o", tmp_path / "bad",
            check=False)
    assert p.returncode == 2
    with pytest.raises(stickslip.Error) as e:
        stickslip.sweep(lam=-2.0, mu=[0.5, 5], realizations=10)
    assert p.stderr.strip() == f"stickslip: error: {e.value}"
    with pytest.raises(stickslip.Error, match="^invalid lam: "):  # the keyword, not --lambda
        stickslip.sweep(lam=[0.1, -2.0], realizations=10)
    with pytest.raises(stickslip.Error):
        stickslip.sweep(lam=1, realizations=0)
    assert not (tmp_path / "bad").exists()


def test_the_recorded_call_replays_the_run(tmp_path):
    """results.nc's command_line is the call: every keyword that is not its
    default (a new user found observe_times, statistics, records and
    output missing, so the record did not replay the run). Evaluated, it
    gives the same Dataset."""
    out = tmp_path / "first"
    ds = stickslip.sweep(lam=np.array([0.5, 3.8]), mu=5, k=40, realizations=40, seed=11,
                         observe_times=np.linspace(0, 50, 6), statistics=["paper", "survival"],
                         survival_bins=30, records=True, burn_in=0.0, output=str(out))
    call = ds.attrs["command_line"]
    assert call.startswith("python: stickslip.sweep(lam=[0.5, 3.8], mu=5.0, k=40.0, "), call
    for keyword in ("realizations=40", "seed=11", "observe_times=[0.0, 10.0, 20.0, 30.0, 40.0, "
                    "50.0]", "statistics=['paper', 'survival']", "survival_bins=30",
                    "records=True", f"output={str(out)!r}"):
        assert keyword in call, (keyword, call)
    assert "burn_in" not in call and "threads" not in call  # defaults are left out
    again = eval(call[len("python: "):].replace(repr(str(out)), repr(str(tmp_path / "again"))),
                 {"stickslip": stickslip})
    assert_same_dataset(ds, again)
    # Values as they were read (a review found these written as given): a
    # pathlib output, float32 times in a list (their exact doubles), numpy
    # integers, a statistics name as one str.
    ds = stickslip.sweep(lam=[0.5], realizations=np.int64(20), seed=np.uint32(3),
                         observe_times=[np.float32(0.1), np.float32(5.3)], statistics="survival",
                         output=tmp_path / "path")
    call = ds.attrs["command_line"]
    assert f"output={str(tmp_path / 'path')!r}" in call and "realizations=20, seed=3" in call, call
    again = eval(call[len("python: "):].replace(repr(str(tmp_path / "path")), "None"),
                 {"stickslip": stickslip})
    assert ds["time"].values.tobytes() == again["time"].values.tobytes()
    assert_same_dataset(ds, again)


def test_survival_bins_without_the_survival_statistics_is_refused(cli, tmp_path):
    """As the CLI refuses --survival-bins without --statistics survival (it
    was taken and ignored in Python)."""
    p = cli("sweep", "--lambda", 1, "--survival-bins", 50, "--realizations", 10,
            "-o", tmp_path / "c", check=False)
    assert p.returncode == 2 and "only with the survival statistics" in p.stderr
    with pytest.raises(stickslip.Error, match=r"^invalid survival_bins: '50' \(allowed: only with "
                       "the survival statistics"):
        stickslip.sweep(lam=1, realizations=10, survival_bins=50, output=str(tmp_path / "p"))
    assert not (tmp_path / "c").exists() and not (tmp_path / "p").exists()
    ds = stickslip.sweep(lam=1, realizations=10, survival_bins=50, statistics="survival")
    assert ds.sizes["stick_duration"] == 51


def test_progress_bar_reaches_the_total(capsys):
    stickslip.sweep(lam=[0.5, 2.0], realizations=200, progress=True)
    err = capsys.readouterr().err
    assert "8/8" in err  # 2 points x 4 blocks of 50


def test_the_gil_is_released_while_simulating():
    ticks = []
    stop = threading.Event()

    def ticker():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.001)
    t = threading.Thread(target=ticker)
    t.start()
    before = len(ticks)
    stickslip.sweep(lam=np.logspace(-1, np.log10(30), 8), mu=[0.5, 5], realizations=3000)
    during = len(ticks) - before
    stop.set()
    t.join()
    assert during > 20  # the other Python thread ran while the sweep did


INTERRUPTED = textwrap.dedent("""
    import sys, stickslip
    try:
        stickslip.sweep(lam=[0.1, 1, 5, 20], mu=[0.5, 5], ta=400, realizations=8000,
                        threads=1, output=sys.argv[1], checkpoint_interval=0)
    except KeyboardInterrupt:
        print("KeyboardInterrupt", flush=True)
        sys.exit(42)
    sys.exit(0)
""")


def test_ctrl_c_stops_and_resume_completes_identically(tmp_path, ctrl_c):
    out = tmp_path / "interrupted"
    env = dict(os.environ)
    p = subprocess.Popen([sys.executable, "-c", INTERRUPTED, str(out)], env=env,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    def has_segment():
        j = out / ".journal"
        return j.exists() and any(j.glob("seg-*"))
    deadline = time.time() + 60
    while time.time() < deadline and not has_segment() and p.poll() is None:
        time.sleep(0.02)
    assert p.poll() is None, "the sweep finished before it could be interrupted (make it longer)"
    ctrl_c(p, "the sweep", timeout=30)
    assert (out / ".journal").exists() and not (out / "results.nc").exists()
    resumed = stickslip.sweep(lam=[0.1, 1, 5, 20], mu=[0.5, 5], ta=400, realizations=8000,
                              output=str(out), resume=True)
    whole = stickslip.sweep(lam=[0.1, 1, 5, 20], mu=[0.5, 5], ta=400, realizations=8000)
    assert_same_dataset(resumed, whole)


def test_an_exception_in_the_progress_callback_stops_the_sweep_cleanly(tmp_path):
    # KeyboardInterrupt may land inside tqdm's refresh: the exception must stop
    # the sweep and be raised after the units in flight, not abort the process.
    script = textwrap.dedent("""
        import sys, stickslip._stickslip as core
        calls = []
        def cb(done, total):
            calls.append(done)
            raise RuntimeError("callback failed")
        try:
            core.run_sweep({"ta": 400.0}, [("lambda", [0.1, 1.0, 5.0, 20.0])], 4000, 1, 50, 50, False,
                           "fast", core.default_max_events, 1, sys.argv[1], False, False, 0.0,
                           sys.argv[1] + "/r.nc", "test", cb)
        except RuntimeError as e:
            print("raised:", e, flush=True)
            sys.exit(0)
        sys.exit(3)
    """)
    out = tmp_path / "cb"
    p = subprocess.run([sys.executable, "-c", script, str(out)], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, (p.returncode, p.stderr[-2000:])
    assert "raised: callback failed" in p.stdout
    assert (out / ".journal").exists()  # the finished units are journaled for a resume


def test_common_random_numbers_and_target_ci_equal_the_cli(cli, tmp_path):
    """Common random numbers and --target-ci give the CLI's results.nc, bit for bit."""
    out = tmp_path / "cli"
    cli("sweep", *CLI_GRID, "--common-random-numbers", "--target-ci", "R:0.004",
        "--max-realizations", "20000", "--min-realizations", "500", "--threads", "2",
        "-o", str(out))
    ds = stickslip.sweep(**GRID, realizations=20000, common_random_numbers=True,
                         target_ci="R:0.004", min_realizations=500, threads=2)
    assert_same_dataset(ds, xr.open_dataset(out / "results.nc"))
    assert int(ds.attrs["common_random_numbers"]) == 1
    hw = (ds.stick_fraction_ci95_high - ds.stick_fraction_ci95_low) / 2
    assert float(hw.max()) <= 0.004
    assert len(set(ds.realizations.values.ravel().tolist())) > 1


def test_an_unreachable_target_ci_warns_as_the_cli_does():
    # every point stops at its cap: a UserWarning names how many, and the widest,
    # in the CLI's words (the cap without a flag's name: Python's is realizations=)
    with pytest.warns(UserWarning, match=r"2 of 2 grid points did not reach the target 95 % "
                                         r"half-width 0.0001 of the mean of R within the cap "
                                         r"of 400 realizations per point \(the widest: "
                                         r"[0-9.]+, at lambda = 1\); raise the cap, or read "
                                         r"each point's interval"):
        ds = stickslip.sweep(lam=[1.0, 3.8], mu=5.0, k=40.0, realizations=400, seed=3,
                             target_ci="R:0.0001", min_realizations=100)
    # the Dataset keeps it as results.nc does, with the cap named for everyone
    assert re.match(r"2 of 2 grid points did not reach the target 95 % half-width 0.0001 of "
                    r"the mean of R within the cap of 400 realizations per point \(the widest: "
                    r"[0-9.]+, at lambda = 1\); raise the cap, or read", ds.attrs["warning"])


def test_a_finished_resume_warns_of_its_unmet_target_again(tmp_path):
    args = dict(lam=[1.0, 3.8], mu=5.0, k=40.0, realizations=400, seed=3, target_ci="R:0.0001",
                min_realizations=100, output=str(tmp_path / "out"))
    with pytest.warns(UserWarning, match="within the cap of 400 realizations per point"):
        first = stickslip.sweep(**args)
    # the run is finished: resume=True reads it back, and says what its outputs record
    with pytest.warns(UserWarning, match="within the cap of 400 realizations per point") as caught:
        again = stickslip.sweep(resume=True, **args)
    assert [str(w.message) for w in caught if "did not reach" in str(w.message)] == \
        [first.attrs["warning"]]
    assert again.attrs["warning"] == first.attrs["warning"]


def test_simulate_replays_a_common_random_number_realization():
    ds = stickslip.sweep(lam=[1.0, 3.8], mu=5.0, k=40.0, realizations=50, seed=3,
                         common_random_numbers=True)
    assert int(ds.attrs["common_random_numbers"]) == 1
    one = stickslip.simulate(lam=3.8, mu=5.0, k=40.0, seed=3, realization=0,
                             common_random_numbers=True)
    other = stickslip.simulate(lam=1.0, mu=5.0, k=40.0, seed=3, realization=0,
                               common_random_numbers=True)
    own = stickslip.simulate(lam=3.8, mu=5.0, k=40.0, seed=3, realization=0)
    # Common random numbers: every point starts from the same state.
    assert (one.x0, one.xdot0, one.belt_start) == (other.x0, other.xdot0, other.belt_start)
    assert own.x0 != one.x0



def _halfwidth(ds, name):
    """The 95 % half-width of derivative variable `name` of `ds`."""
    return (ds[name + "_ci95_high"] - ds[name + "_ci95_low"]) / 2


def test_derivatives_reach_the_dataset_and_agree():
    """The derivative estimates in Python: the likelihood-ratio d E[R]/d lambda
    and the common-random-number slope over lambda are Dataset variables with
    units and intervals, and the two independent estimators agree within
    their combined 95 % half-widths at every interior point; so do the score
    over a belt's own rate r1 and the CRN slope over an r1 axis."""
    lam = [1.0, 1.5, 2.0, 2.5, 3.0]
    ds = stickslip.sweep(lam=lam, mu=5.0, k=40.0, realizations=4000, seed=11,
                         common_random_numbers=True, records=True, threads=2,
                         statistics=["paper", "derivatives"])
    lr_name, crn_name = "stick_fraction_dmean_dlambda", "stick_fraction_dmean_dlambda_crn"
    lr, crn = ds[lr_name], ds[crn_name]
    assert lr.attrs["units"] == crn.attrs["units"] == "s"
    assert "likelihood-ratio" in lr.attrs["description"]
    assert "common-random-number" in crn.attrs["description"]
    inner = {"lam": slice(1, len(lam) - 1)}  # central differences only
    gap = abs(lr - crn).isel(inner)
    both = (_halfwidth(ds, lr_name) + _halfwidth(ds, crn_name)).isel(inner)
    assert bool((gap <= both).all()), (gap.values, both.values)
    # The slope is clearly resolved (not a test of two zeros).
    assert bool((abs(crn).isel(inner) > 3 * _halfwidth(ds, crn_name).isel(inner)).all())

    # The belt's own rates: the score over r1 against the CRN slope over an r1 axis.
    rates = stickslip.sweep(belt_levels=[1.0, -0.5], r1=[1.8, 2.0, 2.2], r2=3.0, mu=5.0, k=40.0,
                            realizations=4000, seed=11, common_random_numbers=True, records=True,
                            threads=2, statistics=["paper", "derivatives"])
    lr_name, crn_name = "stick_fraction_dmean_dr1", "stick_fraction_dmean_dr1_crn"
    at = {"r1": 2.0}
    gap = abs(rates[lr_name] - rates[crn_name]).sel(at).item()
    both = (_halfwidth(rates, lr_name) + _halfwidth(rates, crn_name)).sel(at).item()
    assert gap <= both, (gap, both)
    assert abs(rates[crn_name].sel(at).item()) > 3 * _halfwidth(rates, crn_name).sel(at).item()


def test_generator_derivatives_in_the_dataset_equal_summary_json(tmp_path):
    """A belt given by its generator: d mean/d q_ij over (belt_level,
    belt_level_to) in the Dataset (= results.nc) equals summary.json's
    dmean_dgenerator list, entry by entry; NaN on the diagonal and where
    q_ij = 0 (those are not listed)."""
    q = [[-2.0, 1.2, 0.8], [1.0, -1.0, 0.0], [0.4, 0.6, -1.0]]
    ds = stickslip.sweep(belt_levels=[1.0, 0.0, -0.5], belt_generator=q, mu=5.0, k=40.0,
                         realizations=3000, seed=5, threads=2, output=tmp_path / "g",
                         statistics=["paper", "derivatives"])
    d = ds.stick_fraction_dmean_dgenerator
    assert d.dims[-2:] == ("belt_level", "belt_level_to") and d.attrs["units"] == "s"
    listed = json.loads((tmp_path / "g" / "summary.json").read_text())["points"][0]
    listed = {(e["from"], e["to"]): e for e in listed["dmean_dgenerator"]["R"]}
    assert sorted(listed) == [(1, 2), (1, 3), (2, 1), (3, 1), (3, 2)]  # q_23 = 0
    for i in range(3):
        for j in range(3):
            value = float(d.values.reshape(3, 3)[i, j])
            if (i + 1, j + 1) not in listed:
                assert np.isnan(value)
                continue
            e = listed[(i + 1, j + 1)]
            assert value == e["value"]
            low = float(ds.stick_fraction_dmean_dgenerator_ci95_low.values.reshape(3, 3)[i, j])
            assert low == pytest.approx(e["ci95"][0], rel=1e-12)


def test_grid_text_is_the_clis_axis_bit_for_bit(cli, tmp_path):
    """lam="log:0.1:30:8" is the CLI's --lambda log:0.1:30:8, value for value
    (np.logspace differs in last bits, and the streams are keyed by them),
    and bad grid text is refused with the CLI's message, under the keyword."""
    ds = stickslip.sweep(lam="log:0.1:30:8", mu="0.5,5", k=40, realizations=100, seed=2)
    cli("sweep", "--lambda", "log:0.1:30:8", "--mu", "0.5,5", "--k", "40", "--realizations", "100",
        "--seed", "2", "-o", tmp_path / "cli")
    with xr.open_dataset(tmp_path / "cli" / "results.nc") as c:
        assert ds["lambda"].values.tobytes() == c["lambda"].values.tobytes()
        assert ds.stick_fraction_mean.values.tobytes() == c.stick_fraction_mean.values.tobytes()
    assert not np.array_equal(np.logspace(-1, np.log10(30), 8), ds["lambda"].values)
    with pytest.raises(stickslip.Error, match=r"invalid lam: 'log:0:30:4' \(allowed: values > 0"):
        stickslip.sweep(lam="log:0:30:4", mu=5, realizations=10)
