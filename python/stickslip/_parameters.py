"""The model parameters as keyword arguments, named as the command line's
flags: the paper's symbols (--m, --k, --g, --mu, --V, --lambda, --ta), with
`lam` for lambda, which is a Python keyword (or `lambda_`, PEP 8's
spelling); each also under its long name, as the command line's alias
flag (stiffness for k, switch_rate for lam, damping for c); the model
family's scalars (--c, --mu-s, --mu-k), the belt (--belt-levels,
--belt-rates, --belt-generator), and a belt level vI or a rate rI of a
two-level belt by its symbol (as a sweep axis of a TOML config)."""
import functools
import keyword
import numbers
import os
import re
import warnings

import numpy as np

from . import _stickslip

# symbol used by the library -> (keyword, default, unit, meaning): the rows
# of the library's parameter table (parameters.hpp, scalar_parameters),
# whose `keyword` is the symbol, or its spelling where the symbol is one of
# Python's keywords (lambda: lam).
_TABLE = _stickslip.parameter_table()
PARAMETERS = {
    row["symbol"]: (row["keyword"], "mu" if row["unset_means_mu"] else row["default"],
                    row["units"], row["description"])
    for row in _TABLE
}
# alias -> keyword, from the same rows: each long name, as the command line's
# alias flag (--switch-rate: switch_rate), and PEP 8's spelling of a symbol
# that is a Python keyword (lambda_).
ALIASES = {
    **{row["long_name"].replace("-", "_"): row["keyword"] for row in _TABLE},
    **{row["symbol"] + "_": row["keyword"] for row in _TABLE if keyword.iskeyword(row["symbol"])},
}
BELT = {
    "belt_levels": ("v1,v2,...", "m/s", "belt velocity levels: n >= 2 distinct values, any sign, "
                    "0 allowed (default +V, -V)"),
    "belt_rates": ("r1,r2", "1/s", "two levels: the rates of leaving the first and the second "
                   "level (default lam, lam)"),
    "belt_generator": ("n x n", "1/s", "the belt's generator Q for any number of levels: a nested "
                       "sequence or array, q_ij >= 0 off the diagonal, rows summing to 0"),
}
INDEXED = re.compile(r"^(v[1-9][0-9]*|r[12])$")  # a belt level vI, a two-level rate rI


# ---------------------------------------------------------------------------
# The one coercion of arguments: every public function reads its
# numbers, whole numbers, sequences and flags through these, so that every
# refusal is a stickslip.Error (a ValueError) with exit_code 2 whose message
# names the parameter, the value and what is allowed, as the CLI's do:
#   a number        int, float or a numpy number (or a 0-d array of one),
#                   finite; never a bool, never text
#   a whole number  int or a numpy integer (or a 0-d integer array) in the
#                   CLI's range; a float is refused even when integral (the
#                   CLI refuses "2.0" too): no value is ever truncated. The
#                   range check and its message are the CLI's own parser's
#                   (io::parse_unsigned through the extension).
#   a sequence      a list, tuple, range or 1-D array (Series, DataArray) of
#                   numbers; text and arrays of 2 or more dimensions are refused,
#                   never flattened
#   a flag          True or False (numpy's bool too)
#   text            a str; a path (output=, open()) is a str or an os.PathLike
#   a belt start    an int level or the text "stationary" (belt_start_text)
# ---------------------------------------------------------------------------
UINT64_MAX = 2**64 - 1
INT64_MAX = 2**63 - 1


def error(message):
    """A stickslip.Error for bad input: exit_code 2, as the CLI's."""
    e = _stickslip.Error(message)
    e.exit_code = 2
    return e


def _kind(value):
    """"an int", "a float", ...: the type of a refused value, with its article."""
    name = type(value).__name__
    return ("an " if name[:1].lower() in "aeiou" else "a ") + name


def _is_bool(value):
    return isinstance(value, (bool, np.bool_)) or (
        isinstance(value, np.ndarray) and value.dtype == np.bool_)


def _is_array(value):
    return isinstance(value, np.ndarray) or (hasattr(value, "ndim") and hasattr(value, "shape")
                                             and hasattr(value, "__array__"))


