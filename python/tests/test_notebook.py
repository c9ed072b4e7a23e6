"""examples/qdot_in_python.ipynb runs top to bottom (nbclient), so it cannot
rot: from the repository's root (where a newcomer starts Jupyter or
nbclient), and from a folder outside the repository with QDOT_EXAMPLES
naming the examples."""

import os

import pytest

from conftest import ROOT

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")

NOTEBOOK = ROOT / "examples" / "qdot_in_python.ipynb"


def execute(cwd, monkeypatch):
    """The notebook run by a kernel started in `cwd`; the texts and the
    outputs of its code cells."""
    monkeypatch.setenv("MPLBACKEND", "Agg")
    nb = nbformat.read(NOTEBOOK, as_version=4)
    client = nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                                     resources={"metadata": {"path": str(cwd)}})
    client.execute()
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    text = "\n".join(
        str(o.get("text", "")) + str(o.get("data", {}).get("text/plain", ""))
        + str(o.get("data", {}).get("text/latex", "")) + str(o.get("data", {}).get("text/markdown", ""))
        for o in outputs
    )
    return text, outputs


def test_notebook_runs_top_to_bottom_from_the_repository_root(monkeypatch):
    monkeypatch.delenv("QDOT_EXAMPLES", raising=False)
    text, outputs = execute(ROOT, monkeypatch)
    # the accelerations of 23.4 typeset, the SymPy checks passed, a figure drawn
    assert "\\frac{343}{460} g" in text
    assert text.count("equal; SymPy") == 2
    assert any("image/png" in o.get("data", {}) for o in outputs)
    assert "\\omega_{1}^{2}" in text


def test_notebook_runs_outside_the_repository_with_qdot_examples(tmp_path, monkeypatch):
    monkeypatch.setenv("QDOT_EXAMPLES", str(ROOT / "examples"))
    text, _ = execute(tmp_path, monkeypatch)
    assert text.count("equal; SymPy") == 2
    assert list(tmp_path.iterdir()) == []


def test_the_notebook_finds_the_examples_wherever_it_starts_in_the_repository(tmp_path, monkeypatch):
    """The first cell (imports, EXAMPLES) run here: from the examples
    folder (Jupyter's default for the notebook), the root or a folder
    below it; outside the repository it says what to do."""
    first = nbformat.read(NOTEBOOK, as_version=4).cells[1].source
    assert "EXAMPLES = examples_folder()" in first
    monkeypatch.delenv("QDOT_EXAMPLES", raising=False)
    for cwd in (ROOT / "examples", ROOT, ROOT / "python" / "tests"):
        monkeypatch.chdir(cwd)
        names = {}
        exec(first, names)  # noqa: S102 - the notebook's own cell
        assert names["EXAMPLES"] == ROOT / "examples", cwd
    monkeypatch.chdir(tmp_path)
    with pytest.raises(FileNotFoundError, match=r"^no seed_23_4.qd here, above here, or in an examples/ "
                       r"folder of either: start Jupyter in the qdot repository, or set QDOT_EXAMPLES "
                       r"to its examples folder$"):
        exec(first, {})  # noqa: S102
