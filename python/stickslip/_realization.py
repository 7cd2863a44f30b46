"""stickslip.simulate(): one realization, exactly as the CLI's `simulate`."""
import numpy as np
import pandas as pd

from ._parameters import unexpected_keywords
from ._parameters import (belt_arguments, belt_start_text, describe, error, extension, flag,
                          max_events_of, model_arguments, number, optional, sequence, whole)

EPISODE_COLUMNS = ["mode", "start", "end", "x_start", "belt_velocity", "censored"]

# The record table (record_schema.hpp): the symbol of each field that has one.
_RECORD_SYMBOLS = {f["symbol"]: f["name"] for f in extension.record_fields() if f["symbol"]}


class Record(dict):
    """A realization's record: {name: value} with the names of records.csv's
    columns (sticks, slips, stick_fraction, first_stick_start,
    first_stick_duration, first_stick_censored, friction_power,
    damping_power, belt_switches, stick_onsets, stick_breaks,
    slip_reversals). A field is read by its symbol too: record["S_T"] is
    record["sticks"], and likewise S_L, R, T_1, D_1, W_f, W_c, N."""

    def __missing__(self, key):
        if key in _RECORD_SYMBOLS:
            return self[_RECORD_SYMBOLS[key]]
        raise KeyError(key)

    def get(self, key, default=None):
        try:
            return self[key]
        except KeyError:
            return default


class Realization:
    """One realization on [0, t_a].

    Attributes:
      episodes    pandas.DataFrame: mode ("stick"/"slip"), start, end [s],
                  x_start [m], belt_velocity [m/s] at the episode's start (a
                  slip can span belt switches: they are the events of kind
                  "belt_switch"), censored (cut off by t_a); the very numbers
                  of `stickslip simulate`'s episodes.csv.
      events      pandas.DataFrame: kind (belt_switch, stick_onset,
                  stick_break, slip_reversal), time [s], x [m], xdot [m/s],
                  belt_velocity [m/s] just after the event.
      record      Record (a dict) keyed by records.csv's column names: sticks,
                  slips, stick_fraction, the first stick (-1 when none), the
                  friction and damping power [W], the event counts; a
                  field's symbol (S_T, S_L, R, ...) reads it too.
      x0, xdot0, belt_start: the initial state used (belt_start: +1 / -1 on
                  two levels, the level number 1..n on more), as the CLI's
                  JSON "initial_conditions".
      parameters  dict of the resolved model, as the CLI's JSON "parameters":
                  m, k, g, mu, V, lambda, ta, c, mu_s, mu_k, belt_levels,
                  belt_generator (rows) and, for two levels, belt_rates; with
                  laws, the model at the drawn values.
      laws, drawn dicts {symbol: ...} of the uncertain parameters: each law's
                  canonical text, and the value this realization drew from
                  it (the CLI's JSON "laws" and "drawn"); empty without laws.
    """

    def __init__(self, seed, realization, raw):
        self.parameters = dict(raw["parameters"])
        self.seed = seed
        self.realization = realization
        self.x0, self.xdot0, self.belt_start = raw["x0"], raw["xdot0"], raw["belt_start"]
        self.record = Record(raw["record"])
        self.laws, self.drawn = dict(raw["laws"]), dict(raw["drawn"])
        self.episodes = pd.DataFrame(raw["episodes"], columns=EPISODE_COLUMNS)
        self.events = pd.DataFrame(raw["events"], columns=["kind", "time", "x", "xdot", "belt_velocity"])
        self._segments = raw["segments"]  # the library's segments, whole (every field)

    def __repr__(self):
        r = self.record
        return (f"<stickslip.Realization seed={self.seed} realization={self.realization}: "
                f"{r['sticks']} sticks, R = {r['stick_fraction']:.6g}, {len(self.episodes)} episodes>")

    def trajectory(self, dt):
        """x, x' and v sampled every `dt` seconds and at every event instant:
        a pandas.DataFrame with columns t [s], x [m], xdot [m/s], v [m/s],
        evaluated from the exact closed form of each piece of motion."""
        dt = number("dt", dt)
        if not dt > 0:
            raise error(f"invalid dt: {dt} (allowed: a finite number > 0 s)")
        rows = extension.sample_trajectory(self._segments, dt)
        return pd.DataFrame(rows, columns=["t", "x", "xdot", "v"])

    def plot(self, dt=0.01, ax=None):
        """x, x' and the belt velocity against time, with sticks shaded
        (matplotlib); the legend sits below the axes, off the trace. Returns
        the Axes."""
        import matplotlib.pyplot as plt
        own_figure = ax is None
        if own_figure:
            _, ax = plt.subplots(figsize=(9, 4))
        tr = self.trajectory(dt)
        ax.plot(tr.t, tr.x, label="x [m]")
        ax.plot(tr.t, tr.xdot, label="x' [m/s]")
        ax.step(tr.t, tr.v, where="post", label="v [m/s]", color="0.4")
        for e in self.episodes.itertuples():
            if e.mode == "stick":
                ax.axvspan(e.start, e.end, color="tab:green", alpha=0.15, lw=0)
        ax.set_xlabel("t [s]")
        # Below the axes, outside the data: the legend never covers the trace.
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=3, frameon=False)
        ax.set_title(f"seed {self.seed}, realization {self.realization} (sticks shaded)")
        if own_figure:
            ax.figure.tight_layout()  # room for the legend below and the title above
        return ax


