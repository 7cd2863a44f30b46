"""stickslip.sweep() and stickslip.open(): the CLI's `sweep`, as xarray."""
import inspect
import os
import tempfile

import xarray as xr

from . import _stickslip
from ._parameters import unexpected_keywords
from ._parameters import (PARAMETERS, belt_arguments, belt_start_text, describe, error, extension,
                          flag, max_events_of, model_arguments, number, sequence, text, whole)
from ._parameters import path as _path  # `path` is open()'s argument


def _axes_and_base(params):
    """Fixed parameters and axes (in the order given; the extension puts
    lambda and mu first, as the CLI does)."""
    base, axes = {}, []
    for sym, value in params.items():
        if isinstance(value, list):
            axes.append((sym, value))
        else:
            base[sym] = value
    return base, axes


def _python_names(ds):
    """The Dataset as Python shows it: a dimension whose symbol is a Python
    keyword is named by the parameter's keyword (lambda: `lam`, since
    ds.sel(lambda=...) cannot be written), with the symbol kept as a
    coordinate along it; nothing else differs from results.nc."""
    for sym, (kw, *_rest) in PARAMETERS.items():
        if kw == sym or sym not in ds.dims or kw in ds.variables:
            continue
        coord = ds[sym]
        ds = ds.assign_coords({kw: (sym, coord.values, dict(coord.attrs))}).swap_dims({sym: kw})
    return ds


def _statistics_names(statistics):
    """statistics=: None, a name or a list of names (checked by the library,
    with the CLI's message)."""
    if statistics is None:
        return []
    names = [statistics] if isinstance(statistics, str) else statistics
    try:
        names = list(names)
    except TypeError:
        raise error(f"invalid statistics: {statistics!r} (allowed: a list of group names: "
                    f"default, survival, all)") from None
    return [text("statistics", n) for n in names]


def _observe_times(times):
    """observe_times=: None, a grid's text (the CLI's --observe-times, e.g.
    "lin:0:50:501") or a 1-D sequence of times; the extension reads either
    with the CLI's parser (its checks and messages)."""
    if times is None or isinstance(times, str):
        return times
    return sequence("observe_times", times, "a grid's text such as 'lin:0:50:501' or a 1-D "
                    "sequence of finite times")


def _progress_bar(enabled):
    if not enabled:
        return None, None
    from tqdm.auto import tqdm
    bar = tqdm(total=1, unit="unit", desc="stickslip sweep")

    def update(done, total):
        if bar.total != total:
            bar.total = total
        bar.n = done
        bar.refresh()
    return update, bar


def open(path):  # noqa: A001 (stickslip.open, like xarray.open_dataset)
    """Reads a results.nc written by `stickslip sweep` (or by sweep(output=...))
    into memory as an xarray.Dataset; `path` (a str or an os.PathLike) may be
    the file or its folder.
    The lambda dimension is named `lam` (ds.sel(lam=3.8)), with the
    coordinate `lambda` along it. Anything else (a truncated file, a
    summary.json) raises stickslip.Error (exit_code 2)."""
    path = _path("path", path)
    if os.path.isdir(path):
        path = os.path.join(path, "results.nc")
    if not os.path.exists(path):
        raise error(f"{path} does not exist (expected a results.nc or a folder holding one)")
    try:
        with xr.open_dataset(path) as ds:
            ds = ds.load()
    except Exception as e:  # noqa: BLE001 (netCDF, HDF5 and xarray raise many kinds)
        reason = " ".join(str(e).split()) or type(e).__name__
        raise error(f"invalid results file: '{path}' (allowed: a results.nc written by stickslip "
                    f"sweep or stickslip.sweep(output=...); reading it failed: {reason})") from e
    return _python_names(ds)


