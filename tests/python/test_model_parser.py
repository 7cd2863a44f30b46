"""One model parser: the same assignments as CLI flags, TOML [model] keys and
Python keywords give the same resolved model, mu applying before mu_s and
mu_k whatever the written order, and the same refusal of a bad value."""
import json
import re
import warnings

import pytest

import stickslip
from stickslip import _stickslip
from stickslip._parameters import PARAMETERS, model_arguments, python_message

# Written with mu last: it still applies first, and mu_s refines it.
ASSIGNMENTS = [("mu_s", 6.0), ("c", 0.3), ("mu", 5.0), ("k", 9.0)]
SCALARS = ["m", "k", "g", "V", "lambda", "ta", "c", "mu_s", "mu_k"]


def flags(assignments):
    return [a for sym, v in assignments for a in ("--" + sym.replace("_", "-"), repr(v))]


def toml(assignments):
    return "[model]\n" + "".join(f"{sym} = {v!r}\n" for sym, v in assignments)


def cli_base(cli, tmp_path, *args):
    out = tmp_path / "out"
    cli("sweep", *args, "--realizations", 2, "-o", out, "--overwrite")
    base = json.loads((out / "summary.json").read_text())["parameters"]["base"]
    return {sym: base[sym] for sym in SCALARS}


def python_base(assignments):
    model = _stickslip.resolve_parameters(model_arguments(dict(assignments)))
    return {sym: model[sym] for sym in SCALARS}


def test_cli_toml_and_python_resolve_the_same_model(cli, tmp_path):
    (tmp_path / "model.toml").write_text(toml(ASSIGNMENTS))
    from_flags = cli_base(cli, tmp_path, *flags(ASSIGNMENTS))
    from_toml = cli_base(cli, tmp_path, "--config", tmp_path / "model.toml")
    from_python = python_base(ASSIGNMENTS)
    assert from_flags == from_toml == from_python
    assert from_python["mu_s"] == 6.0 and from_python["mu_k"] == 5.0 and from_python["k"] == 9.0


def test_mu_alone_sets_both_and_a_refinement_keeps_the_other(cli, tmp_path):
    assignments = [("mu_k", 2.0), ("mu", 3.0)]
    (tmp_path / "model.toml").write_text(toml(assignments))
    expected = python_base(assignments)
    assert expected["mu_s"] == 3.0 and expected["mu_k"] == 2.0
    assert cli_base(cli, tmp_path, *flags(assignments)) == expected
    assert cli_base(cli, tmp_path, "--config", tmp_path / "model.toml") == expected


@pytest.mark.parametrize("assignments, phrase", [
    ([("mu_s", 3.0), ("mu", 5.0)], "invalid mu_k (kinetic friction): 5"),
    ([("c", -1.0)], "invalid c (damping): -1"),
])
def test_a_bad_value_is_refused_alike(cli, tmp_path, assignments, phrase):
    (tmp_path / "bad.toml").write_text(toml(assignments))
    by_flags = cli("sweep", *flags(assignments), "--realizations", 2, "-o", tmp_path / "a",
                   check=False)
    by_toml = cli("sweep", "--config", tmp_path / "bad.toml", "--realizations", 2,
                  "-o", tmp_path / "b", check=False)
    with pytest.raises(stickslip.Error) as by_python:
        stickslip.sweep(**{("lam" if s == "lambda" else s): v for s, v in assignments},
                        realizations=2)
    assert by_flags.returncode == by_toml.returncode == 2
    assert phrase in by_flags.stderr and phrase in by_toml.stderr
    assert python_message(by_flags.stderr.strip()) == f"stickslip: error: {by_python.value}"


def test_the_keywords_are_the_rows_of_the_parameter_table():
    rows = _stickslip.parameter_table()
    assert [r["symbol"] for r in rows] == list(PARAMETERS)
    assert PARAMETERS["lambda"][0] == "lam"
    assert PARAMETERS["mu_s"][1] == "mu" and PARAMETERS["k"][1] == 4.0


WARNING = ("sets neither mu_s nor mu_k: mu_s and mu_k give them. Unless the model is the "
           "paper's (mu_s = mu_k, c = 0, the belt +-V), mu still enters the random streams' key")


def python_sweep_r(**model):
    ds = stickslip.sweep(realizations=50, seed=3, lam=[0.5, 3.0], k=40, **model)
    return ds["stick_fraction_mean"].values.tobytes()


