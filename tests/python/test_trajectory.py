"""Realization.trajectory() across the model family: the
Python samples are the CLI's `simulate --trajectory` samples, bit for bit,
and the sampled motion is continuous. A damped slip once lost its decay
rate on the way through the extension (the segments were copied field by
field), so damped trajectories jumped by 0.15 m at the slip ends."""
import csv

import numpy as np
import pytest

import stickslip

GENERATOR3 = "-2,1,1;1,-1,0;0.5,0.5,-1"

# (Python keywords, the CLI's flags for the same realization)
FAMILY = {
    "paper": (dict(mu=5, lam=1, seed=2, ta=10),
              ["--mu", 5, "--lambda", 1, "--seed", 2, "--ta", 10]),
    "damped": (dict(mu=5, k=40, lam=1, c=2, seed=3, ta=10),
               ["--mu", 5, "--k", 40, "--lambda", 1, "--c", 2, "--seed", 3, "--ta", 10]),
    "static_above_kinetic": (dict(mu_s=6, mu_k=4, k=40, lam=3, seed=4, ta=10),
                             ["--mu-s", 6, "--mu-k", 4, "--k", 40, "--lambda", 3, "--seed", 4,
                              "--ta", 10]),
    "damped_static_above_kinetic_asymmetric": (
        dict(c=0.5, mu_s=6, mu_k=4, belt_levels=[1, 0], belt_rates=[2, 3], seed=2, ta=10),
        ["--c", 0.5, "--mu-s", 6, "--mu-k", 4, "--belt-levels", "1,0", "--belt-rates", "2,3",
         "--seed", 2, "--ta", 10]),
    "three_levels_damped": (
        dict(mu_s=6, mu_k=4, c=1, belt_levels=[1, 0, -2],
             belt_generator=[[-2, 1, 1], [1, -1, 0], [0.5, 0.5, -1]], seed=5, ta=10),
        ["--mu-s", 6, "--mu-k", 4, "--c", 1, "--belt-levels", "1,0,-2", "--belt-generator",
         GENERATOR3, "--seed", 5, "--ta", 10]),
}
DT = 0.001


def read_cli_trajectory(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {col: np.array([float(r[col]) for r in rows]) for col in ("t", "x", "xdot", "v")}


@pytest.mark.parametrize("case", sorted(FAMILY))
def test_trajectory_equals_the_cli_sample_for_sample(case, cli, tmp_path):
    kwargs, flags = FAMILY[case]
    ours = stickslip.simulate(**kwargs).trajectory(DT)
    tr = tmp_path / "trajectory.csv"
    cli("simulate", *flags, "--trajectory", DT, "--trajectory-file", tr, "-o", tmp_path / "ep.csv")
    theirs = read_cli_trajectory(tr)
    assert len(ours) == len(theirs["t"]) > 10_000
    for col in ("t", "x", "xdot", "v"):
        a, b = ours[col].to_numpy(dtype=float), theirs[col]
        bad = np.flatnonzero(a != b)
        assert bad.size == 0, (col, bad[:5], a[bad[:5]], b[bad[:5]])


@pytest.mark.parametrize("case", sorted(FAMILY))
def test_trajectory_is_continuous(case):
    """An invariant independent of any implementation: x is continuous and
    |x'| bounds its slope, so between consecutive samples |dx| <= max|x'| dt."""
    kwargs, _ = FAMILY[case]
    tr = stickslip.simulate(**kwargs).trajectory(DT)
    t, x, xdot = (tr[c].to_numpy() for c in ("t", "x", "xdot"))
    assert (np.diff(t) >= 0).all() and np.diff(t).max() <= DT * (1 + 1e-9)
    bound = np.abs(xdot).max() * np.diff(t) * 1.01 + 1e-9
    jumps = np.abs(np.diff(x))
    worst = int(np.argmax(jumps - bound))
    assert (jumps <= bound).all(), (f"x jumps by {jumps[worst]:.3g} m at t = {t[worst]:.6f} s "
                                    f"(allowed {bound[worst]:.3g})")