def sweep(*, realizations=2000, seed=1, threads=0, progress=False, block_size=50, bins=50,
          records=False, engine="fast", max_events=None, output=None, resume=False,
          keep_journal=False, checkpoint_interval=2.0, belt_levels=None, belt_rates=None,
          belt_generator=None, belt_start=None, common_random_numbers=False, target_ci=None,
          min_realizations=1000, overwrite=False, statistics=None, survival_bins=None, burn_in=0.0,
          observe_times=None, **model):
    """The paper's statistics over a grid of model parameters, exactly as
    `stickslip sweep` computes them (bit-identical for any thread count).

    Model parameters: a number fixes the parameter; a list or array of a
    scalar parameter (m, k, g, mu, V, lam, ta, c, mu_s, mu_k, v1..vN, r1, r2)
    makes it a dimension of the grid (e.g. lam=np.geomspace(0.1, 30, 40),
    mu=[0.5, 5]), and so does the CLI's grid text (lam="log:0.1:30:40",
    mu="0.5,5": the CLI's values, bit for bit; np.geomspace's differ in last
    bits, and so do the results); the CLI's axis order: lambda first, then mu, then the
    others in the order the keywords are given; a law's text makes it
    uncertain (mu="gamma(mean=5,cv=0.2)", lam="loguniform(0.5,10)": each
    realization draws its own value, docs/uncertainty.md), and laws combine
    with axes (each point's statistics are then over the mixture); belt_levels,
    belt_rates and belt_generator describe the belt of every point.
{params}
    belt_start: the initial level of every realization: the text
        "stationary" (default: drawn from the belt's stationary law) or an
        int, +1 / -1 (first / second of two levels) or a level number 1..n.
    realizations: realizations per grid point (default 2000).
    seed: master seed (default 1). threads: worker threads, 0 = all cores.
    progress: show a tqdm progress bar.
    block_size: realizations per work unit (default 50; part of the result's
        identity). bins: histogram bins (default 50).
    records: keep per-realization records (records.csv with output=).
    engine: "fast" (default) or "reference"; the results are identical.
    max_events: bound on the events of one realization (default 1e8).
    output: a folder (a str or an os.PathLike such as pathlib.Path): also
        write results.nc, summary.json, summary.csv
        (records.csv) there, journaling every finished unit. Finished
        results already there are never replaced unless overwrite=True
        (stickslip.Error, exit_code 2, as `stickslip sweep -o`).
    overwrite: with output, replace the results of an earlier run; its
        outputs that this run does not write (records.csv without
        records=True, a study's files) are removed, and a UserWarning
        names them.
    resume: with output, continue an interrupted sweep from its journal; with
        no journal, the folder's finished results must be this
        configuration's (then they are read back untouched), else refused.
    keep_journal: with output, keep the journal after the outputs are written.
    checkpoint_interval: with output, seconds between journal segments
        (default 2; 0 = after every unit).
    common_random_numbers: realization r of every grid point uses the same
        random numbers (smooth curves, low-variance differences; points are
        then correlated; docs/precision.md).
    target_ci: "STAT:HALFWIDTH" (e.g. "R:0.002"): each point runs until the
        95% half-width of the mean of STAT meets it; `realizations` is then
        the cap per point, min_realizations (default 1000) the minimum.
    statistics: the groups of statistics, a list of names (or one name):
        "default" (always on), "survival" (Kaplan-Meier survival of the stick
        and slip durations with censoring at t_a: stick_survival,
        stick_survival_ci95_low/high, stick_at_risk, stick_restricted_mean
        over stick_duration, slip_* over slip_duration), "all"; the CLI's
        --statistics (docs/outputs.md).
    survival_bins: bins of the survival grid (default None: 200; the CLI's
        --survival-bins), only with the survival statistics.
    burn_in: T in seconds, 0 <= T < t_a (default 0: the whole window): every
        statistic counts only [T, t_a] (R, the rates and the level fractions
        over t_a - T; an episode in progress at T counts from T); the CLI's
        --burn-in (docs/outputs.md, "Burn-in"). Recorded as the attribute
        burn_in (absent without a burn-in).
    observe_times: the times t [s] at which the ensemble's state is kept,
        ascending, 0 <= t <= t_a: a grid's text ("lin:0:50:501", "0,10,20")
        or a sequence of numbers (default None: none); the CLI's
        --observe-times (docs/outputs.md, "Observe times"). The Dataset then
        has a coordinate `time` and, over (grid, time): stick_probability,
        stick_probability_std_error, X_mean, X_variance, X_ci95_half_width
        for X = position, velocity, relative_velocity, energy; over (grid,
        time, belt_level): level_occupancy; over (grid, time, quantile):
        position_quantile and velocity_quantile.

    Returns an xarray.Dataset with the variables, coordinates and attributes of
    the results.nc the CLI writes for the same arguments; the lambda dimension
    is named `lam` (ds.sel(lam=3.8)), with the coordinate `lambda` along it.
    Ctrl-C stops within a second (KeyboardInterrupt); with output the
    journal stays resumable.
    Raises stickslip.Error for bad input.
    """
    options = {k: v for k, v in locals().items() if k != "model"}  # the call, for its record
    params = model_arguments(model, axes=True)
    if model:
        raise unexpected_keywords(sweep, model)
    base, axes = _axes_and_base(params)
    belt = belt_arguments(belt_levels, belt_rates, belt_generator)
    realizations = whole("realizations", realizations, 1, _stickslip.max_realizations)
    seed = whole("seed", seed)
    base.update(belt)
    arguments = dict(
        realizations=realizations, seed=seed,
        block_size=whole("block_size", block_size, 1, _stickslip.max_block_size),
        bins=whole("bins", bins, 1, _stickslip.max_histogram_bins),
        records=flag("records", records), engine=text("engine", engine),
        max_events=max_events_of(max_events), threads=whole("threads", threads, 0, 2**16),
        output="" if output is None else _path("output", output),
        resume=flag("resume", resume), keep_journal=flag("keep_journal", keep_journal),
        checkpoint_interval=number("checkpoint_interval", checkpoint_interval),
        belt_start=belt_start_text(belt_start),
        common_random_numbers=flag("common_random_numbers", common_random_numbers),
        target_ci="" if target_ci is None else text("target_ci", target_ci),
        min_realizations=whole("min_realizations", min_realizations, 2,
                               _stickslip.max_realizations),
        overwrite=flag("overwrite", overwrite),
        statistics=_statistics_names(statistics),
        survival_bins=(None if survival_bins is None else
                       whole("survival_bins", survival_bins, 1, _stickslip.max_histogram_bins)),
        burn_in=number("burn_in", burn_in), observe_times=_observe_times(observe_times))
    command = _call_text(params, belt, options, arguments)
    update, bar = _progress_bar(flag("progress", progress))
    try:
        with tempfile.TemporaryDirectory(prefix="stickslip-") as tmp:
            nc = os.path.join(tmp, "results.nc")
            extension.run_sweep(base, axes, netcdf_path=nc, command_line=command, progress=update,
                                 **arguments)
            return open(arguments["output"] or nc)
    finally:
        if bar is not None:
            bar.close()


