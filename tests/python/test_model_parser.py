"""One model parser: the same assignments as CLI flags, TOML [model] keys and
Python keywords give the same resolved model, mu applying before mu_s and
mu_k whatever the written order, and the same refusal of a bad value."""
import json

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


MU_BESIDE_BOTH = "beside both it would have no effect (they set all it sets), so drop"


def test_mu_beside_both_refinements_is_refused_not_ignored(cli, tmp_path):
    """--mu with --mu-s and --mu-k sets nothing they do not set again: the
    CLI and Python refuse it by name and write nothing, rather than run a
    model other than the one the user wrote (a new user's report)."""
    for command in ("sweep", "simulate"):
        out = tmp_path / command
        r = cli(command, "--mu-k", 4, "--mu", 5, "--mu-s", 6, "-o", out, check=False)
        assert r.returncode == 2, r.stderr
        assert "invalid --mu (Coulomb friction coefficient" in r.stderr
        assert "'5'" in r.stderr and MU_BESIDE_BOTH + " --mu or one of them" in r.stderr
        assert not out.exists()
    r = cli("sweep", "--mu", 5, "--mu-s", "6,7", "--mu-k", 4, "-o", tmp_path / "grid", check=False)
    assert r.returncode == 2 and "invalid --mu" in r.stderr and not (tmp_path / "grid").exists()
    # Python's words: the CLI's refusal with keywords for flags
    with pytest.raises(stickslip.Error) as e:
        stickslip.sweep(mu=5, mu_s=[6, 7], mu_k=4, realizations=2)
    assert str(e.value).startswith("invalid mu (Coulomb friction coefficient")
    assert "'5'" in str(e.value) and MU_BESIDE_BOTH + " mu or one of them" in str(e.value)
    assert "one of mu_s, mu_k" in str(e.value) and e.value.exit_code == 2
    with pytest.raises(stickslip.Error, match=r"invalid mu \(.*\): '0.5,2'"):
        stickslip.sweep(friction_coefficient=[0.5, 2], static_friction=6, mu_k=4, realizations=2)
    with pytest.raises(stickslip.Error, match=r"invalid mu \(.*\): 'uniform\(4,6\)'"):
        stickslip.simulate(mu="uniform(4,6)", mu_s=6, mu_k=4)
    # with one refinement, mu still sets the other
    assert python_base([("mu", 5.0), ("mu_s", 6.0)])["mu_k"] == 5.0
    assert python_base([("mu", 5.0), ("mu_k", 4.0)])["mu_s"] == 5.0


def test_a_resolved_configuration_with_mu_beside_both_reads_back(cli, tmp_path):
    """The resolved configuration writes mu beside mu_s and mu_k (all it
    was given); as a --config it gives the same model again."""
    import xarray as xr
    cli("sweep", "--mu-s", 6, "--mu-k", 4, "--realizations", 2, "-o", tmp_path / "a")
    with xr.open_dataset(tmp_path / "a" / "results.nc") as ds:
        config = ds.attrs["resolved_config"]
    assert {"mu = 5.0", "mu_s = 6.0", "mu_k = 4.0"} <= set(config.splitlines())
    (tmp_path / "again.toml").write_text(config)
    assert cli_base(cli, tmp_path, "--config", tmp_path / "again.toml") == cli_base(
        cli, tmp_path, "--mu-s", 6, "--mu-k", 4)
