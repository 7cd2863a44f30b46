#!/usr/bin/env python3
"""Figures of docs/models.md: what the model family adds to the paper's model.

Runs `stickslip sweep` for three families of curves on the paper's point
(m = 1, k = 40, mu_k = 5, V = 1, t_a = 50 s) and plots mean R against lambda
with 95 % intervals:
  1. static above kinetic friction, mu_s / mu_k = 1, 1.2, 1.5, 2;
  2. viscous damping, damping ratio zeta = c / (2 sqrt(k m)) = 0, 0.05, 0.2, 1,
     with mu_s = 6 > mu_k = 5 (with mu_s = mu_k a damped slip that leaves the
     band edge never returns to x' = v before the next switch: docs/model.md);
  3. belts that are not symmetric: (+1, -1) (the paper), (+1, 0) (stop and go),
     (+1, -0.5), and a three-level belt (+1, 0, -1) with the same mean rate.

usage: model_family_figures.py STICKSLIP_BINARY OUT_DIR [--realizations N]
Prints the commands it runs and the wall time of each sweep.
"""
import argparse
import csv
import json
import math
import pathlib
import subprocess
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LAMBDA = "log:0.1:30:25"
BASE = ["--k", "40", "--mu", "5", "--seed", "2026"]


def sweep(binary, out, args, realizations):
    cmd = [binary, "sweep", "--lambda", LAMBDA, *BASE, *args,
           "--realizations", str(realizations), "--overwrite", "-o", str(out)]
    t0 = time.monotonic()
    subprocess.run(cmd, check=True, stderr=subprocess.DEVNULL)
    print(f"{time.monotonic() - t0:6.1f} s  stickslip {' '.join(cmd[1:])}")
    return list(csv.DictReader(open(out / "summary.csv")))


def curve(ax, rows, label, **style):
    lam = [float(r["lambda"]) for r in rows]
    mean = [float(r["R_mean"]) for r in rows]
    lo = [float(r["R_ci95_low"]) for r in rows]
    hi = [float(r["R_ci95_high"]) for r in rows]
    line, = ax.plot(lam, mean, marker="o", markersize=3, label=label, **style)
    ax.fill_between(lam, lo, hi, color=line.get_color(), alpha=0.25, linewidth=0)
    peak = max(range(len(mean)), key=mean.__getitem__)
    return {"label": label, "lambda_at_max": lam[peak], "R_max": mean[peak],
            "R_at_0.1": mean[0], "R_at_30": mean[-1]}


def panel(title):
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.set_xscale("log")
    ax.set_xlabel("switch rate λ [1/s]")
    ax.set_ylabel("mean stick fraction R")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    return fig, ax


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("binary")
    ap.add_argument("out_dir", type=pathlib.Path)
    ap.add_argument("--realizations", type=int, default=2000)
    a = ap.parse_args()
    a.out_dir.mkdir(parents=True, exist_ok=True)
    work = a.out_dir / "runs"
    work.mkdir(exist_ok=True)
    table = {}

    fig, ax = panel("static above kinetic friction (μk = 5, k = 40)")
    table["friction"] = []
    for ratio in (1.0, 1.2, 1.5, 2.0):
        rows = sweep(a.binary, work / f"mus{ratio}", ["--mu-s", f"{5 * ratio:g}", "--mu-k", "5"],
                     a.realizations)
        table["friction"].append(curve(ax, rows, f"μs/μk = {ratio:g}"))
    ax.legend()
    fig.tight_layout()
    fig.savefig(a.out_dir / "models_R_friction_ratio.png", dpi=110)

    fig, ax = panel("viscous damping (μs = 6, μk = 5, k = 40)")
    table["damping"] = []
    for zeta in (0.0, 0.05, 0.2, 1.0):
        c = 2 * zeta * math.sqrt(40.0)
        rows = sweep(a.binary, work / f"zeta{zeta}",
                     ["--c", f"{c:.6g}", "--mu-s", "6", "--mu-k", "5"], a.realizations)
        table["damping"].append(curve(ax, rows, f"ζ = {zeta:g} (c = {c:.3g} N s/m)"))
    ax.legend()
    fig.tight_layout()
    fig.savefig(a.out_dir / "models_R_damping.png", dpi=110)

    fig, ax = panel("belts that are not symmetric (μ = 5, k = 40)")
    table["belts"] = []
    for levels in ("1,-1", "1,0", "1,-0.5"):
        rows = sweep(a.binary, work / f"levels{levels}", ["--belt-levels", levels], a.realizations)
        table["belts"].append(curve(ax, rows, f"levels ({levels})"))
    ax.legend()
    fig.tight_layout()
    fig.savefig(a.out_dir / "models_R_belts.png", dpi=110)
    json.dump(table, open(a.out_dir / "models_summary.json", "w"), indent=1)
    for name, rows in table.items():
        print(f"\n{name}:")
        for r in rows:
            print(f"  {r['label']:32s} R max {r['R_max']:.3f} at lambda {r['lambda_at_max']:.3g};"
                  f" R(0.1) {r['R_at_0.1']:.3f}, R(30) {r['R_at_30']:.3f}")


if __name__ == "__main__":
    sys.exit(main())
