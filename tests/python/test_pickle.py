"""A Realization survives pickle and copy.deepcopy (multiprocessing and
joblib pickle what they pass): the unpickled object samples the same
trajectory, bit for bit, for the paper model and a damped one. And
simulate_many labels realization indices beyond 2^63 without wrapping."""
import copy
import pickle

import numpy as np
import pytest

import stickslip


@pytest.mark.parametrize("model", [dict(mu=5, lam=1), dict(mu=5, k=40, lam=1, c=2)])
def test_a_realization_pickles_and_samples_the_same(model):
    r = stickslip.simulate(seed=3, ta=10, **model)
    for other in (pickle.loads(pickle.dumps(r)), copy.deepcopy(r)):
        a, b = r.trajectory(0.01), other.trajectory(0.01)
        assert np.array_equal(a.to_numpy(), b.to_numpy())
        assert r.episodes.equals(other.episodes)


def test_simulate_many_labels_large_indices_without_wrapping():
    big = 2**63 + 5
    frame = stickslip.simulate_many(realizations=[big], seed=1, ta=2)
    assert set(frame["realization"]) == {big}
