"""Python's keywords, not the command line's flags: belt_start follows the
argument rules (an int level or "stationary"), a path is a str or an
os.PathLike, every message names the Python keyword (switch_times,
belt_start, output, overwrite=True, resume=True), lambda_ is a
documented alias of lam, and every parameter is also taken under its long
name (the command line's alias flag)."""
import pathlib
import re

import numpy as np
import pytest

import stickslip
from stickslip._parameters import python_message

DOCS = pathlib.Path(__file__).resolve().parents[2] / "docs"
THREE = dict(belt_levels=[1.0, 0.0, -2.0], belt_generator=[[-2, 1, 1], [1, -1, 0], [0.5, 0.5, -1]])
TWO_LEVELS = "(allowed: +1 (first level), -1 (second level) or stationary)"
THREE_LEVELS = "(allowed: a level number 1..3, or stationary)"


def refused(call):
    with pytest.raises(stickslip.Error) as e:
        call()
    assert isinstance(e.value, ValueError) and not isinstance(e.value, TypeError)
    assert e.value.exit_code == 2, (str(e.value), e.value.exit_code)
    assert "--" not in str(e.value), str(e.value)
    return str(e.value)


# --- belt_start: an int level or "stationary" --------------------------------

@pytest.mark.parametrize("value, belt, message", [
    (1.0, {}, f"invalid belt_start: '1.0' {TWO_LEVELS}"),
    (-1.0, {}, f"invalid belt_start: '-1.0' {TWO_LEVELS}"),
    (np.float64(1.0), {}, f"invalid belt_start: '1.0' {TWO_LEVELS}"),
    (2.0, THREE, f"invalid belt_start: '2.0' {THREE_LEVELS}"),
    ("1", {}, f"invalid belt_start: ''1'' {TWO_LEVELS}"),
    ("-1", {}, f"invalid belt_start: ''-1'' {TWO_LEVELS}"),
    ("+1", {}, f"invalid belt_start: ''+1'' {TWO_LEVELS}"),
    ("2", THREE, f"invalid belt_start: ''2'' {THREE_LEVELS}"),
    (" stationary", {}, f"invalid belt_start: '' stationary'' {TWO_LEVELS}"),
    (True, {}, f"invalid belt_start: 'True' {TWO_LEVELS}"),
    (2, {}, f"invalid belt_start: '2' {TWO_LEVELS}"),
    (0, THREE, f"invalid belt_start: '0' {THREE_LEVELS}"),
    (-1, THREE, f"invalid belt_start: '-1' {THREE_LEVELS}"),
])
def test_belt_start_refuses_floats_and_text_with_the_clis_message(value, belt, message):
    assert refused(lambda: stickslip.simulate(belt_start=value, ta=2, **belt)) == message
    assert refused(lambda: stickslip.simulate_many(belt_start=value, ta=2, realizations=[0],
                                                   **belt)) == message
    assert refused(lambda: stickslip.sweep(belt_start=value, ta=2, realizations=10,
                                           **belt)) == message


def test_a_refused_float_is_refused_by_the_cli_too(cli, tmp_path):
    p = cli("simulate", "--belt-start", "1.0", "--ta", 2, "-o", tmp_path / "x.csv", check=False)
    assert p.returncode == 2
    ours = refused(lambda: stickslip.simulate(belt_start=1.0, ta=2))
    assert p.stderr.strip() == "stickslip: error: " + ours.replace("belt_start", "--belt-start")


@pytest.mark.parametrize("value, belt, level", [
    (1, {}, 1), (-1, {}, -1), (np.int64(-1), {}, -1), (np.array(1), {}, 1),
    (3, THREE, 3), (np.uint8(2), THREE, 2),
])
def test_belt_start_accepts_int_levels(value, belt, level):
    r = stickslip.simulate(belt_start=value, ta=2, **belt)
    assert r.belt_start == level
    assert r.episodes.equals(stickslip.simulate(belt_start=level, ta=2, **belt).episodes)


def test_belt_start_stationary_is_the_default_draw():
    for belt in ({}, THREE):
        a = stickslip.simulate(belt_start="stationary", seed=4, ta=3, **belt)
        b = stickslip.simulate(seed=4, ta=3, **belt)
        assert a.episodes.equals(b.episodes) and a.belt_start == b.belt_start


