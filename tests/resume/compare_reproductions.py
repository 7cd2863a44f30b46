#!/usr/bin/python3
"""compare_reproductions.py A B: exit 0 when two `stickslip reproduce` output
folders hold the same results: every sweep output directory (one with a
results.nc) as compare_outputs.py compares it, every other file byte for byte,
and report.md line for line except the lines that name the run (wall times,
command line, creation time, threads and MPI ranks), which may differ.
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import compare_outputs  # noqa: E402

RUN_SPECIFIC = re.compile(r"\d s \||\d s on |threads|MPI ranks|\| command \||created \(UTC\)")


def files(root):
    out = set()
    for d, _, names in os.walk(root):
        for n in names:
            out.add(os.path.relpath(os.path.join(d, n), root))
    return out


def report_lines(path):
    with open(path, encoding="utf-8") as f:
        return [line for line in f if not RUN_SPECIFIC.search(line)]


def main(a, b):
    problems = []
    fa, fb = files(a), files(b)
    if fa != fb:
        problems.append(f"different files: {sorted(fa ^ fb)}")
    sweep_dirs = sorted({os.path.dirname(f) for f in fa & fb if os.path.basename(f) == "results.nc"})
    for d in sweep_dirs:
        if compare_outputs.main(os.path.join(a, d), os.path.join(b, d)) != 0:
            problems.append(f"sweep outputs in {d} differ")
    for f in sorted(fa & fb):
        if os.path.dirname(f) in sweep_dirs and os.path.basename(f) in (
                "results.nc", "summary.json", "summary.csv", "records.csv"):
            continue  # compared above, less their run metadata
        pa, pb = os.path.join(a, f), os.path.join(b, f)
        if f == "report.md":
            if report_lines(pa) != report_lines(pb):
                problems.append("report.md differs (beyond run times and names)")
        elif f == "report.html":
            continue  # rendered from the same document as report.md
        elif open(pa, "rb").read() != open(pb, "rb").read():
            problems.append(f"{f} differs")
    for p in problems:
        print(f"compare_reproductions: {a} vs {b}: {p}", file=sys.stderr)
    if not problems:
        print(f"compare_reproductions: {a} == {b} ({len(sweep_dirs)} sweep outputs, "
              f"{len(fa)} files)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