def test_mu_beside_both_refinements_is_kept_with_a_warning(cli, tmp_path):
    """--mu with --mu-s and --mu-k sets no friction coefficient, yet it
    enters the random streams' key (a new user's report: it was taken
    without a word). It is not refused: a run recorded with it must replay
    with it. The CLI and Python warn, in their words, and the model is
    mu_s, mu_k; the draws are mu's (another mu, other draws). With only one
    of them, mu sets a coefficient: no warning."""
    runs = {}
    for name, mu in (("a", ["--mu", 3]), ("b", ["--mu", 3]), ("c", [])):
        out = tmp_path / name
        r = cli("sweep", "--mu-k", 4, *mu, "--mu-s", 6, "--k", 40, "--lambda", "0.5,3",
                "--realizations", 50, "--seed", 3, "-o", out)
        cli_words = WARNING.replace("mu_s and mu_k give", "--mu-s and --mu-k give").replace(
            "mu still", "--mu still")
        assert r.stderr.count("stickslip: warning: --mu 3 " + cli_words) == (1 if mu else 0), r.stderr
        runs[name] = (out / "summary.csv").read_text()
    assert runs["a"] == runs["b"] != runs["c"]  # mu's draws, reproducibly
    base = json.loads((tmp_path / "a" / "summary.json").read_text())["parameters"]["base"]
    assert (base["mu_s"], base["mu_k"]) == (6.0, 4.0)
    for command in (["simulate"], ["peak", "--initial-realizations", 20, "--max-realizations", 200,
                                    "--ta", 5], ["sensitivity", "--lambda", "uniform(1,3)",
                                                 "--samples", 8, "-o", tmp_path / "s"]):
        r = cli(*command, "--mu", 3, "--mu-s", 6, "--mu-k", 4, check=False)
        assert r.stderr.count("stickslip: warning: --mu 3 sets neither") == 1, r.stderr
    r = cli("simulate", "--mu", 3, "--mu-s", 6)
    assert "warning" not in r.stderr, r.stderr
    with pytest.warns(UserWarning, match=re.escape("mu 3 " + WARNING)) as w:
        with_mu = python_sweep_r(mu=3, mu_s=6, mu_k=4)
    mine = [x for x in w if "sets neither" in str(x.message)]
    assert len(mine) == 1 and mine[0].filename == __file__  # the user's line
    with pytest.warns(UserWarning, match=r"mu 2 sets neither"):
        stickslip.sweep(friction_coefficient=2, static_friction=[6, 7], mu_k=4, realizations=2)
    for call in (lambda: stickslip.simulate(mu=3, mu_s=6, mu_k=4),
                 lambda: stickslip.simulate_many(realizations=2, mu=3, mu_s=6, mu_k=4),
                 lambda: stickslip.peak(mu=3, mu_s=6, mu_k=4, initial_realizations=20,
                                        max_realizations=200, ta=5)):
        with pytest.warns(UserWarning) as w:
            try:
                call()
            except stickslip.Error:
                pass  # peak's scan may end at the range's edge; the warning came first
        mine = [x for x in w if "sets neither" in str(x.message)]
        assert len(mine) == 1 and mine[0].filename == __file__, [str(x.message) for x in w]
    # a law over mu beside a refinement is refused, as before (it would draw nothing)
    with pytest.raises(stickslip.Error, match="has no effect on the model"):
        stickslip.simulate(mu="uniform(4,6)", mu_s=6, realization=0)
    assert with_mu == python_sweep_r(mu=3, mu_s=6, mu_k=4) != python_sweep_r(mu_s=6, mu_k=4)
    with warnings.catch_warnings():
        warnings.simplefilter("error", UserWarning)
        python_sweep_r(mu=3, mu_s=6)
    # with one refinement, mu still sets the other
    assert python_base([("mu", 5.0), ("mu_s", 6.0)])["mu_k"] == 5.0
    assert python_base([("mu", 5.0), ("mu_k", 4.0)])["mu_s"] == 5.0


