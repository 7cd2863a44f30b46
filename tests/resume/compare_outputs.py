#!/usr/bin/python3
"""compare_outputs.py A B: exit 0 when two sweep output directories hold the
same results: every variable of results.nc bit for bit (values, dtype, shape,
dimensions), summary.json's "points" text byte for byte, summary.csv and
records.csv (if present) byte for byte. Metadata that names the run (created
time, command line, elapsed time, thread count) may differ and is not compared.
"""
import os
import sys

import netCDF4
import numpy as np


def points_text(path):
    text = open(path, encoding="utf-8").read()
    start = text.index('"points"')
    i = text.index("[", start)
    depth = 0
    in_string = False
    for j in range(i, len(text)):
        c = text[j]
        if in_string:
            if c == "\\":
                continue
            if c == '"' and text[j - 1] != "\\":
                in_string = False
        elif c == '"':
            in_string = True
        elif c == "[":
            depth += 1
        elif c == "]":
            depth -= 1
            if depth == 0:
                return text[i:j + 1]
    raise ValueError(f"{path}: unterminated points array")


def variables(path):
    out = {}
    with netCDF4.Dataset(path) as ds:
        ds.set_auto_mask(False)
        for name, var in ds.variables.items():
            data = np.asarray(var[...])
            out[name] = (var.dimensions, data.dtype.str, data.shape, data.tobytes())
    return out


def main(a, b):
    problems = []
    va, vb = variables(os.path.join(a, "results.nc")), variables(os.path.join(b, "results.nc"))
    if va.keys() != vb.keys():
        problems.append(f"results.nc variables differ: {sorted(va.keys() ^ vb.keys())}")
    for name in sorted(va.keys() & vb.keys()):
        if va[name] != vb[name]:
            problems.append(f"results.nc variable {name} differs")
    if points_text(os.path.join(a, "summary.json")) != points_text(os.path.join(b, "summary.json")):
        problems.append("summary.json points differ")
    for name in ("summary.csv", "records.csv"):
        pa, pb = os.path.join(a, name), os.path.join(b, name)
        if os.path.exists(pa) or os.path.exists(pb):
            if not (os.path.exists(pa) and os.path.exists(pb)) or open(pa, "rb").read() != open(pb, "rb").read():
                problems.append(f"{name} differs")
    for p in problems:
        print(f"compare_outputs: {a} vs {b}: {p}", file=sys.stderr)
    if not problems:
        print(f"compare_outputs: {a} == {b} ({len(va)} netCDF variables, points, CSV)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
