#!/usr/bin/env python3
"""The worked example of docs/ensemble-in-time.md: the paper's model at k = 40,
mu = 5 and lambda = 0.5, 3.8, 10, watched in time.

    python3 examples/ensemble_in_time.py STICKSLIP OUT [REALIZATIONS]

Runs three sweeps of the same realizations (one seed) with the CLI STICKSLIP:
  OUT/transient  observe times lin:0:5:201 (the start from the uniform law)
  OUT/window     observe times lin:0:50:101 and the survival group
  OUT/burn_in    the same window with --burn-in 25
draws the figures with `stickslip plot` (and one overlay with matplotlib), and
prints the tables the page shows. Nothing here knows the closed forms: every
number is read from the sweeps' results.nc.
"""
import pathlib
import subprocess
import sys

import numpy as np
import xarray as xr

POINT = ["--k", "40", "--mu", "5", "--lambda", "0.5,3.8,10", "--seed", "1"]
LAMBDAS = [0.5, 3.8, 10.0]


def run(binary, *args):
    subprocess.run([binary, *args], check=True, stdout=subprocess.DEVNULL)


def sweeps(binary, out, realizations):
    n = ["--realizations", str(realizations)]
    run(binary, "sweep", *POINT, *n, "--observe-times", "lin:0:5:201", "-o", str(out / "transient"))
    run(binary, "sweep", *POINT, *n, "--observe-times", "lin:0:50:101",
        "--statistics", "paper,survival", "-o", str(out / "window"))
    run(binary, "sweep", *POINT, *n, "--burn-in", "25", "-o", str(out / "burn_in"))


def figures(binary, out):
    at = [a for lam in LAMBDAS for a in ("--at", f"lambda={lam:g}")]
    figs = out / "figures"
    run(binary, "plot", str(out / "transient"), "--time", *at, "-o", str(figs / "transient"))
    run(binary, "plot", str(out / "window"), "--time", *at, "-o", str(figs / "window"))
    run(binary, "plot", str(out / "window"), "--survival", "stick", *at, "-o", str(figs / "window"))
    overlay(xr.open_dataset(out / "window" / "results.nc"), figs / "stick_survival_vs_histogram.png")


def histogram_survival(d, lam):
    """1 - the cumulative share of the D histogram at its bin edges: the law of
    the sticks' durations if the stick cut by t_a were a whole stick."""
    p = d.sel({"lambda": lam})
    counts = p.stick_duration_counts.values.astype(float)
    total = counts.sum() + float(p.stick_duration_overflow)
    edges = np.append(p.stick_duration_bin_low.values, p.stick_duration_bin_high.values[-1])
    return edges, np.concatenate([[1.0], 1.0 - np.cumsum(counts) / total])


def overlay(d, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.2))
    for lam, colour in zip(LAMBDAS, ["C0", "C1", "C2"]):
        p = d.sel({"lambda": lam})
        t = d.stick_duration.values
        ax.fill_between(t, p.stick_survival_ci95_low, p.stick_survival_ci95_high, color=colour,
                        alpha=0.25, step="post", linewidth=0)
        ax.step(t, p.stick_survival, where="post", color=colour,
                label=f"Kaplan-Meier, lambda = {lam:g}")
        edges, s = histogram_survival(d, lam)
        ax.plot(edges, s, "--", color=colour, label=f"histogram of D, lambda = {lam:g}")
    ax.set_xlabel("stick duration D (s)")
    ax.set_ylabel("P(D > d) (1)")
    ax.set_xlim(0, float(d.stick_duration.values[-1]))
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def tables(out):
    tr = xr.open_dataset(out / "transient" / "results.nc")
    win = xr.open_dataset(out / "window" / "results.nc")
    bi = xr.open_dataset(out / "burn_in" / "results.nc")
    times = [0.0, 0.25, 0.5, 1.0, 2.0, 3.0, 5.0]
    print("Stick probability p(t) from the uniform start (OUT/transient; +- 1 SE in the last digit shown):")
    print("| lambda | " + " | ".join(f"t = {t:g} s" for t in times) + " |")
    print("|---:|" + "---:|" * len(times))
    for lam in LAMBDAS:
        p = tr.sel({"lambda": lam})
        cells = []
        for t in times:
            q = p.sel(time=t)
            cells.append(f"{float(q.stick_probability):.3f} ± {float(q.stick_probability_std_error):.3f}")
        print(f"| {lam:g} | " + " | ".join(cells) + " |")
    print()
    print("Long-time stick probability against R (OUT/window, OUT/burn_in):")
    print("| lambda | mean p(t), t in [25, 50] | R over [0, 50] | R over [25, 50] (--burn-in 25) |")
    print("|---:|---:|---:|---:|")
    for lam in LAMBDAS:
        p = win.sel({"lambda": lam})
        late = p.stick_probability.sel(time=slice(25.0, 50.0))
        # the times are 0.5 s apart: their p(t) are correlated, so this SE
        # (of independent times) is a lower bound; the table shows it as such
        se = float(np.sqrt((p.stick_probability_std_error.sel(time=slice(25.0, 50.0)) ** 2).mean()
                           / late.size))
        r = float(p.stick_fraction_mean)
        r_hw = float(p.stick_fraction_mean - p.stick_fraction_ci95_low)
        b = bi.sel({"lambda": lam})
        rb = float(b.stick_fraction_mean)
        rb_hw = float(b.stick_fraction_mean - b.stick_fraction_ci95_low)
        print(f"| {lam:g} | {float(late.mean()):.4f} (SE ≥ {se:.4f}) | {r:.4f} ± {r_hw:.4f} "
              f"| {rb:.4f} ± {rb_hw:.4f} |")
    print()
    print("Stick durations: Kaplan-Meier against the histogram of D (OUT/window):")
    print("| lambda | sticks | mean D (histogram: the cut stick whole) | KM restricted mean |")
    print("|---:|---:|---:|---:|")
    for lam in LAMBDAS:
        p = win.sel({"lambda": lam})
        print(f"| {lam:g} | {int(p.stick_duration_count)} | {float(p.stick_duration_mean):.4f} s "
              f"| {float(p.stick_restricted_mean):.4f} s |")


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    binary, out = sys.argv[1], pathlib.Path(sys.argv[2])
    realizations = int(sys.argv[3]) if len(sys.argv) > 3 else 20000
    out.mkdir(parents=True, exist_ok=True)
    sweeps(binary, out, realizations)
    figures(binary, out)
    tables(out)


if __name__ == "__main__":
    main()
