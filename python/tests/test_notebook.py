"""examples/qdot_in_python.ipynb runs top to bottom (nbclient), so it cannot rot."""

import os

import pytest

from conftest import ROOT

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")


def test_notebook_runs_top_to_bottom():
    os.environ.setdefault("MPLBACKEND", "Agg")
    path = ROOT / "examples" / "qdot_in_python.ipynb"
    nb = nbformat.read(path, as_version=4)
    client = nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                                     resources={"metadata": {"path": str(path.parent)}})
    client.execute()
    outputs = {i: c.get("outputs", []) for i, c in enumerate(nb.cells) if c.cell_type == "code"}
    text = "\n".join(
        str(o.get("text", "")) + str(o.get("data", {}).get("text/plain", ""))
        + str(o.get("data", {}).get("text/latex", "")) + str(o.get("data", {}).get("text/markdown", ""))
        for outs in outputs.values() for o in outs
    )
    # the accelerations of 23.4 typeset, the SymPy checks passed, a figure drawn
    assert "\\frac{343}{460} g" in text
    assert text.count("equal; SymPy") == 2
    assert any("image/png" in o.get("data", {}) for outs in outputs.values() for o in outs)
    assert "\\omega_{1}^{2}" in text