def number(name, value):
    """One finite number, as a float."""
    allowed = "a finite number"
    if _is_array(value) and np.ndim(value) == 0 and not _is_bool(value):
        value = np.asarray(value).item()
    if isinstance(value, (str, bytes)):
        raise error(f"invalid {name}: {value!r} (allowed: {allowed}; got text, not a number)")
    if _is_bool(value):
        raise error(f"invalid {name}: {value} (allowed: {allowed}; a bool is not a number)")
    if not isinstance(value, numbers.Real):
        raise error(f"invalid {name}: {value!r} (allowed: {allowed}; got {_kind(value)})")
    x = float(value)
    if not np.isfinite(x):
        raise error(f"invalid {name}: {x} (allowed: {allowed})")
    return x


def whole(name, value, lo=0, hi=UINT64_MAX):
    """One whole number in [lo, hi], read by the CLI's parser of whole numbers
    (its rule, its message "invalid NAME: 'V' (allowed: a whole number from lo
    to hi)")."""
    if _is_array(value) and np.ndim(value) == 0 and np.asarray(value).dtype.kind in "iu":
        value = np.asarray(value).item()
    if isinstance(value, (numbers.Integral, np.integer)) and not _is_bool(value):
        text = str(int(value))
    elif isinstance(value, (str, bytes)):
        text = repr(value)  # quoted: text is never a number here
    else:
        text = str(value)   # a float, a bool, ...: never a whole number's text
    return extension.parse_unsigned(name, text, lo, hi)


def flag(name, value):
    """True or False."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise error(f"invalid {name}: {value!r} (allowed: True or False)")


def text(name, value):
    """A str."""
    if isinstance(value, str):
        return value
    raise error(f"invalid {name}: {value!r} (allowed: text (a str); got {_kind(value)})")


def path(name, value):
    """The name of a file or folder: a str or an os.PathLike (pathlib.Path),
    not empty, as a str."""
    allowed = "a path: a str or an os.PathLike such as pathlib.Path"
    if isinstance(value, str) or (isinstance(value, os.PathLike) and not isinstance(value, bytes)):
        p = os.fspath(value)
        if isinstance(p, str) and p:
            return p
        raise error(f"invalid {name}: {value!r} (allowed: {allowed}, not empty)")
    raise error(f"invalid {name}: {value!r} (allowed: {allowed}; got {_kind(value)})")


def _is_sequence(value):
    if isinstance(value, (str, bytes)):
        return False
    if isinstance(value, (list, tuple, range)):
        return True
    return _is_array(value) and np.ndim(value) > 0


def sequence(name, value, allowed="a sequence of finite numbers", item=number):
    """A 1-D sequence of numbers (or of whole numbers with item=whole), as a
    list; entry i is named "NAME entry #i" in a message."""
    if isinstance(value, (str, bytes)):
        raise error(f"invalid {name}: {value!r} (allowed: {allowed}; got text)")
    if not _is_sequence(value):
        raise error(f"invalid {name}: {value!r} (allowed: {allowed})")
    if _is_array(value):
        if np.ndim(value) != 1:
            raise error(f"invalid {name}: an array of {np.ndim(value)} dimensions, shape "
                        f"{tuple(np.shape(value))} (allowed: {allowed}, 1-D: it is never "
                        "flattened)")
        value = np.asarray(value).tolist()
    return [item(f"{name} entry #{i}", v) for i, v in enumerate(value, start=1)]


def number_or_axis(name, value):
    """A sweep's model parameter: a number fixes it, a 1-D sequence makes an
    axis (a float or a list of floats)."""
    if _is_sequence(value):
        return sequence(name, value, "a number or a 1-D sequence of finite numbers")
    return number(name, value)


def is_law(value):
    """Whether a keyword's value is a law's text ("gamma(mean=5,cv=0.2)"), told
    apart as the CLI tells a flag's: the extension parses it (parse_law), so
    its refusals are the CLI's messages."""
    return isinstance(value, str) and _stickslip.looks_like_law(value)


