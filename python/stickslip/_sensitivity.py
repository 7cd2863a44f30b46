"""stickslip.sensitivity(): the CLI's `sensitivity` (docs/uncertainty.md)."""
import json
import os
import warnings

from . import _stickslip
from ._parameters import unexpected_keywords
from ._parameters import (belt_arguments, extension, flag, max_events_of, model_arguments, number,
                          text, whole)
from ._parameters import path as _path
from ._sweep import _progress_bar


def sensitivity(*, statistic="R", samples=None, target_halfwidth=None, max_samples=None,
                min_samples=None, seed=1, threads=0, progress=False, block_size=None,
                max_events=None, output=None, resume=False, keep_journal=False,
                checkpoint_interval=2.0, overwrite=False, belt_levels=None, belt_rates=None,
                belt_generator=None, **model):
    """Sobol' indices of a per-realization statistic over uncertain model
    parameters, exactly as `stickslip sensitivity` computes them (the same
    numbers for the same arguments, for any thread count).

    Model parameters: a number fixes the parameter, a law's text makes it an
    uncertain input (mu="uniform(2,7)", lam="loguniform(0.5,10)",
    k="lognormal(mean=40,cv=0.1)"); at least one must be a law, and there is
    no grid.
    statistic: the per-realization statistic (default "R").
    samples: design rows N (default 4096); each row runs d + 3 realizations.
    target_halfwidth: instead of samples, run rows until every index and
        share has a 95% half-width <= this (between min_samples, default
        1000, and max_samples, default 10**6, rows).
    block_size: rows per work unit (default 64; part of the result's identity).
    output: a folder: also write sensitivity.nc and summary.json there,
        journaling every finished unit (resume, keep_journal,
        checkpoint_interval and overwrite as for stickslip.sweep).

    Returns a dict: "statistic", "realizations", "samples", "laws", "base"
        (the fixed parameters, None for those the laws set), with
        target_halfwidth "target_halfwidth" and "target_met", "warning" when
        there is one (also given as a UserWarning), "mean",
    "variance", "intrinsic_variance", "indices" (per input, "of": "mean" with
    first and total order of E[STAT | theta], and "of": "response" with the
    first order in STAT, each with its "_ci95"), "shares" (parameters,
    intrinsic, with their "_ci95") and "elapsed_seconds": the CLI's
    `--format json`. Raises stickslip.Error for bad input.
    """
    params = model_arguments(model, axes=False)
    if model:
        raise unexpected_keywords(sensitivity, model)
    belt = belt_arguments(belt_levels, belt_rates, belt_generator)
    base = dict(params)
    base.update(belt)

    def rows(name, value):
        return None if value is None else whole(name, value, 2, _stickslip.max_realizations)

    # The rules and defaults are the library's (set_sensitivity_design), so
    # refusals are the CLI's, with these keyword names.
    design = dict(statistic=text("statistic", statistic), samples=rows("samples", samples),
                  max_samples=rows("max_samples", max_samples),
                  min_samples=rows("min_samples", min_samples),
                  block_size=rows("block_size", block_size),
                  target_halfwidth=None if target_halfwidth is None
                  else number("target_halfwidth", target_halfwidth))
    given = ", ".join(f"{k}={v!r}" for k, v in base.items())
    command = f"python: stickslip.sensitivity({given}, {', '.join(f'{k}={v!r}' for k, v in design.items() if v is not None)})"
    out = "" if output is None else _path("output", output)
    update, bar = _progress_bar(flag("progress", progress))
    try:
        result = extension.run_sweep(
            base, [], realizations=1, seed=whole("seed", seed), block_size=1, bins=50,
            records=False, engine="fast", max_events=max_events_of(max_events),
            threads=whole("threads", threads, 0, 2**16), output=out,
            resume=flag("resume", resume), keep_journal=flag("keep_journal", keep_journal),
            checkpoint_interval=number("checkpoint_interval", checkpoint_interval),
            netcdf_path="", command_line=command, progress=update,
            overwrite=flag("overwrite", overwrite), design=design)
    finally:
        if bar is not None:
            bar.close()
    if not result:  # resume=True found this study's finished outputs: read them back
        with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
            data = json.load(f)
        data.pop("run", None)
    else:
        data = json.loads(result)
    if "warning" in data:  # the CLI's warning: undefined indices, or intervals wider than [0, 1]
        warnings.warn(data["warning"], UserWarning, stacklevel=2)
    return data
