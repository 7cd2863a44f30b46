"""Names and layout in Python: the lambda axis is
selectable by the keyword's name (`ds.sel(lam=...)`; `lambda` is a Python
keyword), the axes come in the command line's order, the docs say what `c`
accepts, and Realization.plot()'s legend does not cover the trace."""
import os
import re

import numpy as np
import pytest
import xarray as xr

import stickslip

HERE = os.path.dirname(os.path.abspath(__file__))
DOCS = os.path.join(HERE, "..", "..", "docs", "python.md")


@pytest.fixture(scope="module")
def cli_grid(tmp_path_factory, cli):
    out = tmp_path_factory.mktemp("names") / "sweep"
    cli("sweep", "--k", "2,4", "--mu", "1,2", "--lambda", "1,3.8", "--realizations", 60, "--ta", 5,
        "-o", out)
    with xr.open_dataset(out / "results.nc") as ds:
        return out, ds.load()


def test_lambda_is_selected_as_lam(cli_grid):
    out, theirs = cli_grid
    for ds in (stickslip.sweep(k=[2, 4], mu=[1, 2], lam=[1, 3.8], realizations=60, ta=5),
               stickslip.open(out)):
        ours = ds.stick_fraction_mean.sel(lam=3.8, mu=2)
        assert ours.values.tobytes() == theirs.stick_fraction_mean.sel({"lambda": 3.8, "mu": 2}).values.tobytes()
        assert float(ds.stick_fraction_mean.idxmax("lam").sel(mu=2, k=4)) in (1.0, 3.8)
        assert ds["lambda"].values.tolist() == ds["lam"].values.tolist() == [1.0, 3.8]


def test_axes_are_in_the_command_lines_order(cli_grid):
    _, theirs = cli_grid
    ours = stickslip.sweep(k=[2, 4], mu=[1, 2], lam=[1, 3.8], realizations=60, ta=5)
    names = [{"lam": "lambda"}.get(d, d) for d in ours.stick_fraction_mean.dims]
    assert names == list(theirs.stick_fraction_mean.dims) == ["lambda", "mu", "k"]
    assert ours.attrs["swept_parameters"] == theirs.attrs["swept_parameters"]
    assert (ours.stick_fraction_mean.values.tobytes() == theirs.stick_fraction_mean.values.tobytes())


def test_a_damping_axis_from_zero_is_accepted_as_the_docs_say(cli, tmp_path):
    ds = stickslip.sweep(c=[0, 1], realizations=20, ta=2)
    assert ds["c"].values.tolist() == [0.0, 1.0]
    cli("sweep", "--c", "0,1", "--realizations", 20, "--ta", 2, "-o", tmp_path / "c")
    text = open(DOCS).read()
    said = re.findall(r"[^.]*`c=\[0, 1\]`[^.]*\.", text)
    assert said, "docs/python.md says nothing about c=[0, 1]"
    assert not any("refused" in s for s in said), said


def test_plot_legend_does_not_cover_the_trace(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    for kwargs in (dict(seed=4, ta=20), dict(mu=5, k=40, c=2, seed=3, ta=10)):
        ax = stickslip.simulate(**kwargs).plot()
        fig = ax.figure
        fig.savefig(tmp_path / "r.png")
        renderer = fig.canvas.get_renderer()
        legend = ax.get_legend().get_window_extent(renderer)
        axes = ax.get_window_extent(renderer)
        # The legend lies outside the data area, so no line can run under it ...
        assert not legend.overlaps(axes), (legend, axes)
        # ... and inside the figure, so it is seen.
        assert fig.bbox.contains(legend.x0, legend.y0) and fig.bbox.contains(legend.x1, legend.y1)
        title = ax.title.get_window_extent(renderer)
        assert fig.bbox.contains(title.x0, title.y1 - 1) and fig.bbox.contains(title.x1, title.y1 - 1)
        import matplotlib.pyplot as plt
        plt.close(fig)