def model_arguments(kwargs, axes=False, stacklevel=3):
    """Pops the scalar model parameters out of `kwargs` (in the order given)
    and returns {symbol: value} with only the given ones: numbers, or with
    axes=True a number or a list of numbers (number_or_axis), each read under
    the keyword the caller used; any of them may be a law's text (is_law),
    kept as a str. mu beside both mu_s and mu_k sets neither and only changes
    the draws: a UserWarning, as the CLI warns of --mu beside --mu-s and
    --mu-k, at `stacklevel` (that of the user's call: 3 when the public
    function calls this directly)."""
    by_keyword = {kw: sym for sym, (kw, *_rest) in PARAMETERS.items()}
    given = {}
    for key in list(kwargs):
        kw = ALIASES.get(key, key)
        if kw in by_keyword or INDEXED.match(kw):
            sym = by_keyword.get(kw, kw)
            if sym in given:
                raise TypeError(f"{key}: {sym} given twice (an alias names the same parameter)")
            value = kwargs.pop(key)
            if is_law(value):
                given[sym] = value
            elif axes and isinstance(value, str) and (":" in value or "," in value):
                # the CLI's grid text ("log:0.1:30:40", "0.5,3,7"): its values, bit for bit
                given[sym] = _stickslip.parse_axis(key, sym, value)
            elif isinstance(value, str):
                forms = ("a number, a 1-D sequence of finite numbers or a grid's text such as "
                         "'log:0.1:30:40'") if axes else "a finite number"
                raise error(f"invalid {key}: {value!r} (allowed: {forms}, or a law's text such as "
                            "'gamma(mean=5,cv=0.2)'; got text that is neither)")
            elif not axes and (isinstance(value, (list, tuple)) or
                               (_is_array(value) and np.ndim(value) > 0)):
                # a grid where one value or a law is taken (a new user's
                # lam=[1, 2] in sensitivity was told only "a finite number")
                raise error(f"invalid {key}: {value!r} (allowed: a finite number, or a law's "
                            "text such as 'uniform(0.5,10)'; got a sequence: a grid of values "
                            "is stickslip.sweep's)")
            else:
                given[sym] = number_or_axis(key, value) if axes else number(key, value)
    note = _stickslip.only_in_the_stream_key(given)
    if note:  # the CLI's warning, in keywords; stacklevel: the caller of the public function
        warnings.warn(python_message(note), UserWarning, stacklevel=stacklevel)
    return given


def unexpected_keywords(function, leftover):
    """The TypeError for keywords that `function` (a public function) does
    not take, each with the nearest keyword it does take, as the command
    line suggests the nearest flag."""
    import inspect
    known = [kw for kw, *_rest in PARAMETERS.values()]
    known += [name for name in inspect.signature(function).parameters if name != "model"]
    words = []
    for key in leftover:  # the keywords first, then their long aliases; the CLI's rule
        near = (_stickslip.nearest_name(key, known) or
                _stickslip.nearest_name(key, list(ALIASES)))
        words.append(f"{key} (did you mean {near}?)" if near else key)
    return TypeError(f"{function.__name__}() got unexpected keyword arguments: {', '.join(words)}")


def belt_arguments(belt_levels, belt_rates, belt_generator):
    """The belt keywords as the extension takes them: lists of floats, the
    generator as a list of rows (its shape is checked there, with the CLI's
    message)."""
    belt = {}
    if belt_levels is not None:
        belt["belt_levels"] = sequence("belt_levels", belt_levels)
    if belt_rates is not None:
        belt["belt_rates"] = sequence("belt_rates", belt_rates)
    if belt_generator is not None:
        allowed = "an n x n nested sequence or array of rates"
        if isinstance(belt_generator, (str, bytes)) or not _is_sequence(belt_generator):
            raise error(f"invalid belt_generator: {belt_generator!r} (allowed: {allowed})")
        rows = (np.asarray(belt_generator).tolist() if _is_array(belt_generator)
                else list(belt_generator))
        belt["belt_generator"] = [sequence(f"belt_generator row {i}", row, allowed)
                                  for i, row in enumerate(rows, start=1)]
    return belt


def optional(read, name, value, *args):
    """read(name, value, *args), or None for None."""
    return None if value is None else read(name, value, *args)


def max_events_of(value):
    """max_events: None for the default (1e8), else 1 .. 2^63 - 1 (the CLI's --max-events)."""
    if value is None:
        return _stickslip.default_max_events
    return whole("max_events", value, 1, INT64_MAX)


