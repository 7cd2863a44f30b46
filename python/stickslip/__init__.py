"""stickslip: exact event-driven simulation and parametric statistics of a
dry-friction (stick-slip) oscillator on a randomly switching belt.

    import stickslip
    r = stickslip.simulate(mu=5, lam=1, seed=2)        # one realization
    r.episodes                                          # pandas.DataFrame
    eps = stickslip.simulate_many(mu=5, lam=1, seed=2, realizations=range(2000))
    ds = stickslip.sweep(lam=[0.5, 1, 2], mu=[0.5, 5])  # xarray.Dataset
    ds = stickslip.open("results/results.nc")
    # the model family: damping, static/kinetic friction, a Markov belt
    r = stickslip.simulate(c=0.5, mu_s=6, mu_k=4, belt_levels=[1, 0], belt_rates=[2, 3])

The numbers are the command-line tool's, bit for bit: the same seed gives the
same realization and the same statistics (docs/python.md).
"""
from ._stickslip import Error, __version__, git_revision
from ._realization import Realization, simulate, simulate_many
from ._sweep import open, sweep  # noqa: A004 (stickslip.open reads results.nc)
from ._peak import peak
from ._sensitivity import sensitivity

Error.__doc__ = (
    "Bad input or a failed run; a ValueError. The message is the command-line "
    "tool's: it names the parameter, the value and the allowed range. "
    "`exit_code` is the CLI's exit code for the same error.")

__all__ = ["Error", "Realization", "__version__", "git_revision", "open", "peak", "sensitivity",
           "simulate", "simulate_many", "sweep"]
