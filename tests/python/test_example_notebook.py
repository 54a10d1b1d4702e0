"""The example notebook, executed as a user's Jupyter would (nbclient, a fresh kernel): the
hybrid run shows as the result's HTML table, the plot as an image, the events as a table."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
import syssimx

nbclient = pytest.importorskip("nbclient")
nbformat = pytest.importorskip("nbformat")
pytest.importorskip("ipykernel")

NOTEBOOK = Path(__file__).resolve().parents[2] / "examples" / "hybrid_pendulum.ipynb"


def test_the_hybrid_pendulum_notebook_shows_its_tables_and_plot(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch):
    # the kernel imports the syssimx this test imports, from any folder
    python_dir = str(Path(syssimx.__file__).resolve().parents[1])
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join(
        [python_dir, *filter(None, [os.environ.get("PYTHONPATH")])]))
    if os.environ.get("SYSSIMX_BUILD_DIR"):
        monkeypatch.setenv("SYSSIMX_BUILD_DIR",
                           str(Path(os.environ["SYSSIMX_BUILD_DIR"]).resolve()))
    notebook = nbformat.read(NOTEBOOK, as_version=4)
    nbclient.NotebookClient(notebook, timeout=120, kernel_name="python3",
                            resources={"metadata": {"path": str(tmp_path)}}).execute()
    nbformat.write(notebook, tmp_path / "executed.ipynb")  # to look at after a failure
    shown = [cell.outputs for cell in notebook.cells if cell.cell_type == "code"]
    run, plot, events, table = ([o for o in outputs if o.output_type == "execute_result"]
                                for outputs in shown)
    result_html = run[0].data["text/html"]
    assert "pendulum against a wall" in result_html and "<td>P.wall_hit</td>" in result_html
    assert "<caption>statistics</caption>" in result_html
    assert run[0].data["text/plain"].startswith("SimulationResult('pendulum against a wall'")
    assert plot[0].data["image/png"]  # the figure itself, not "<Figure size ...>"
    assert "Figure" in plot[0].data["text/plain"]
    assert events[0].data["text/html"].count("P.wall_hit") == 3  # at t*, 3t*, 5t* (< 3 s)
    assert "micro" in table[0].data["text/html"]
