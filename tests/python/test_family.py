"""The model family (damping c, static and kinetic friction mu_s >= mu_k,
Markov belts) from Python against the CLI: episodes of random replay
scenarios bit for bit against `simulate --format json`, the recorded model,
sweeps against results.nc and summary.json, errors with the CLI's message."""
import json

import numpy as np
import pytest
import xarray as xr

import stickslip
from stickslip._parameters import python_message
from test_sweep import assert_same_dataset

GENERATOR3 = [[-2.0, 1.0, 1.0], [1.0, -1.0, 0.0], [0.5, 0.5, -1.0]]


def generator_text(q):
    return ";".join(",".join(repr(float(x)) for x in row) for row in q)


def family_scenarios():
    """24 fixed random scenarios: mu_s > mu_k, damping under (c < 2 sqrt(km))
    and over, two-level belts with rates (one with a zero level), three-level
    belts from a generator with given switch levels, stationary and fixed
    starts, fixed initial states."""
    rng = np.random.default_rng(20261212)
    for i in range(24):
        k = float(rng.choice([4.0, 40.0]))
        critical = 2 * np.sqrt(k)  # m = 1
        kw = {"k": k, "ta": float(rng.choice([5.0, 20.0])),
              "c": float(rng.choice([0.0, 0.3, 0.9]) * critical if i % 2 else rng.choice([1.5, 3.0]) * critical),
              "seed": int(rng.integers(1, 2**31)), "realization": int(rng.integers(0, 5000))}
        mu_k = float(rng.choice([0.5, 2.0, 4.0]))
        kw["mu_s"] = mu_k * float(rng.choice([1.0, 1.25, 2.0]))
        kw["mu_k"] = mu_k
        kind = i % 4
        if kind == 0:    # two levels, asymmetric rates
            kw["belt_levels"] = [float(rng.choice([0.5, 1.0, 2.0])), float(rng.choice([-1.0, -0.25]))]
            kw["belt_rates"] = [float(rng.choice([0.5, 2.0])), float(rng.choice([1.0, 3.8]))]
        elif kind == 1:  # a zero level
            kw["belt_levels"] = [1.0, 0.0]
            kw["belt_rates"] = [float(rng.choice([0.9, 2.0])), float(rng.choice([0.5, 3.0]))]
        elif kind == 2:  # three levels, one of them zero, via the generator
            kw["belt_levels"] = [1.0, 0.0, -2.0]
            kw["belt_generator"] = GENERATOR3
        else:            # the paper's belt, family friction and damping
            kw["lam"] = float(rng.choice([0.3, 3.8]))
        n = len(kw.get("belt_levels", [1, -1]))
        start = int(rng.integers(0, 3))
        if start == 1:
            kw["belt_start"] = "stationary"
        elif start == 2:
            kw["belt_start"] = int(rng.integers(1, n + 1)) if n > 2 else int(rng.choice([1, -1]))
        if i % 3 == 0:
            kw["x0"] = float(rng.uniform(-2, 2))
            kw["xdot0"] = float(rng.uniform(-1, 1))
        if i % 8 == 2 or i % 5 == 0:
            times = sorted(float(t) for t in rng.uniform(0, kw["ta"], 5))
            kw["switch_times"] = times
            if n > 2 or i % 2 == 0:
                # each switch goes to another level than the current one
                if not isinstance(kw.get("belt_start"), int):
                    kw["belt_start"] = int(rng.integers(1, n + 1)) if n > 2 else int(rng.choice([1, -1]))
                level, levels = kw["belt_start"] if kw["belt_start"] > 0 else 2, []
                for _ in times:
                    level = int(rng.choice([v for v in range(1, n + 1) if v != level]))
                    levels.append(level)
                kw["switch_levels"] = levels
        yield kw
    # mu sets mu_s and mu_k both, then mu_s refines it, whatever the order
    yield {"mu_s": 7.0, "mu": 5.0, "c": 1.0, "seed": 5}


def to_flags(kw, tmp_path):
    flags = []
    for key, value in kw.items():
        if key == "switch_times":
            if "switch_levels" in kw:
                f = tmp_path / "switches.txt"
                f.write_text("".join(f"{t!r} {lv}\n" for t, lv in zip(value, kw["switch_levels"])))
                flags += ["--switch-times-file", f]
            else:
                flags += ["--switch-times", ",".join(repr(t) for t in value)]
        elif key == "switch_levels":
            continue
        elif key == "belt_generator":
            flags += ["--belt-generator", generator_text(value)]
        elif key in ("belt_levels", "belt_rates"):
            flags += ["--" + key.replace("_", "-"), ",".join(repr(v) for v in value)]
        elif key == "belt_start":
            flags += ["--belt-start", value if isinstance(value, str) else f"{value:+d}" if value == 1 else value]
        elif key == "lam":
            flags += ["--lambda", repr(value)]
        else:
            flags += ["--" + key.replace("_", "-"), repr(value) if isinstance(value, float) else value]
    return flags


