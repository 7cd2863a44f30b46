"""Laws for model parameters (uncertain parameters) through the Python keywords: any
model keyword takes a law's text, parsed by the library's parse_law, so that
sweep() equals the CLI's `sweep` with the same law bit for bit, simulate()
with realization= replays a sweep's realization and returns the values it
drew, and every bad law is refused with the CLI's message, keywords in place
of flags (python_message)."""
import csv
import json

import pytest
import xarray as xr

import stickslip
from stickslip._parameters import python_message
from test_sweep import assert_same_dataset

LAW = "gamma(mean=5,cv=0.2)"


@pytest.fixture(scope="module")
def cli_sweep(tmp_path_factory, cli):
    out = tmp_path_factory.mktemp("cli") / "laws"
    cli("sweep", "--k", 40, "--lambda", "1,3.8", "--mu", LAW, "--realizations", 300,
        "--block-size", 40, "--seed", 7, "--records", "-o", out)
    return out


def test_sweep_with_a_law_and_an_axis_equals_the_cli(cli_sweep):
    ours = stickslip.sweep(k=40, lam=[1, 3.8], mu=LAW, realizations=300, block_size=40, seed=7,
                           records=True)
    with xr.open_dataset(cli_sweep / "results.nc") as theirs:
        assert_same_dataset(ours, theirs.load())
    assert list(ours.dims)[:1] == ["lam"]  # the law is not a dimension


def test_simulate_replays_the_sweeps_records_and_returns_the_drawn_values(cli_sweep, cli):
    rows = list(csv.DictReader(open(cli_sweep / "records.csv")))
    for row in rows[::37]:
        r = stickslip.simulate(k=40, lam=float(row["lambda"]), mu=LAW, seed=7,
                               realization=int(row["realization"]))
        assert r.drawn == {"mu": float(row["mu"])}
        assert r.laws == {"mu": LAW}
        assert r.parameters["mu"] == float(row["mu"])
        assert (r.x0, r.xdot0, r.belt_start) == (float(row["x0"]), float(row["xdot0"]),
                                                 int(row["belt_start"]))
        assert r.record["S_T"] == int(row["sticks"])
        assert r.record["R"] == float(row["stick_fraction"])
        assert r.record["belt_switches"] == int(row["belt_switches"])
        theirs = json.loads(cli("simulate", "--k", 40, "--lambda", row["lambda"], "--mu", LAW,
                                "--seed", 7, "--realization", row["realization"],
                                "--format", "json").stdout)
        assert theirs["drawn"] == r.drawn and theirs["laws"] == r.laws
        assert [e["end"] for e in theirs["episodes"]] == list(r.episodes["end"])


def test_simulate_many_with_a_law_is_simulate_realization_by_realization():
    many = stickslip.simulate_many(realizations=[4, 1], k=40, mu=LAW, seed=3, threads=2)
    for i in (4, 1):
        one = stickslip.simulate(k=40, mu=LAW, seed=3, realization=i).episodes
        assert list(many[many["realization"] == i]["end"]) == list(one["end"])


def test_without_laws_nothing_changes():
    r = stickslip.simulate(k=40, seed=3)
    assert r.realization == 0 and r.drawn == {} and r.laws == {}
    assert r.record == stickslip.simulate(k=40, seed=3, realization=0).record