def simulate(*, seed=1, realization=None, x0=None, xdot0=None, belt_start=None, switch_times=None,
             switch_levels=None, belt_levels=None, belt_rates=None, belt_generator=None,
             max_events=None, common_random_numbers=False, burn_in=0.0, **model):
    """One realization of the stick-slip oscillator, exactly as
    `stickslip simulate` computes it: realization `realization` of the sweep
    point with these parameters and `seed`, unless x0, xdot0, belt_start or
    switch_times fix those inputs.

    Model parameters (keyword arguments, any subset):
{params}
    seed: master seed (default 1); realization: index of the realization
        (default 0; required when a parameter is a law).
    A parameter may be a law's text, e.g. mu="gamma(mean=5,cv=0.2)": the
        realization is then realization `realization` of the sweep point
        with that law, its values drawn as the sweep draws them (returned in
        .drawn); x0, xdot0 and switch_times cannot be fixed then, and
        belt_start is the sweep's (the law of the starting level).
    x0: initial position [m]; xdot0: initial velocity [m/s]; default: drawn
        from U[-1, 1] as in the sweep.
    belt_start: the level at t = 0, an int: +1 or -1 (first / second of two
        levels, v(0) = +V or -V) or a level number 1..n; or the text
        "stationary" (default: drawn from the belt's stationary law, equal
        odds for the paper's belt). A float (1.0) or other text ("1") is
        refused, as `--belt-start 1.0` is.
    switch_times: belt switch times [s], sorted, >= 0, replacing the random
        switches (then lam, belt_rates and the generator play no role).
    switch_levels: with switch_times, the level number (1..n) each switch
        goes to, as the lines 't level' of --switch-times-file; needed for
        more than two levels (default: two levels alternate).
    max_events: bound on the events of the realization (default 1e8).
    common_random_numbers: replay realization `realization` of a sweep run
        with common_random_numbers=True (the streams every point shares).
    burn_in: T [s], 0 <= T < t_a: .record counts only [T, t_a] (S_T, S_L,
        R over t_a - T, the first stick from T), as a sweep with
        burn_in=T records realization `realization`; the episodes are the
        whole window either way (default 0).

    Returns a Realization. Raises stickslip.Error for bad input.
    """
    arguments = _replay_arguments("simulate", model, seed, x0, xdot0, belt_start, switch_times,
                                  switch_levels, belt_levels, belt_rates, belt_generator,
                                  max_events, common_random_numbers)
    realization = optional(whole, "realization", realization)
    raw = extension.replay(**arguments, realization=realization,
                           burn_in=number("burn_in", burn_in))
    return Realization(arguments["seed"], realization or 0, raw)


def _replay_arguments(function, model, seed, x0, xdot0, belt_start, switch_times, switch_levels,
                      belt_levels, belt_rates, belt_generator, max_events, common_random_numbers):
    """The arguments of one replay, read through the one coercion
    (_parameters.py), shared by simulate() and simulate_many()."""
    params = model_arguments(model, stacklevel=4)  # the user's call is two frames up
    if model:
        raise unexpected_keywords(globals()[function], model)
    params.update(belt_arguments(belt_levels, belt_rates, belt_generator))
    return dict(parameters=params, seed=whole("seed", seed), x0=optional(number, "x0", x0),
                xdot0=optional(number, "xdot0", xdot0), belt_start=belt_start_text(belt_start),
                switch_times=optional(sequence, "switch_times", switch_times,
                                      "a sequence of switch times [s]"),
                switch_levels=optional(sequence, "switch_levels", switch_levels,
                                       "a sequence of level numbers 1..n", _level),
                max_events=max_events_of(max_events),
                common_random_numbers=flag("common_random_numbers", common_random_numbers))


def _level(name, value):
    return whole(name, value, 1, 2**31 - 1)


simulate.__doc__ = simulate.__doc__.format(params=describe())


def simulate_many(*, realizations, seed=1, threads=0, x0=None, xdot0=None, belt_start=None,
                  switch_times=None, switch_levels=None, belt_levels=None, belt_rates=None,
                  belt_generator=None, max_events=None, common_random_numbers=False, **model):
    """Many realizations of one model at once: the episodes of
    simulate(realization=r, ...) for every r in `realizations` (a range or a
    sequence of whole numbers, in any order), computed on `threads` worker
    threads (0 = all cores) with the GIL released.

    Every other argument is simulate()'s. Each realization is computed alone,
    exactly as simulate() computes it, so the result is bit for bit the
    single calls' and does not depend on `threads`.

    Returns one pandas.DataFrame: realization, then the columns of
    Realization.episodes (mode, start, end, x_start, belt_velocity,
    censored), realizations in the order given. Raises stickslip.Error for
    bad input; Ctrl-C starts no further realization (KeyboardInterrupt).
    """
    arguments = _replay_arguments("simulate_many", model, seed, x0, xdot0, belt_start,
                                  switch_times, switch_levels, belt_levels, belt_rates,
                                  belt_generator, max_events, common_random_numbers)
    indices = sequence("realizations", realizations, "a range or sequence of realization indices",
                       whole)
    rows = extension.replay_many(**arguments, realizations=indices,
                                  threads=whole("threads", threads, 0, 2**16))
    frame = pd.DataFrame(rows, columns=["realization", *EPISODE_COLUMNS])
    frame["realization"] = frame["realization"].astype(np.uint64)  # indices reach 2^64 - 1
    return frame
