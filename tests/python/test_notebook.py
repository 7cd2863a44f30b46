"""examples/paper_fig7.ipynb runs headless (nbclient, the python3 kernel of
Debian's ipykernel) and draws the paper's Fig. 7."""
import os
import shutil

import nbclient
import nbformat

EXAMPLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples",
                       "paper_fig7.ipynb")


def test_paper_fig7_notebook_runs(tmp_path):
    shutil.copy(EXAMPLE, tmp_path / "paper_fig7.ipynb")
    nb = nbformat.read(tmp_path / "paper_fig7.ipynb", as_version=4)
    nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": str(tmp_path)}}).execute()
    png = tmp_path / "paper_fig7.png"
    assert png.exists() and png.stat().st_size > 20000
    text = "".join(o.get("text", "") for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", []))
    assert "mu = 5: largest mean R on the grid" in text
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])
              if o.get("output_type") == "error"]
    assert not errors