def cli_json(cli, args, tmp_path):
    out = tmp_path / "r.json"
    cli("simulate", *args, "--format", "json", "-o", out, "--overwrite")
    return json.loads(out.read_text())


SCENARIOS = list(family_scenarios())


def test_the_scenarios_cover_the_family():
    assert len(SCENARIOS) >= 20
    assert any(s["mu_s"] > s.get("mu_k", s["mu_s"]) for s in SCENARIOS if "mu_s" in s)
    assert any(s.get("c", 0) > 2 * np.sqrt(s["k"]) for s in SCENARIOS if "k" in s)           # over-damped
    assert any(0 < s.get("c", 0) < 2 * np.sqrt(s["k"]) for s in SCENARIOS if "k" in s)       # under-damped
    assert any("belt_generator" in s and "switch_levels" in s for s in SCENARIOS)
    assert any(0.0 in s.get("belt_levels", []) for s in SCENARIOS)
    assert any(s.get("belt_start") == "stationary" for s in SCENARIOS)
    assert any(isinstance(s.get("belt_start"), int) and s["belt_start"] > 1 for s in SCENARIOS)
    assert any(s.get("belt_start") == -1 for s in SCENARIOS)


@pytest.mark.parametrize("kw", SCENARIOS)
def test_family_episodes_equal_the_cli_json_bit_for_bit(cli, tmp_path, kw):
    ours = stickslip.simulate(**kw)
    theirs = cli_json(cli, to_flags(kw, tmp_path), tmp_path)
    ep = theirs["episodes"]
    assert list(ours.episodes["mode"]) == [e["mode"] for e in ep]
    for col in ("start", "end", "x_start", "belt_velocity"):
        a = ours.episodes[col].to_numpy(dtype=np.float64)
        b = np.array([e[col] for e in ep], dtype=np.float64)
        assert a.tobytes() == b.tobytes(), f"{col} differs: {a[a != b][:3]} vs {b[a != b][:3]}"
    assert list(ours.episodes["censored"]) == [e["censored"] for e in ep]
    # the model and the initial state as the CLI records them
    assert ours.parameters == theirs["parameters"]
    ic = theirs["initial_conditions"]
    assert (ours.x0, ours.xdot0, ours.belt_start) == (ic["x0"], ic["xdot0"], ic["belt_start"])
    st = theirs["statistics"]
    assert (ours.record["S_T"], ours.record["S_L"], ours.record["R"]) == (
        st["sticks"], st["slips"], st["stick_fraction"])


def test_family_keywords_are_recorded():
    r = stickslip.simulate(damping=0.5, mu_s=6, mu_k=4, belt_levels=[1, 0], belt_rates=[2, 3], seed=2)
    p = r.parameters
    assert (p["c"], p["mu_s"], p["mu_k"]) == (0.5, 6.0, 4.0)
    assert p["belt_levels"] == [1.0, 0.0] and p["belt_rates"] == [2.0, 3.0]
    assert p["belt_generator"] == [[-2.0, 2.0], [3.0, -3.0]]
    r = stickslip.simulate(belt_levels=np.array([1.0, 0.0, -2.0]), belt_generator=np.array(GENERATOR3),
                           belt_start=3, ta=5)
    assert r.parameters["belt_generator"] == GENERATOR3 and "belt_rates" not in r.parameters
    assert r.belt_start == 3 and r.episodes["belt_velocity"].iloc[0] == -2.0
    # the paper's model spelled as a family gives the paper's bits
    a = stickslip.simulate(mu=5, lam=1, seed=4).episodes
    b = stickslip.simulate(mu_s=5, mu_k=5, belt_levels=[1, -1], belt_rates=[1, 1], seed=4).episodes
    assert a.equals(b)


BAD = [
    (dict(belt_levels=[1.0]), ["--belt-levels", "1.0"]),
    (dict(belt_generator=[[1.0, 2.0], [3.0]]), ["--belt-generator", "1,2;3"]),
    (dict(belt_start=2), ["--belt-start", "2"]),
    (dict(belt_levels=[1.0, 0.0, -2.0], belt_generator=GENERATOR3, belt_start=4), ["--belt-levels", "1,0,-2",
     "--belt-generator", generator_text(GENERATOR3), "--belt-start", "4"]),
    (dict(mu_s=3.0, mu_k=4.0), ["--mu-s", "3.0", "--mu-k", "4.0"]),
    (dict(c=-1.0), ["--c", "-1.0"]),
    (dict(belt_levels=[1.0, 1.0]), ["--belt-levels", "1.0,1.0"]),
    (dict(belt_rates=[1.0, -2.0]), ["--belt-rates", "1.0,-2.0"]),
    (dict(belt_rates=[1.0, 2.0], belt_generator=[[-1.0, 1.0], [2.0, -2.0]]),
     ["--belt-rates", "1.0,2.0", "--belt-generator", "-1.0,1.0;2.0,-2.0"]),
    (dict(switch_times=[2.0, 1.0]), ["--switch-times", "2.0,1.0"]),
]


