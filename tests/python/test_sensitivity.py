"""stickslip.sensitivity() against the CLI's `sensitivity`: the same indices
for the same arguments, output= and resume=, the writer lock's files, and
bad input raised with keyword names."""
import json
import os
import subprocess

import pytest

import stickslip

ARGS = dict(k=40.0, ta=20.0, mu="uniform(2,7)", lam="loguniform(0.5,10)", samples=600,
            block_size=20, seed=3)
CLI = ["--k", "40", "--ta", "20", "--mu", "uniform(2,7)", "--lambda", "loguniform(0.5,10)",
       "--samples", "600", "--block-size", "20", "--seed", "3"]
ESTIMATES = ("statistic", "realizations", "samples", "laws", "mean", "variance",
             "intrinsic_variance", "indices", "shares")


def estimates(d):
    return {k: d[k] for k in ESTIMATES}


def test_same_indices_as_the_cli(tmp_path):
    cli = os.environ.get("STICKSLIP_CLI")
    if not cli:
        pytest.skip("STICKSLIP_CLI is not set")
    out = subprocess.run([cli, "sensitivity", *CLI, "--threads", "2", "--format", "json",
                          "-o", str(tmp_path / "cli")], check=True, capture_output=True, text=True)
    theirs = json.loads(out.stdout)
    ours = stickslip.sensitivity(**ARGS, threads=1)
    assert estimates(ours) == estimates(theirs)
    assert ours["realizations"] == 600 * 5 and len(ours["indices"]) == 4


def test_output_and_resume(tmp_path):
    d = tmp_path / "study"
    first = stickslip.sensitivity(**ARGS, output=d)
    assert (d / "sensitivity.nc").is_file() and (d / "summary.json").is_file()
    assert not (d / ".journal").exists()
    again = stickslip.sensitivity(**ARGS, output=d, resume=True)
    assert estimates(again) == estimates(first)
    with pytest.raises(stickslip.Error, match="already exists"):
        stickslip.sensitivity(**ARGS, output=d)
    with pytest.raises(stickslip.Error, match="another configuration"):
        stickslip.sensitivity(**{**ARGS, "seed": 4}, output=d, resume=True)


def test_target_halfwidth_stops_when_every_interval_is_narrow_enough():
    r = stickslip.sensitivity(k=40.0, ta=20.0, mu="uniform(2,7)", target_halfwidth=0.05,
                              min_samples=200, block_size=50)
    groups = [*r["indices"], r["shares"]]
    widths = [(v[1] - v[0]) / 2 for g in groups for k, v in g.items() if k.endswith("_ci95")]
    assert len(widths) == 2 + 1 + 2
    assert max(widths) <= 0.05 and r["samples"] >= 200


@pytest.mark.parametrize("kwargs, phrase", [
    (dict(mu=5.0), "no uncertain input"),
    (dict(mu="uniform(2,7)", statistic="first_stick_duration"), "statistic"),
    (dict(m="normal(mean=1,sd=0.1)"), "normal"),
    (dict(mu="uniform(2,7)", target_halfwidth=2.0), "target_halfwidth"),
    (dict(mu="frobnicate(1,2)"), "frobnicate"),
    (dict(mu="uniform(2,7)", statistic=""), "statistic"),
    (dict(mu="gamma(mean=5,cv=1e-200)"), "cv"),
])
def test_bad_input(kwargs, phrase, tmp_path):
    with pytest.raises(stickslip.Error, match=phrase) as e:
        stickslip.sensitivity(**kwargs, samples=10, output=tmp_path / "bad")
    assert e.value.exit_code == 2
    assert not (tmp_path / "bad").exists()


def test_samples_beside_a_target_are_refused_not_ignored():
    with pytest.raises(stickslip.Error, match="samples.*target_halfwidth"):
        stickslip.sensitivity(mu="uniform(2,7)", samples=100, target_halfwidth=0.3)
    with pytest.raises(stickslip.Error, match="max_samples.*only with target_halfwidth"):
        stickslip.sensitivity(mu="uniform(2,7)", max_samples=7)


def test_a_grid_is_refused():
    # named as a grid, with the law it could be (it said only "a finite number")
    with pytest.raises(stickslip.Error, match=r"invalid lam: \[1.0, 2.0\] \(allowed: a finite "
                                              r"number, or a law's text such as "
                                              r"'uniform\(0.5,10\)'; got a sequence"):
        stickslip.sensitivity(mu="uniform(2,7)", lam=[1.0, 2.0], samples=10)


def test_a_sweep_too_big_for_memory_is_refused_without_an_output_folder():
    # The in-memory path (no output=) checks the memory estimate too: it
    # asked for ~80 GB and raised MemoryError before (the joint histogram,
    # which only the family statistics hold).
    with pytest.raises(stickslip.Error, match="invalid grid size") as e:
        stickslip.sweep(bins=100000, realizations=1, statistics="family")
    assert e.value.exit_code == 2