def test_mu_flag_beside_refinements_from_a_configuration(cli, tmp_path):
    """A --mu flag on top of a --config file: flags come after the file, so
    --mu replaces the file's mu_s and mu_k values and sets the friction (no
    warning); but an axis or a law of both in the file still sets them at
    every point, and then --mu only changes the draws: the warning, as for
    flags. With one of them on an axis, --mu sets the other: no warning."""
    cases = {
        "values": ("[model]\nmu_s = 6\nmu_k = 4\n", 0),
        "axes": ("[grid]\nmu_s = [6, 7]\nmu_k = [4]\n", 1),
        "axis and flag": ("[grid]\nmu_s = [6, 7]\n", 1),  # with --mu-k 4 below
        "one axis": ("[model]\nmu_k = 4\n[grid]\nmu_s = [6, 7]\n", 0),
    }
    for name, (toml, warned) in cases.items():
        config = tmp_path / f"{len(name)}-{warned}.toml"
        config.write_text(toml)
        out = tmp_path / name.replace(" ", "_")
        extra = ["--mu-k", 4] if name == "axis and flag" else []
        r = cli("sweep", "--config", config, "--mu", 5, *extra, "--lambda", "1,2",
                "--realizations", 20, "-o", out)
        assert r.stderr.count("stickslip: warning: --mu 5 sets neither") == warned, (name, r.stderr)
        if name == "axes":  # who gives them: the file, not flags that were not given
            assert "sets neither mu_s nor mu_k: the --config file gives them." in r.stderr
        if name == "axis and flag":
            assert "nor mu_k: --mu-k and the --config file give them." in r.stderr, r.stderr
        base = json.loads((out / "summary.json").read_text())["parameters"]["base"]
        if name == "values":  # --mu replaced the file's values: the friction is 5
            assert (base["mu_s"], base["mu_k"]) == (5.0, 5.0), base


def test_a_resolved_configuration_with_mu_beside_both_reads_back(cli, tmp_path):
    """The resolved configuration writes mu beside mu_s and mu_k (all it
    was given); as a --config it gives the same results again, mu's draws
    included."""
    import xarray as xr
    cli("sweep", "--mu", 3, "--mu-s", 6, "--mu-k", 4, "--realizations", 20, "-o", tmp_path / "a")
    with xr.open_dataset(tmp_path / "a" / "results.nc") as ds:
        config = ds.attrs["resolved_config"]
    assert {"mu = 3.0", "mu_s = 6.0", "mu_k = 4.0"} <= set(config.splitlines())
    (tmp_path / "again.toml").write_text(config)
    cli("sweep", "--config", tmp_path / "again.toml", "-o", tmp_path / "b")
    assert (tmp_path / "a" / "summary.csv").read_bytes() == (tmp_path / "b" / "summary.csv").read_bytes()


@pytest.mark.parametrize("symbol", ["mu_s", "mu_k"])
def test_an_explicit_zero_friction_is_refused_not_taken_for_mu(cli, tmp_path, symbol):
    """mu_s or mu_k left out is mu; written as 0 it was taken for mu as well,
    without a word (a new user asked for mu_k = 0 and got 5). A flag, a TOML
    key and a keyword refuse it alike, naming it; a grid already did."""
    phrase = f"invalid {symbol} ({'static' if symbol == 'mu_s' else 'kinetic'} friction): 0 " \
             f"(allowed: a finite number > 0; leave {symbol} out for {symbol} = mu)"
    flag = "--" + symbol.replace("_", "-")
    (tmp_path / "zero.toml").write_text(f"[model]\n{symbol} = 0.0\n")
    runs = [cli("simulate", flag, 0, check=False),
            cli("sweep", flag, 0, "--realizations", 2, "-o", tmp_path / "a", check=False),
            cli("sweep", "--config", tmp_path / "zero.toml", "-o", tmp_path / "b", check=False),
            cli("peak", "--initial-realizations", 20, "--ta", 5, flag, 0, check=False)]
    for r in runs:
        assert r.returncode == 2 and phrase in r.stderr, r.stderr
    assert not (tmp_path / "a").exists() and not (tmp_path / "b").exists()
    for call in (stickslip.simulate, stickslip.sweep):
        with pytest.raises(stickslip.Error) as e:
            call(**{symbol: 0})
        assert phrase in str(e.value) and e.value.exit_code == 2
    r = cli("sweep", flag, "0,4", "--realizations", 2, "-o", tmp_path / "c", check=False)
    assert r.returncode == 2 and not (tmp_path / "c").exists()
