"""stickslip.simulate() against the CLI's `simulate`: the same episodes, bit
for bit, for random replay scenarios; events; trajectory; errors."""
import io

import numpy as np
import pandas as pd
import pytest

import stickslip


def cli_episodes(cli, args, tmp_path):
    out = tmp_path / "ep.csv"
    cli("simulate", *args, "-o", out)
    return pd.read_csv(out, float_precision="round_trip")


def scenarios():
    rng = np.random.default_rng(20261123)  # fixed: the scenarios are the same every run
    for i in range(25):
        kw = {"mu": float(rng.choice([0.5, 2.0, 5.0, 7.0])), "lam": float(rng.choice([0.1, 0.9, 3.8, 30.0])),
              "k": float(rng.choice([4.0, 40.0])), "ta": float(rng.choice([5.0, 50.0])),
              "seed": int(rng.integers(1, 2**31)), "realization": int(rng.integers(0, 5000))}
        if i % 3 == 1:
            kw["x0"] = float(rng.uniform(-3, 3))
            kw["xdot0"] = float(rng.uniform(-2, 2))
            kw["belt_start"] = int(rng.choice([1, -1]))
        if i % 4 == 2:
            kw["switch_times"] = sorted(float(t) for t in rng.uniform(0, kw["ta"], 6))
        yield kw


def to_flags(kw):
    flags = []
    names = {"lam": "--lambda", "realization": "--realization", "seed": "--seed", "x0": "--x0",
             "xdot0": "--xdot0", "belt_start": "--belt-start", "mu": "--mu", "k": "--k", "ta": "--ta"}
    for key, value in kw.items():
        if key == "switch_times":
            flags += ["--switch-times", ",".join(repr(t) for t in value)]
        elif key == "belt_start":
            flags += [names[key], f"{value:+d}"]
        else:
            flags += [names[key], repr(value)]
    return flags


@pytest.mark.parametrize("kw", list(scenarios()))
def test_episodes_equal_the_cli_bit_for_bit(cli, tmp_path, kw):
    ours = stickslip.simulate(**kw).episodes
    theirs = cli_episodes(cli, to_flags(kw), tmp_path)
    assert list(ours["mode"]) == list(theirs["mode"])
    for col in ("start", "end", "x_start", "belt_velocity"):
        a, b = ours[col].to_numpy(dtype=float), theirs[col].to_numpy(dtype=float)
        assert a.tobytes() == b.tobytes(), f"{col} differs: {a[a != b][:3]} vs {b[a != b][:3]}"
    assert list(ours["censored"].astype(int)) == list(theirs["censored"])


def test_events_equal_the_cli(cli, tmp_path):
    ours = stickslip.simulate(mu=2, lam=3.8, k=40, seed=9, realization=4).events
    ev = tmp_path / "events.csv"
    cli("simulate", "--mu", 2, "--lambda", 3.8, "--k", 40, "--seed", 9, "--realization", 4,
        "--events", "--events-file", ev, "-o", tmp_path / "ep.csv")
    theirs = pd.read_csv(ev, float_precision="round_trip")
    assert list(ours["kind"]) == list(theirs.iloc[:, 0])
    assert ours["time"].to_numpy().tobytes() == theirs["time"].to_numpy().tobytes()
    assert ours["x"].to_numpy().tobytes() == theirs["x"].to_numpy().tobytes()


def test_episodes_tile_the_window():  # an invariant, independent of the CLI
    r = stickslip.simulate(mu=5, lam=1, seed=3, ta=50)
    ep = r.episodes
    assert ep["start"].iloc[0] == 0.0 and ep["end"].iloc[-1] == 50.0
    assert (ep["end"].to_numpy()[:-1] == ep["start"].to_numpy()[1:]).all()
    assert r.record["S_T"] == (ep["mode"] == "stick").sum()


def test_trajectory_equals_the_cli_sampling(cli, tmp_path):
    ours = stickslip.simulate(mu=5, lam=1, seed=2).trajectory(0.05)
    tr = tmp_path / "tr.csv"
    cli("simulate", "--mu", 5, "--lambda", 1, "--seed", 2, "--trajectory", 0.05, "--trajectory-file", tr,
        "-o", tmp_path / "ep.csv")
    theirs = pd.read_csv(tr, float_precision="round_trip")
    for col in ("t", "x", "xdot", "v"):
        assert ours[col].to_numpy(dtype=float).tobytes() == theirs[col].to_numpy(dtype=float).tobytes(), col
    # sticks: x' equals the belt velocity at every sample inside a stick
    r = stickslip.simulate(mu=5, lam=1, seed=2)
    st = r.episodes[r.episodes["mode"] == "stick"].iloc[0]
    inside = ours[(ours.t > st.start) & (ours.t < st.end)]
    assert len(inside) > 0 and (inside.xdot == inside.v).all()


def test_bad_input_raises_error_with_the_cli_message(cli):
    p = cli("simulate", "--mu", -1, check=False)
    assert p.returncode == 2
    with pytest.raises(stickslip.Error) as e:
        stickslip.simulate(mu=-1)
    assert isinstance(e.value, ValueError)
    assert e.value.exit_code == 2
    assert p.stderr.strip() == f"stickslip: error: {e.value}"


def test_unknown_keyword_is_a_type_error():
    with pytest.raises(TypeError, match="lamda"):
        stickslip.simulate(lamda=1)


def test_docstring_names_every_parameter_with_its_unit():
    doc = stickslip.simulate.__doc__
    for kw, unit in [("m", "kg"), ("k", "N/m"), ("g", "m/s^2"), ("mu", "1"), ("V", "m/s"),
                     ("lam", "1/s"), ("ta", "s"), ("x0", "m"), ("xdot0", "m/s"), ("switch_times", "s")]:
        assert f"{kw}:" in doc and f"[{unit}]" in doc, kw


def test_plot_draws(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    ax = stickslip.simulate(seed=4).plot()
    assert len(ax.lines) == 3
    ax.figure.savefig(tmp_path / "r.png")
    assert (tmp_path / "r.png").stat().st_size > 1000