@pytest.mark.parametrize("kw,flags", BAD)
def test_bad_family_input_raises_error_with_the_cli_message(cli, tmp_path, kw, flags):
    p = cli("simulate", *flags, "-o", tmp_path / "x.csv", check=False)
    assert p.returncode == 2, p.stderr
    with pytest.raises(stickslip.Error) as e:
        stickslip.simulate(**kw)
    assert isinstance(e.value, ValueError) and e.value.exit_code == 2
    # the CLI's message, with the Python keyword in place of each flag
    assert python_message(p.stderr.strip()) == f"stickslip: error: {e.value}"
    assert "--" not in str(e.value)


def test_bad_switch_levels():
    three = dict(belt_levels=[1, 0, -2], belt_generator=GENERATOR3)
    with pytest.raises(stickslip.Error, match="belt level"):
        stickslip.simulate(**three, switch_times=[1, 2], switch_levels=[1, 4])
    with pytest.raises(stickslip.Error, match="switch_levels"):
        stickslip.simulate(**three, switch_times=[1, 2], switch_levels=[1])
    with pytest.raises(stickslip.Error, match="levels"):
        stickslip.simulate(**three, switch_times=[1, 2])
    with pytest.raises(TypeError, match="given twice"):
        stickslip.simulate(c=1, damping=1)


# --- sweeps ---------------------------------------------------------------

# Every group but survival: the family statistics and the derivatives too.
GROUPS = ["paper", "family", "derivatives"]
FAMILY_GRID = dict(c=[0.5, 2.0, 6.0], k=[4.0, 40.0], mu_s=6.0, mu_k=4.0, belt_levels=[1, 0], belt_rates=[2, 3],
                   statistics=GROUPS)
FAMILY_CLI = ["--c", "0.5,2,6", "--k", "4,40", "--mu-s", "6", "--mu-k", "4", "--belt-levels", "1,0",
              "--belt-rates", "2,3", "--statistics", ",".join(GROUPS)]
LEVELS_GRID = dict(mu_k=[2.0, 3.0], c=np.array([0.5, 5.0]), mu_s=4.0, belt_levels=[1.0, 0.0, -2.0],
                   belt_generator=np.array(GENERATOR3), belt_start=3, statistics=GROUPS)
LEVELS_CLI = ["--mu-k", "2,3", "--c", "0.5,5", "--mu-s", "4", "--belt-levels", "1,0,-2",
              "--belt-generator", generator_text(GENERATOR3), "--belt-start", "3",
              "--statistics", ",".join(GROUPS)]


@pytest.fixture(scope="module")
def cli_family_sweeps(tmp_path_factory, cli):
    base = tmp_path_factory.mktemp("family")
    cli("sweep", *FAMILY_CLI, "--realizations", 200, "--seed", 11, "--records", "-o", base / "a")
    cli("sweep", *LEVELS_CLI, "--realizations", 150, "--seed", 12, "-o", base / "b")
    return base


@pytest.mark.parametrize("which", ["a", "b"])
def test_family_dataset_equals_the_cli_results_nc(cli_family_sweeps, which):
    if which == "a":
        ours = stickslip.sweep(**FAMILY_GRID, realizations=200, seed=11, records=True)
        assert list(ours.dims)[:2] == ["c", "k"]
        assert (ours.attrs["mu_s"], ours.attrs["mu_k"]) == (6.0, 4.0)
        assert list(ours.attrs["belt_levels"]) == [1.0, 0.0]
        assert list(ours.attrs["belt_generator"]) == [-2.0, 2.0, 3.0, -3.0]
    else:
        ours = stickslip.sweep(**LEVELS_GRID, realizations=150, seed=12)
        assert list(ours.dims)[:2] == ["mu_k", "c"]
        assert ours.attrs["initial_belt_start"] == "3" and ours.attrs["mu_s"] == 4.0
        assert list(ours.attrs["belt_generator"]) == sum(GENERATOR3, [])
    with xr.open_dataset(cli_family_sweeps / which / "results.nc") as theirs:
        theirs = theirs.load()
        assert_same_dataset(ours, theirs)
    # and results.nc read back through stickslip.open
    assert_same_dataset(ours, stickslip.open(cli_family_sweeps / which))