# (Python keywords, the same call as CLI arguments): each refused with exit
# code 2 and the CLI's message, flags turned into keywords.
BAD = [
    (dict(mu="gama(mean=5,cv=0.2)"), ["--mu", "gama(mean=5,cv=0.2)"]),
    (dict(mu="gamma(mean=5)"), ["--mu", "gamma(mean=5)"]),
    (dict(k="gamma(mean=40,cv=0.2,sd=1)"), ["--k", "gamma(mean=40,cv=0.2,sd=1)"]),
    (dict(k="gamma(40,0.2)"), ["--k", "gamma(40,0.2)"]),
    (dict(lam="uniform(1,2,3)"), ["--lambda", "uniform(1,2,3)"]),
    (dict(m="normal(mean=1,sd=0.1)"), ["--m", "normal(mean=1,sd=0.1)"]),
    (dict(lam="uniform(-1,2)"), ["--lambda", "uniform(-1,2)"]),
    (dict(c="normal(mean=0.1,sd=0.01)"), ["--c", "normal(mean=0.1,sd=0.01)"]),
    (dict(mu_s=5, mu_k="uniform(1,6)"), ["--mu-s", "5", "--mu-k", "uniform(1,6)"]),
    (dict(mu_s="uniform(3,5)", mu_k="uniform(1,4)"),
     ["--mu-s", "uniform(3,5)", "--mu-k", "uniform(1,4)"]),
]


def cli_message(cli, *args):
    p = cli(*args, check=False)
    assert p.returncode == 2, p.stderr
    prefix = "stickslip: error: "
    assert p.stderr.startswith(prefix), p.stderr
    return p.stderr[len(prefix):].strip()


@pytest.mark.parametrize("keywords, flags", BAD, ids=[" ".join(f) for _, f in BAD])
def test_bad_laws_give_the_cli_message_with_keywords(keywords, flags, cli, tmp_path):
    expected = python_message(cli_message(cli, "sweep", *flags, "-o", tmp_path / "cli"))
    with pytest.raises(stickslip.Error) as e:
        stickslip.sweep(**keywords, realizations=10, output=tmp_path / "py")
    assert str(e.value) == expected
    assert e.value.exit_code == 2
    assert not (tmp_path / "cli").exists() and not (tmp_path / "py").exists()
    # the message names the parameter by its keyword and the law
    keyword = list(keywords)[-1]
    assert keyword in expected and "--" not in expected


def test_simulate_refuses_a_law_without_realization_as_the_cli(cli):
    expected = python_message(cli_message(cli, "simulate", "--mu", LAW))
    with pytest.raises(stickslip.Error) as e:
        stickslip.simulate(mu=LAW)
    assert str(e.value) == expected
    assert "realization" in expected and "--" not in expected
    expected = python_message(cli_message(cli, "simulate", "--mu", LAW, "--realization", 2,
                                          "--x0", 0.25))
    with pytest.raises(stickslip.Error) as e:
        stickslip.simulate(mu=LAW, realization=2, x0=0.25)
    assert str(e.value) == expected


def test_peak_refuses_laws():
    with pytest.raises(stickslip.Error, match=r"^invalid mu: 'gamma\(mean=5,cv=0.2\)'.*"
                                              r"does not take laws"):
        stickslip.peak(mu=LAW)


def test_text_that_is_not_a_law_is_refused_naming_both_forms():
    with pytest.raises(stickslip.Error, match=r"invalid mu: 'five' \(allowed: a number, a 1-D "
                                              r"sequence of finite numbers or a grid's text such as "
                                              r"'log:0.1:30:40', or a law's text"):
        stickslip.sweep(mu="five", realizations=10)
    with pytest.raises(stickslip.Error, match=r"invalid k: '40' \(allowed: a finite number, or"):
        stickslip.simulate(k="40")


def test_resume_recognizes_finished_outputs_with_laws(tmp_path):
    """The resolved config in results.nc writes the law in canonical text and
    reads back to the same spec, so resume=True finds the finished outputs
    (and reads them back) instead of refusing or recomputing them."""
    out = tmp_path / "laws"
    keywords = dict(k=40, lam=[1, 3.8], mu="gamma(mean = 5, cv = 0.2)", realizations=100, seed=5)
    first = stickslip.sweep(**keywords, output=out)
    stamp = (out / "results.nc").stat().st_mtime_ns
    again = stickslip.sweep(**keywords, output=out, resume=True)
    assert (out / "results.nc").stat().st_mtime_ns == stamp
    assert_same_dataset(first, again)
    assert 'mu = "gamma(mean=5,cv=0.2)"' in first.attrs["resolved_config"]
