"""stickslip.sensitivity(): the CLI's `sensitivity` (docs/uncertainty.md)."""
import json
import os

from . import _stickslip
from ._parameters import (belt_arguments, error, extension, flag, max_events_of, model_arguments,
                          number, text, whole)
from ._parameters import path as _path
from ._sweep import _progress_bar


def sensitivity(*, statistic="R", samples=4096, target_halfwidth=None, max_samples=1_000_000,
                min_samples=1000, seed=1, threads=0, progress=False, block_size=64,
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
        share has a 95% half-width <= this (between min_samples and
        max_samples rows).
    output: a folder: also write sensitivity.nc and summary.json there,
        journaling every finished unit (resume, keep_journal,
        checkpoint_interval and overwrite as for stickslip.sweep).

    Returns a dict: "statistic", "realizations", "samples", "laws", "mean",
    "variance", "intrinsic_variance", "indices" (per input, "of": "mean" with
    first and total order of E[STAT | theta], and "of": "response" with the
    first order in STAT, each with its "_ci95"), "shares" (parameters,
    intrinsic, with their "_ci95") and "elapsed_seconds": the CLI's
    `--format json`. Raises stickslip.Error for bad input.
    """
    params = model_arguments(model, axes=False)
    if model:
        raise TypeError(f"sensitivity() got unexpected keyword arguments: {', '.join(model)}")
    if not any(isinstance(v, str) for v in params.values()):
        raise error("sensitivity: no uncertain input: give at least one model parameter as a "
                    "law, e.g. mu='uniform(2,7)'")
    belt = belt_arguments(belt_levels, belt_rates, belt_generator)
    base = dict(params)
    base.update(belt)
    statistic = text("statistic", statistic)
    if target_halfwidth is not None:
        halfwidth = number("target_halfwidth", target_halfwidth)
        if not 0.0 < halfwidth <= 1.0:
            raise error(f"invalid target_halfwidth: {halfwidth!r} (allowed: 0 < H <= 1)")
        rows = whole("max_samples", max_samples, 1, _stickslip.max_realizations)
        minimum = whole("min_samples", min_samples, 2, _stickslip.max_realizations)
    else:
        halfwidth = 0.0
        rows = whole("samples", samples, 2, _stickslip.max_realizations)
        minimum = 1000
    given = ", ".join(f"{k}={v!r}" for k, v in base.items())
    command = f"python: stickslip.sensitivity({given}, statistic={statistic!r}, samples={rows})"
    out = "" if output is None else _path("output", output)
    update, bar = _progress_bar(flag("progress", progress))
    try:
        result = extension.run_sweep(
            base, [], realizations=rows, seed=whole("seed", seed),
            block_size=whole("block_size", block_size, 1, _stickslip.max_block_size), bins=50,
            records=False, engine="fast", max_events=max_events_of(max_events),
            threads=whole("threads", threads, 0, 2**16), output=out,
            resume=flag("resume", resume), keep_journal=flag("keep_journal", keep_journal),
            checkpoint_interval=number("checkpoint_interval", checkpoint_interval),
            netcdf_path="", command_line=command, progress=update,
            min_realizations=minimum, overwrite=flag("overwrite", overwrite),
            sensitivity_statistic=statistic, target_halfwidth=halfwidth)
    finally:
        if bar is not None:
            bar.close()
    if not result:  # resume=True found this study's finished outputs: read them back
        with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
            data = json.load(f)
        data.pop("run", None)
        return data
    return json.loads(result)
