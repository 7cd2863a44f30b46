"""Python's argument types: a number is a number, a whole
number is a whole number, a bool is neither, a parameter is a scalar or a 1-D
sequence, and text is not a number. Every refusal is a stickslip.Error (a
ValueError) naming the parameter, the value and what is allowed, with the
CLI's exit code 2; where the CLI has the same parameter the message is its
own, word for word, with the keyword in place of the flag."""
import numpy as np
import pytest

import stickslip

SMALL = dict(realizations=10, ta=2)


def refused(call, *words):
    with pytest.raises(stickslip.Error) as e:
        call()
    assert isinstance(e.value, ValueError)
    assert e.value.exit_code == 2, (str(e.value), e.value.exit_code)
    for w in words:
        assert w in str(e.value), (w, str(e.value))
    return str(e.value)


@pytest.mark.parametrize("call, words", [
    (lambda: stickslip.simulate(seed=1.5), ["seed", "1.5", "allowed: a whole number"]),
    (lambda: stickslip.simulate(seed=-1), ["seed", "-1", "allowed: a whole number from 0"]),
    (lambda: stickslip.simulate(seed=True), ["seed", "True", "allowed: a whole number"]),
    (lambda: stickslip.simulate(realization=2.0), ["realization", "2.0", "allowed: a whole number"]),
    (lambda: stickslip.simulate(mu=True), ["mu", "True", "allowed: a finite number"]),
    (lambda: stickslip.simulate(mu="five"), ["mu", "five", "allowed: a finite number"]),
    (lambda: stickslip.simulate(mu="5"), ["mu", "'5'", "allowed: a finite number"]),
    (lambda: stickslip.simulate(mu=[1, 2]), ["mu", "[1, 2]", "allowed: a finite number"]),
    (lambda: stickslip.simulate(mu=float("nan")), ["mu", "nan", "allowed: a finite number"]),
    (lambda: stickslip.simulate(x0="0.5"), ["x0", "0.5", "allowed: a finite number"]),
    (lambda: stickslip.simulate(switch_times="1,2"), ["switch_times", "1,2", "allowed: a sequence"]),
    (lambda: stickslip.simulate(switch_times=[1, "x"]), ["switch_times entry #2", "x", "allowed"]),
    (lambda: stickslip.simulate(switch_times=[0.5, 1], switch_levels=[2, 1.5]),
     ["switch_levels entry #2", "1.5", "allowed: a whole number"]),
    (lambda: stickslip.simulate(belt_levels=[1, True]), ["belt_levels entry #2", "True"]),
    (lambda: stickslip.simulate(max_events=0), ["max_events", "0", "allowed: a whole number from 1"]),
    (lambda: stickslip.sweep(realizations=2.5), ["realizations", "2.5", "allowed: a whole number"]),
    (lambda: stickslip.sweep(realizations=-5), ["realizations", "-5", "allowed: a whole number"]),
    (lambda: stickslip.sweep(threads=-1, **SMALL), ["threads", "-1", "allowed: a whole number"]),
    (lambda: stickslip.sweep(seed=-1, **SMALL), ["seed", "-1", "allowed: a whole number"]),
    (lambda: stickslip.sweep(block_size=0.5, **SMALL), ["block_size", "0.5"]),
    (lambda: stickslip.sweep(mu=True, **SMALL), ["mu", "True", "allowed"]),
    (lambda: stickslip.sweep(mu=[1, True], **SMALL), ["mu entry #2", "True"]),
    (lambda: stickslip.sweep(mu="five", **SMALL), ["mu", "five", "allowed"]),
    (lambda: stickslip.sweep(lam=np.array([[1.0, 2.0], [3.0, 4.0]]), **SMALL),
     ["lam", "2 dimensions", "allowed: a number or a 1-D sequence"]),
    (lambda: stickslip.sweep(lam=[[1.0, 2.0], [3.0, 4.0]], **SMALL), ["lam entry #1", "[1.0, 2.0]"]),
    (lambda: stickslip.sweep(records="yes", **SMALL), ["records", "yes", "True or False"]),
    (lambda: stickslip.peak(mu=True, initial_realizations=10), ["mu", "True"]),
    (lambda: stickslip.peak(seed=1.5), ["seed", "1.5", "allowed: a whole number"]),
    (lambda: stickslip.peak(range=(5, 1)), ["range", "(5, 1)", "0 < lo < hi"]),
    (lambda: stickslip.peak(range=("a", 2)), ["range", "allowed"]),
    (lambda: stickslip.simulate(ta=2).trajectory(0), ["dt", "0", "allowed"]),
], ids=lambda v: "" if callable(v) else "-".join(map(str, v[:2])))
def test_refused_with_exit_code_2(call, words):
    refused(call, *words)


