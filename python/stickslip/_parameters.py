"""The model parameters as keyword arguments: the paper's symbols, as on the
command line (--m, --k, --g, --mu, --V, --lambda, --ta), with `lam` (or
`switch_rate`) for lambda, which is a Python keyword."""

# symbol used by the library -> (keyword, default, unit, meaning)
PARAMETERS = {
    "m": ("m", 1.0, "kg", "mass"),
    "k": ("k", 4.0, "N/m", "spring stiffness"),
    "g": ("g", 9.81, "m/s^2", "gravitational acceleration"),
    "mu": ("mu", 5.0, "1", "friction coefficient"),
    "V": ("V", 1.0, "m/s", "belt speed (the belt runs at +V or -V)"),
    "lambda": ("lam", 1.0, "1/s", "switch rate of the belt direction (Poisson)"),
    "ta": ("ta", 50.0, "s", "observation window t_a"),
}
ALIASES = {"switch_rate": "lam", "lambda_": "lam"}


def model_arguments(kwargs):
    """Pops the model parameters out of `kwargs` (in the order given) and
    returns {symbol: value} with only the given ones."""
    by_keyword = {kw: sym for sym, (kw, *_rest) in PARAMETERS.items()}
    given = {}
    for key in list(kwargs):
        kw = ALIASES.get(key, key)
        if kw in by_keyword:
            sym = by_keyword[kw]
            if sym in given:
                raise TypeError(f"{key}: lambda given twice (lam and switch_rate are the same parameter)")
            given[sym] = kwargs.pop(key)
    return given


def describe():
    """One line per parameter for docstrings."""
    return "\n".join(f"    {kw}: {meaning} [{unit}], default {default}"
                     for kw, default, unit, meaning in PARAMETERS.values())
