"""The model parameters as keyword arguments, named as the command line's
flags: the paper's symbols (--m, --k, --g, --mu, --V, --lambda, --ta), with
`lam` (or `switch_rate`) for lambda, which is a Python keyword; the model
family's scalars (--c, --mu-s, --mu-k), the belt (--belt-levels,
--belt-rates, --belt-generator), and a belt level vI or a rate rI of a
two-level belt by its symbol (as a sweep axis of a TOML config)."""
import re

import numpy as np

# symbol used by the library -> (keyword, default, unit, meaning)
PARAMETERS = {
    "m": ("m", 1.0, "kg", "mass"),
    "k": ("k", 4.0, "N/m", "spring stiffness"),
    "g": ("g", 9.81, "m/s^2", "gravitational acceleration"),
    "mu": ("mu", 5.0, "1", "friction coefficient; sets mu_s and mu_k both"),
    "V": ("V", 1.0, "m/s", "belt speed (the belt runs at +V or -V)"),
    "lambda": ("lam", 1.0, "1/s", "switch rate of the belt direction (Poisson)"),
    "ta": ("ta", 50.0, "s", "observation window t_a"),
    "c": ("c", 0.0, "N s/m", "viscous damping (alias damping)"),
    "mu_s": ("mu_s", "mu", "1", "static friction coefficient, >= mu_k"),
    "mu_k": ("mu_k", "mu", "1", "kinetic friction coefficient"),
}
ALIASES = {"switch_rate": "lam", "lambda_": "lam", "damping": "c"}
BELT = {
    "belt_levels": ("v1,v2,...", "m/s", "belt velocity levels: n >= 2 distinct values, any sign, "
                    "0 allowed (default +V, -V)"),
    "belt_rates": ("r1,r2", "1/s", "two levels: the rates of leaving the first and the second "
                   "level (default lam, lam)"),
    "belt_generator": ("n x n", "1/s", "the belt's generator Q for any number of levels: a nested "
                       "sequence or array, q_ij >= 0 off the diagonal, rows summing to 0"),
}
INDEXED = re.compile(r"^(v[1-9][0-9]*|r[12])$")  # a belt level vI, a two-level rate rI


def model_arguments(kwargs):
    """Pops the scalar model parameters out of `kwargs` (in the order given)
    and returns {symbol: value} with only the given ones."""
    by_keyword = {kw: sym for sym, (kw, *_rest) in PARAMETERS.items()}
    given = {}
    for key in list(kwargs):
        kw = ALIASES.get(key, key)
        if kw in by_keyword or INDEXED.match(kw):
            sym = by_keyword.get(kw, kw)
            if sym in given:
                raise TypeError(f"{key}: {sym} given twice (an alias names the same parameter)")
            given[sym] = kwargs.pop(key)
    return given


def belt_arguments(belt_levels, belt_rates, belt_generator):
    """The belt keywords as the extension takes them: lists of floats, the
    generator as a list of rows (its shape is checked there, with the CLI's
    message)."""
    belt = {}
    if belt_levels is not None:
        belt["belt_levels"] = [float(v) for v in np.asarray(belt_levels, dtype=float).ravel()]
    if belt_rates is not None:
        belt["belt_rates"] = [float(v) for v in np.asarray(belt_rates, dtype=float).ravel()]
    if belt_generator is not None:
        rows = belt_generator.tolist() if isinstance(belt_generator, np.ndarray) else belt_generator
        belt["belt_generator"] = [[float(q) for q in np.ravel(np.asarray(row, dtype=float))]
                                  for row in rows]
    return belt


def belt_start_text(belt_start):
    """belt_start as --belt-start reads it: "stationary", "+1", "-1", "3"."""
    if belt_start is None:
        return None
    if isinstance(belt_start, str):
        return belt_start.strip()
    if isinstance(belt_start, (bool, np.bool_)) or not float(belt_start).is_integer():
        return str(belt_start)
    b = int(belt_start)
    return "+1" if b == 1 else str(b)


def describe():
    """One line per parameter for docstrings."""
    lines = [f"    {kw}: {meaning} [{unit}], default {default}"
             for kw, default, unit, meaning in PARAMETERS.values()]
    lines += [f"    {kw}: {meaning} [{unit}] ({shape})" for kw, (shape, unit, meaning) in BELT.items()]
    lines.append("    v1, v2, ...: one belt level [m/s]; r1, r2: the rate of leaving level 1 / 2 "
                 "of a two-level belt [1/s]")
    return "\n".join(lines)