# --- paths and text ------------------------------------------------------------

@pytest.mark.parametrize("value, kind", [(5, "an int"), (2.5, "a float"), (b"out", "a bytes"),
                                         (["out"], "a list"), (True, "a bool")])
def test_sweep_output_must_be_a_path(value, kind):
    message = refused(lambda: stickslip.sweep(lam=1, realizations=10, ta=1, output=value))
    assert message == (f"invalid output: {value!r} (allowed: a path: a str or an os.PathLike such "
                       f"as pathlib.Path; got {kind})")


def test_sweep_output_refuses_an_empty_path():
    message = refused(lambda: stickslip.sweep(lam=1, realizations=10, ta=1, output=""))
    assert message.startswith("invalid output: '' (allowed: a path")


def test_sweep_output_takes_a_pathlib_path(tmp_path):
    out = tmp_path / "p"
    ds = stickslip.sweep(lam=[1, 2], realizations=10, ta=1, output=out)
    assert (out / "results.nc").exists() and dict(ds.sizes)["lam"] == 2


@pytest.mark.parametrize("value", [5, None, b"results.nc", 1.5])
def test_open_path_must_be_a_path(value):
    message = refused(lambda: stickslip.open(value))
    assert message.startswith(f"invalid path: {value!r} (allowed: a path: a str or an os.PathLike")


@pytest.mark.parametrize("call, keyword", [
    (lambda: stickslip.sweep(lam=1, realizations=10, engine=5), "engine"),
    (lambda: stickslip.sweep(lam=1, realizations=10, target_ci=5), "target_ci"),
    (lambda: stickslip.peak(statistic=5), "statistic"),
    (lambda: stickslip.peak(over=5), "over"),
    (lambda: stickslip.peak(method=5), "method"),
])
def test_every_text_keyword_is_checked(call, keyword):
    assert refused(call) == f"invalid {keyword}: 5 (allowed: text (a str); got an int)"


# --- messages name the Python keywords -----------------------------------------

def test_switch_times_message_names_the_keyword():
    assert refused(lambda: stickslip.simulate(switch_times=[2, 1])) == (
        "invalid switch_times entry #2: 1 (allowed: strictly greater than the previous time 2: "
        "switch times must be sorted and distinct)")


def test_belt_start_message_names_the_keyword():
    assert refused(lambda: stickslip.simulate(belt_start=2)) == f"invalid belt_start: '2' {TWO_LEVELS}"
    assert refused(lambda: stickslip.sweep(belt_start=4, realizations=10, **THREE)).startswith(
        "invalid belt_start: '4'")


def test_axis_and_belt_messages_name_the_keywords():
    assert refused(lambda: stickslip.sweep(lam=[0.1, -2.0], realizations=10)).startswith(
        "invalid lam: '0.1,-2'")
    assert refused(lambda: stickslip.sweep(mu_s=[3.0, -1.0], realizations=10)).startswith(
        "invalid mu_s: '3,-1'")
    assert refused(lambda: stickslip.simulate(belt_levels=[1, 0, -1])).endswith(
        "(allowed: a 3 x 3 rate matrix for 3 belt levels (belt_generator))")
    assert refused(lambda: stickslip.simulate(belt_generator=[[1.0, 2.0], [3.0]])).startswith(
        "invalid belt_generator: '1,2;3'")
    assert refused(lambda: stickslip.simulate(belt_levels=[1.0])).startswith(
        "invalid belt_levels (count): 1")


def test_resume_refusal_names_the_keywords(tmp_path):
    out = tmp_path / "ow"
    stickslip.sweep(lam=[1, 2], realizations=20, seed=1, output=out)
    message = refused(lambda: stickslip.sweep(lam=[1, 3], realizations=20, seed=1, output=out,
                                              resume=True))
    assert message == (
        f"output '{out}' holds the finished run of another configuration (grid axis lambda value "
        "#2: 2 vs 3; those results vs this call); there is no journal, so resume=True has nothing "
        "to continue: choose another output folder for this configuration, or pass overwrite=True "
        "to replace those results")
    (out / "summary.csv").unlink()
    message = refused(lambda: stickslip.sweep(lam=[1, 2], realizations=20, seed=1, output=out,
                                              resume=True))
    assert message.startswith(f"output '{out}' holds an incomplete set of finished outputs")
    assert "resume=True" in message and "overwrite=True" in message and " -o " not in message