def belt_start_text(belt_start):
    """belt_start as --belt-start reads it. Allowed: an int level (+1 / -1
    on two levels, a level number 1..n on more; int or numpy integer) or the
    text "stationary". Anything else is handed to the CLI's parser as text it
    refuses, so that the refusal is the CLI's message with the levels of this
    belt: a float as its digits ("2.0": the CLI refuses --belt-start 2.0 too,
    no value is truncated), other text quoted ("'1'": text is never a level),
    a bool as "True"."""
    if belt_start is None:
        return None
    if _is_array(belt_start) and np.ndim(belt_start) == 0 and np.asarray(belt_start).dtype.kind in "iu":
        belt_start = np.asarray(belt_start).item()
    if isinstance(belt_start, str) and belt_start == "stationary":
        return belt_start
    if isinstance(belt_start, (numbers.Integral, np.integer)) and not _is_bool(belt_start):
        b = int(belt_start)
        return "+1" if b == 1 else str(b)
    if isinstance(belt_start, (float, np.floating)) or _is_bool(belt_start):
        return str(belt_start)
    return repr(belt_start)


def describe():
    """One line per parameter for docstrings."""
    lines = [f"    {kw}: {meaning} [{unit}], default {default}"
             for kw, default, unit, meaning in PARAMETERS.values()]
    aliases = ", ".join(f"{alias} for {kw}" for alias, kw in ALIASES.items())
    lines.append(f"    (aliases: {aliases})")
    lines += [f"    {kw}: {meaning} [{unit}] ({shape})" for kw, (shape, unit, meaning) in BELT.items()]
    lines.append("    v1, v2, ...: one belt level [m/s]; r1, r2: the rate of leaving level 1 / 2 "
                 "of a two-level belt [1/s]")
    return "\n".join(lines)


# ---------------------------------------------------------------------------
# The extension's messages are the command line's, which name its flags
# (--belt-start, -o, --resume); a Python user passes keywords. One mapping,
# flag -> keyword, rewrites every stickslip.Error the extension raises
# (`extension` below), so that C++ messages stay the CLI's.
# ---------------------------------------------------------------------------
KEYWORD_OF_FLAG = {
    **{"--" + sym.replace("_", "-"): kw for sym, (kw, *_rest) in PARAMETERS.items()},  # --lambda: lam
    **{"--" + kw.replace("_", "-"): kw for kw in BELT},
    "--belt-start": "belt_start", "--switch-times": "switch_times",
    "--max-events": "max_events", "--target-ci": "target_ci",
    "--realization": "realization", "--x0": "x0", "--xdot0": "xdot0",
    "-o": "output", "--resume": "resume=True", "--overwrite": "overwrite=True",
    "--records": "records=True", "--keep-journal": "keep_journal=True",
    "--common-random-numbers": "common_random_numbers=True",
    "--statistic": "statistic", "--samples": "samples", "--target-halfwidth": "target_halfwidth",
    "--max-samples": "max_samples", "--min-samples": "min_samples", "--block-size": "block_size",
}
# Phrases around a flag that read wrong with a keyword, first.
PHRASES = [
    ("-o (output directory)", "output"),
    ("choose another -o DIR", "choose another output folder"),
    ("add --resume", "pass --resume"),
    ("add --overwrite", "pass --overwrite"),
    ("vs this command", "vs this call"),
    ("the same command and", "the same call and"),
    (" (--belt-generator, or belt_generator in TOML [model])", " (belt_generator)"),
]
FLAG = re.compile(r"(?<![\w-])(--[A-Za-z][\w-]*|-o)(?![\w-])")


def python_message(message):
    """A message of the command line's with the Python keywords in place of
    its flags ("--belt-start" -> "belt_start", "--resume" -> "resume=True")."""
    for cli, python in PHRASES:
        message = message.replace(cli, python)
    return FLAG.sub(lambda m: KEYWORD_OF_FLAG.get(m.group(0), m.group(0)), message)


class _Extension:
    """The compiled module (_stickslip), whose functions raise
    stickslip.Error with python_message's wording and the same exit_code."""

    def __getattr__(self, name):
        value = getattr(_stickslip, name)
        if not callable(value) or isinstance(value, type):
            return value

        @functools.wraps(value)
        def call(*args, **kwargs):
            try:
                return value(*args, **kwargs)
            except _stickslip.Error as e:
                python = _stickslip.Error(python_message(str(e)))
                python.exit_code = getattr(e, "exit_code", 2)
                raise python from None
        return call


extension = _Extension()
