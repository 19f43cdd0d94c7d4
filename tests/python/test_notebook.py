"""examples/notebooks/rockbench_tour.ipynb runs from its first cell to its last (nbclient, the
python3 kernel): a cell that raises fails the test. Its figures go to a temporary folder."""

import os

import nbclient
import nbformat

SOURCE = os.environ["ROCKBENCH_SOURCE_DIR"]
NOTEBOOK = os.path.join(SOURCE, "examples", "notebooks", "rockbench_tour.ipynb")


def test_the_notebook_runs(tmp_path, monkeypatch):
    monkeypatch.setenv("ROCKBENCH_FIGURES", str(tmp_path))
    monkeypatch.setenv("MPLBACKEND", "Agg")
    nb = nbformat.read(NOTEBOOK, as_version=4)
    client = nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                                     resources={"metadata": {"path": str(tmp_path)}})
    client.execute()
    # Every code cell ran, and drew what it says.
    assert all(c.get("execution_count") for c in nb.cells if c.cell_type == "code")
    for figure in ("python_reference_angles.png", "python_compare_error.png",
                   "python_fragility.png"):
        assert (tmp_path / figure).stat().st_size > 10_000, figure
