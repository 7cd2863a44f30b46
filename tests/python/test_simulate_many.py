"""stickslip.simulate_many(): many realizations in one
call, on threads, as one episodes DataFrame with a `realization` column --
bit for bit the single simulate() calls, whatever the thread count."""
import numpy as np
import pandas as pd
import pytest

import stickslip

MODELS = {
    "paper": dict(mu=5, lam=1, k=40, seed=2, ta=20),
    "damped": dict(mu=5, k=40, lam=1, c=2, seed=3, ta=20),
    "family": dict(mu_s=6, mu_k=4, c=0.5, belt_levels=[1, 0, -2],
                   belt_generator=[[-2, 1, 1], [1, -1, 0], [0.5, 0.5, -1]], seed=4, ta=20),
}


def single_calls(kwargs, realizations):
    frames = []
    for r in realizations:
        ep = stickslip.simulate(realization=r, **kwargs).episodes
        frames.append(ep.assign(realization=r)[["realization", *ep.columns]])
    return pd.concat(frames, ignore_index=True)


def assert_bit_identical(a, b):
    assert list(a.columns) == list(b.columns) and len(a) == len(b)
    for col in a.columns:
        x, y = a[col].to_numpy(), b[col].to_numpy()
        if x.dtype.kind == "f":
            assert x.tobytes() == y.tobytes(), col
        else:
            assert (x == y).all(), col


@pytest.mark.parametrize("model", sorted(MODELS))
def test_equals_the_single_calls_bit_for_bit(model):
    kwargs = MODELS[model]
    realizations = range(3, 23)
    many = stickslip.simulate_many(realizations=realizations, threads=2, **kwargs)
    assert list(many.columns) == ["realization", "mode", "start", "end", "x_start",
                                  "belt_velocity", "censored"]
    assert_bit_identical(many, single_calls(kwargs, realizations))
    assert many["realization"].unique().tolist() == list(realizations)


@pytest.mark.parametrize("model", ["paper", "damped"])
def test_does_not_depend_on_the_thread_count(model):
    kwargs = MODELS[model]
    one = stickslip.simulate_many(realizations=range(40), threads=1, **kwargs)
    two = stickslip.simulate_many(realizations=range(40), threads=2, **kwargs)
    every = stickslip.simulate_many(realizations=range(40), threads=0, **kwargs)
    assert_bit_identical(one, two)
    assert_bit_identical(one, every)


def test_any_order_and_replay_inputs():
    kwargs = dict(mu=5, lam=1, seed=9, ta=10, x0=0.2, belt_start=-1)
    order = [7, 0, 3, 3]
    assert_bit_identical(stickslip.simulate_many(realizations=order, **kwargs),
                         single_calls(kwargs, order))
    assert len(stickslip.simulate_many(realizations=[], **kwargs)) == 0


def test_bad_input_is_refused():
    with pytest.raises(stickslip.Error) as e:
        stickslip.simulate_many(realizations=range(3), mu=-1)
    assert e.value.exit_code == 2 and "mu" in str(e.value)
    with pytest.raises(stickslip.Error, match="realizations entry #2") as e:
        stickslip.simulate_many(realizations=[0, 1.5])
    assert e.value.exit_code == 2
    with pytest.raises(stickslip.Error, match="threads"):
        stickslip.simulate_many(realizations=range(3), threads=-1)