def test_family_statistics_equal_summary_json(cli_family_sweeps):
    ours = stickslip.sweep(**FAMILY_GRID, realizations=200, seed=11)
    summary = json.load(open(cli_family_sweeps / "a" / "summary.json"))
    checked = 0
    for p in summary["points"]:
        sel = ours.sel({"c": p["c"], "k": p["k"]})
        for key, value in p.items():
            if isinstance(value, dict) and "mean" in value:
                name = "stick_fraction" if key == "R" else key
                assert float(sel[name + "_mean"]) == value["mean"], key
                assert float(sel[name + "_std"]) == value["std"], key
                checked += 1
    assert checked == 9 * len(summary["points"]) == 54  # the 9 quantities of the schema


LEVEL_AXES_TOML = """
[model]
belt_levels = [1.0, -1.0]
ta = 10.0
[grid]
v2 = [0.0, -0.5]
r1 = [1.0, 4.0]
order = ["v2", "r1"]
[sweep]
realizations = 100
"""


def test_belt_level_and_rate_axes_equal_the_cli_toml_sweep(cli, tmp_path):
    ds = stickslip.sweep(v2=[0.0, -0.5], r1=[1.0, 4.0], belt_levels=[1, -1], realizations=100, ta=10)
    (tmp_path / "axes.toml").write_text(LEVEL_AXES_TOML)
    cli("sweep", "--config", tmp_path / "axes.toml", "-o", tmp_path / "out")
    assert_same_dataset(ds, stickslip.open(tmp_path / "out"))
    assert list(ds.dims)[:2] == ["v2", "r1"]
    assert ds.attrs["swept_parameters"] == "v2 r1"
    assert np.isfinite(ds.stick_fraction_mean.values).all()
    with pytest.raises(stickslip.Error, match="r1"):
        stickslip.sweep(r1=[1.0, 2.0], belt_levels=[1, 0, -1], belt_generator=GENERATOR3, realizations=10)


def test_bad_family_sweep_input_raises_error_with_the_cli_message(cli, tmp_path):
    p = cli("sweep", "--c", "0.5,-1", "--realizations", 10, "-o", tmp_path / "bad", check=False)
    assert p.returncode == 2
    with pytest.raises(stickslip.Error) as e:
        stickslip.sweep(c=[0.5, -1.0], realizations=10)
    assert python_message(p.stderr.strip()) == f"stickslip: error: {e.value}"
    p = cli("sweep", "--belt-start", "3", "--realizations", 10, "-o", tmp_path / "bad", check=False)
    with pytest.raises(stickslip.Error) as e:
        stickslip.sweep(belt_start=3, realizations=10)
    assert python_message(p.stderr.strip()) == f"stickslip: error: {e.value}"
    assert str(e.value).startswith("invalid belt_start: '3'")


def test_docstrings_name_the_family_with_units():
    for fn in (stickslip.simulate, stickslip.sweep):
        doc = fn.__doc__
        for kw, unit in [("c", "N s/m"), ("mu_s", "1"), ("mu_k", "1"), ("belt_levels", "m/s"),
                         ("belt_rates", "1/s"), ("belt_generator", "1/s"), ("belt_start", None)]:
            assert f"    {kw}:" in doc, (fn.__name__, kw)
            if unit:
                line = next(ln for ln in doc.splitlines() if ln.strip().startswith(kw + ":"))
                assert f"[{unit}]" in line, (fn.__name__, kw, line)
    assert "switch_levels:" in stickslip.simulate.__doc__


def test_family_output_dir_writes_the_cli_files(cli_family_sweeps, tmp_path):
    import subprocess
    from test_sweep import COMPARE
    out = tmp_path / "py"
    stickslip.sweep(**FAMILY_GRID, realizations=200, seed=11, records=True, output=str(out))
    p = subprocess.run(["/usr/bin/python3", COMPARE, str(cli_family_sweeps / "a"), str(out)],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr


def test_the_family_example_of_docs_python_md():
    r = stickslip.simulate(mu_s=6, mu_k=4, c=0.5, belt_levels=[1, 0], belt_rates=[2, 3], seed=2, ta=10)
    assert repr(r) == "<stickslip.Realization seed=2 realization=0: 25 sticks, R = 0.926262, 50 episodes>"
    ds = stickslip.sweep(c=[0.5, 2, 6], k=[4, 40], mu_s=6, mu_k=4, belt_levels=[1, 0], belt_rates=[2, 3])
    table = ds.stick_fraction_mean.round(4).values.tolist()
    assert table == [[0.5104, 0.3508], [0.526, 0.3704], [0.5415, 0.3927]]