@pytest.mark.parametrize("cli_message, python", [
    ("invalid --switch-times entry #2: 1 (allowed: x)", "invalid switch_times entry #2: 1 (allowed: x)"),
    ("invalid --belt-start: '2' (allowed: y)", "invalid belt_start: '2' (allowed: y)"),
    ("invalid --lambda: '0.1,-2' (allowed: z)", "invalid lam: '0.1,-2' (allowed: z)"),
    ("invalid --mu-k: '-1'", "invalid mu_k: '-1'"),
    # the run layer's (src/run/journaled_run.cpp) and the writer lock's
    ("invalid -o (output directory): 'd' (allowed: a directory without the journal of an "
     "unfinished run (found d/.journal): add --resume to continue that run, or remove the journal)",
     "invalid output: 'd' (allowed: a directory without the journal of an unfinished run (found "
     "d/.journal): pass resume=True to continue that run, or remove the journal)"),
    ("interrupted by signal 2: 3 finished units are journaled in d/.journal; continue with the "
     "same command and --resume", "interrupted by signal 2: 3 finished units are journaled in "
     "d/.journal; continue with the same call and resume=True"),
    ("x; the units of the journal's last checkpoint, if any, stay in it: rerun with --resume to "
     "write the outputs (units finished after that checkpoint are computed again)",
     "x; the units of the journal's last checkpoint, if any, stay in it: rerun with resume=True "
     "to write the outputs (units finished after that checkpoint are computed again)"),
    ("output directory 'd' is in use by stickslip sweep: one writer at a time; wait for it to "
     "finish (or stop it), or choose another -o DIR", "output directory 'd' is in use by "
     "stickslip sweep: one writer at a time; wait for it to finish (or stop it), or choose "
     "another output folder"),
    ("the bound on events per realization was hit (raise --max-events, or check that ...)",
     "the bound on events per realization was hit (raise max_events, or check that ...)"),
    # values are never rewritten: negative numbers, text that is no known flag, paths
    ("invalid mu: -1 (allowed: > 0)", "invalid mu: -1 (allowed: > 0)"),
    ("invalid x0: -inf", "invalid x0: -inf"),
    ("cannot write or read '/tmp/a--resume/x-o': y", "cannot write or read '/tmp/a--resume/x-o': y"),
    ("invalid --unknown-flag: 1", "invalid --unknown-flag: 1"),
])
def test_python_message_maps_flags_to_keywords(cli_message, python):
    assert python_message(cli_message) == python


# --- lambda_: a documented alias of lam ----------------------------------------

def test_lambda_underscore_is_lam():
    a = stickslip.simulate(lambda_=3, seed=5, ta=5)
    assert a.parameters["lambda"] == 3.0
    assert a.episodes.equals(stickslip.simulate(lam=3, seed=5, ta=5).episodes)
    ds = stickslip.sweep(lambda_=[1, 3], realizations=20, ta=2)
    assert "lam" in ds.dims and list(ds["lambda"].values) == [1.0, 3.0]
    with pytest.raises(TypeError, match="given twice"):
        stickslip.simulate(lam=1, lambda_=2)


# --- the long names: the command line's alias flags, from the parameter table --

LONG_NAMES = {"m": "mass", "k": "stiffness", "g": "gravity", "mu": "friction_coefficient",
              "V": "belt_speed", "lam": "switch_rate", "ta": "window", "c": "damping",
              "mu_s": "static_friction", "mu_k": "kinetic_friction"}


