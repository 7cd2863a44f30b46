"""One model parser: the same assignments as CLI flags, TOML [model] keys and
Python keywords give the same resolved model, mu applying before mu_s and
mu_k whatever the written order, and the same refusal of a bad value."""
import json

import pytest

import stickslip
from stickslip import _stickslip
from stickslip._parameters import PARAMETERS, model_arguments, python_message

# Written with mu last: it still applies first, and mu_s, mu_k refine it.
ASSIGNMENTS = [("mu_s", 6.0), ("mu_k", 4.0), ("mu", 5.0), ("c", 0.3), ("k", 9.0)]
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
    assert from_python["mu_s"] == 6.0 and from_python["mu_k"] == 4.0 and from_python["k"] == 9.0


def test_mu_alone_sets_both_and_a_refinement_keeps_the_other(cli, tmp_path):
    assignments = [("mu_k", 2.0), ("mu", 3.0)]
    (tmp_path / "model.toml").write_text(toml(assignments))
    expected = python_base(assignments)
    assert expected["mu_s"] == 3.0 and expected["mu_k"] == 2.0
    assert cli_base(cli, tmp_path, *flags(assignments)) == expected
    assert cli_base(cli, tmp_path, "--config", tmp_path / "model.toml") == expected


@pytest.mark.parametrize("assignments, phrase", [
    ([("mu_s", 3.0), ("mu", 5.0), ("mu_k", 4.0)], "invalid mu_k (kinetic friction): 4"),
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