def _call_text(params, belt, options, arguments):
    """The call as its record (results.nc's command_line and history): the
    model and belt keywords given, realizations and seed, then every other
    keyword whose value is not its default (observe_times, statistics,
    records, output, ...), so that the record replays the run. Each value
    as it was read (`arguments`: plain ints, floats, lists and str, a path
    as its text), else as given."""
    defaults = {k: p.default for k, p in inspect.signature(sweep).parameters.items()
                if p.default is not inspect.Parameter.empty}
    keyword = {sym: kw for sym, (kw, *_rest) in PARAMETERS.items()}  # lambda -> lam
    given = [f"{keyword.get(k, k)}={v!r}" for k, v in {**params, **belt}.items()]
    given += [f"{k}={arguments[k]!r}" for k in ("realizations", "seed")]
    for k, v in options.items():
        if k in defaults and k not in ("realizations", "seed") and k not in belt:
            default = defaults[k]
            if v is not default and not (type(v) is type(default) and v == default):
                read = arguments[k] if k in arguments and k != "belt_start" else v
                given.append(f"{k}={_literal(read)}")
    return f"python: stickslip.sweep({', '.join(given)})"


def _literal(value):
    """A keyword's value as Python text: arrays and numpy scalars as lists
    and numbers."""
    if hasattr(value, "tolist") and not isinstance(value, (str, bytes)):
        value = value.tolist()
    return repr(value)


sweep.__doc__ = sweep.__doc__.format(params=describe())