def test_each_parameter_is_also_taken_under_its_long_name():
    # the keywords and the long names as the paper and the CLI's --help
    # spell them, written here by hand: the table's rows must give them
    assert sorted(kw for kw, *_ in stickslip._parameters.PARAMETERS.values()) == sorted(LONG_NAMES)
    assert stickslip._parameters.ALIASES == {**{v: k for k, v in LONG_NAMES.items()},
                                             "lambda_": "lam"}
    values = {"m": 2.0, "k": 30.0, "g": 9.0, "mu": 4.0, "V": 0.5, "lam": 1.5, "ta": 3.0,
              "c": 0.3, "mu_s": 5.0, "mu_k": 3.5}  # ten distinct values
    # mu beside both mu_s and mu_k sets neither (a warning, test_model_parser):
    # mu with mu_s, then mu_s with mu_k, each under both names
    for left_out in ("mu_k", "mu"):
        given = {kw: v for kw, v in values.items() if kw != left_out}
        a = stickslip.simulate(seed=4, **given)
        b = stickslip.simulate(seed=4, **{LONG_NAMES[kw]: v for kw, v in given.items()})
        assert a.parameters == b.parameters
        assert a.episodes.equals(b.episodes)
        assert (a.parameters["mu_s"], a.parameters["mu_k"]) == (
            5.0, 4.0 if left_out == "mu_k" else 3.5)
    for kw, long_name in LONG_NAMES.items():
        with pytest.raises(TypeError, match="given twice"):
            stickslip.simulate(**{kw: values[kw], long_name: values[kw]})
    ds = stickslip.sweep(stiffness=[20, 40], realizations=10, ta=2)
    assert list(ds["k"].values) == [20.0, 40.0]


def test_lambda_underscore_is_documented():
    for fn in (stickslip.simulate, stickslip.sweep, stickslip.peak):
        assert "lambda_ for lam" in fn.__doc__, fn.__name__
    assert "`lambda_`" in (DOCS / "python.md").read_text()


# --- docs: belt_velocity and the Realization's attributes ----------------------

def test_docs_define_the_episodes_belt_velocity_and_the_realization_attributes():
    python, outputs = (" ".join((DOCS / name).read_text().split())
                       for name in ("python.md", "outputs.md"))
    for text in (python, outputs):
        assert "belt velocity at the episode's start" in text
        assert "belt_switch" in text and "a slip can span belt switches" in text.lower()
    for attribute in ("`x0`, `xdot0`", "`belt_start`", "`episodes`", "`events`", "`record`",
                      "`parameters`"):
        assert f"| {attribute} |" in python, attribute
    doc = stickslip.Realization.__doc__
    assert "at the episode's start" in doc and "x0, xdot0, belt_start" in doc


@pytest.mark.parametrize("call, typo, near", [
    (lambda **kw: stickslip.sweep(realizations=2, **kw), "lamda", "lam"),
    (lambda **kw: stickslip.sweep(**kw), "realisations", "realizations"),
    (lambda **kw: stickslip.sweep(**kw), "switchrate", "switch_rate"),
    (lambda **kw: stickslip.simulate(**kw), "xdot", "xdot0"),
    (lambda **kw: stickslip.simulate_many(realizations=2, **kw), "sed", "seed"),
    (lambda **kw: stickslip.peak(**kw), "staticfriction", "static_friction"),
    (lambda **kw: stickslip.sensitivity(**kw), "sample", "samples"),
])
def test_a_misspelt_keyword_is_named_with_the_nearest(call, typo, near):
    """As the command line suggests the nearest flag (a new user found a
    plain TypeError); a word near nothing gets no suggestion."""
    with pytest.raises(TypeError, match=re.escape(f"{typo} (did you mean {near}?)")):
        call(**{typo: 1})
    with pytest.raises(TypeError, match=r"unexpected keyword arguments: zzzz$"):
        call(zzzz=1)


def test_a_constant_statistic_warns_that_its_indices_are_undefined(tmp_path):
    """As the CLI warns (damping_power is 0 without damping): the mean and
    variance are 0, the indices NaN (None in JSON), and a UserWarning says
    why."""
    with pytest.warns(UserWarning, match="damping_power is constant over the design"):
        r = stickslip.sensitivity(statistic="damping_power", k=40, mu="uniform(2,7)",
                                  samples=32)
    assert r["mean"] == 0 and r["variance"] == 0 and r["indices"][0]["first_order"] is None
    stickslip.sensitivity(mu="uniform(2,7)", samples=16, output=str(tmp_path / "s"))
    with pytest.raises(stickslip.Error, match="continue an interrupted study"):
        stickslip.sensitivity(mu="uniform(2,7)", samples=16, output=str(tmp_path / "s"))