@pytest.mark.parametrize("python, flags", [
    (lambda: stickslip.simulate(seed=1.5), ("simulate", "--seed", "1.5")),
    (lambda: stickslip.simulate(seed=-1), ("simulate", "--seed", "-1")),
    (lambda: stickslip.simulate(realization=-3), ("simulate", "--realization", "-3")),
    (lambda: stickslip.sweep(realizations=2.5), ("sweep", "--realizations", "2.5")),
    (lambda: stickslip.sweep(realizations=-5), ("sweep", "--realizations", "-5")),
    (lambda: stickslip.sweep(threads=-1, **SMALL), ("sweep", "--threads", "-1")),
    (lambda: stickslip.sweep(bins=0, **SMALL), ("sweep", "--bins", "0")),
    (lambda: stickslip.sweep(block_size=2**30, **SMALL), ("sweep", "--block-size", str(2**30))),
])
def test_whole_number_messages_are_the_clis(python, flags, cli, tmp_path):
    command, flag, value = flags
    p = cli(command, flag, value, "--ta", 1, "-o", tmp_path / "out", check=False)
    assert p.returncode == 2
    ours = refused(python)
    keyword = flag.removeprefix("--").replace("-", "_")
    assert p.stderr.strip() == "stickslip: error: " + ours.replace(f"invalid {keyword}:", f"invalid {flag}:")


def test_integers_are_any_integer_type_and_give_the_same_realization():
    a = stickslip.simulate(seed=3, realization=2, ta=5)
    for seed, realization in [(np.int64(3), np.uint8(2)), (np.array(3), 2)]:
        b = stickslip.simulate(seed=seed, realization=realization, ta=5)
        assert b.episodes.equals(a.episodes)
    huge = 2**64 - 1
    assert stickslip.simulate(seed=huge, ta=1).seed == huge
    refused(lambda: stickslip.simulate(seed=2**64), "seed", str(2**64))


def test_numbers_are_any_real_type():
    a = stickslip.simulate(mu=5, lam=2, seed=1, ta=5)
    b = stickslip.simulate(mu=np.int32(5), lam=np.float32(2), seed=1, ta=5)
    assert b.episodes.equals(a.episodes)
    ds = stickslip.sweep(lam=np.array([1, 2]), mu=(np.float64(5),), realizations=20, ta=2)
    assert list(ds["lambda"].values) == [1.0, 2.0]


def test_open_refuses_what_is_not_a_results_file(tmp_path):
    out = tmp_path / "run"
    stickslip.sweep(lam=[1, 2], realizations=20, ta=2, output=str(out))
    data = (out / "results.nc").read_bytes()
    (tmp_path / "truncated.nc").write_bytes(data[: len(data) // 2])
    for path in (tmp_path / "truncated.nc", out / "summary.json", out / "summary.csv"):
        message = refused(lambda: stickslip.open(path), str(path))
        assert "allowed" in message or "not a results.nc" in message
    refused(lambda: stickslip.open(tmp_path / "missing.nc"), "missing.nc", "does not exist")
