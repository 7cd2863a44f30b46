"""stickslip.peak(): the maximizer of a mean statistic over one parameter,
exactly as `stickslip peak` computes it (docs/precision.md)."""
from . import _stickslip
from ._parameters import unexpected_keywords
from ._parameters import (belt_arguments, describe, error, extension, max_events_of, model_arguments,
                          number, text, whole)


def peak(*, statistic="R", over="lambda", range=None, target_halfwidth=0.01,  # noqa: A002
         method="auto", seed=1, threads=0, initial_realizations=1000,
         max_realizations=400_000_000, max_events=None, belt_levels=None, belt_rates=None,
         belt_generator=None, **model):
    """Locate the maximizer of the mean of `statistic` over the parameter
    `over` to a 95 % half-width `target_halfwidth`; the interval counts both
    the sampling error and the bias of the local model.

    Model parameters (keyword arguments, numbers; not the one in `over`):
{params}
    statistic: "R" (default), "sticks_per_time", "slips_per_time" or
        "first_stick_duration".
    over: the parameter symbol to maximize over (default "lambda").
    range: (lo, hi), required unless over="lambda" (default (0.1, 100)).
    method: "auto" (default: "score" where it applies, else "common"),
        "score" (the root of dE[R]/dlambda from the causal score derivative
        and the values at 3 points, in groups with common random numbers:
        over="lambda", statistic="R", Poisson switching), "common" (the same
        groups, a cubic fitted to the values at 5 points) or "independent"
        (every point its own streams).
    seed, threads, initial_realizations, max_realizations, max_events: as
        the CLI's flags.

    Returns a dict with the CLI's JSON fields: argmax, argmax_ci95, max,
    max_ci95, realizations, stages, target_met, elapsed_seconds, ...
    Raises stickslip.Error for bad input.
    """
    params = model_arguments(model)
    if model:
        raise unexpected_keywords(peak, model)
    params.update(belt_arguments(belt_levels, belt_rates, belt_generator))
    over = text("over", over)
    if over in params:
        raise error(f"invalid {over}: {params[over]} (allowed: not given: over={over!r} "
                    "sweeps it over range)")
    if range is None:
        if over != "lambda":
            raise error("invalid range: None (allowed: (lo, hi), required unless over='lambda')")
        range = (0.1, 100.0)
    if isinstance(range, (str, bytes)) or not hasattr(range, "__len__") or len(range) != 2:
        raise error(f"invalid range: {range!r} (allowed: (lo, hi) with 0 < lo < hi)")
    lo, hi = number("range lo", range[0]), number("range hi", range[1])
    if not (lo > 0 and hi > lo):
        raise error(f"invalid range: {tuple(range)!r} (allowed: (lo, hi) with 0 < lo < hi)")
    return extension.peak(params, over, text("statistic", statistic), lo, hi,
                           number("target_halfwidth", target_halfwidth), text("method", method),
                           whole("seed", seed), whole("threads", threads, 0, 2**16),
                           whole("initial_realizations", initial_realizations, 2, 2**24),
                           whole("max_realizations", max_realizations, 2,
                                 _stickslip.max_realizations),
                           max_events_of(max_events))


peak.__doc__ = peak.__doc__.format(params=describe())
