"""The example notebook: its code cells compile, and run from top to bottom (in order, in one
namespace)."""

import json
from pathlib import Path

import matplotlib
import pytest

NOTEBOOK = Path(__file__).resolve().parent.parent / "examples" / "walkthrough.ipynb"


def code_cells():
    cells = json.loads(NOTEBOOK.read_text(encoding="utf-8"))["cells"]
    return ["".join(c["source"]) for c in cells if c["cell_type"] == "code"]


def test_walkthrough_notebook_cells_compile():
    code = code_cells()
    assert code, "the notebook has no code"
    for i, source in enumerate(code):
        compile(source, f"{NOTEBOOK.name}[code cell {i}]", "exec")


@pytest.mark.slow
def test_walkthrough_notebook_runs(monkeypatch, tmp_path):
    matplotlib.use("Agg")
    monkeypatch.chdir(tmp_path)
    code = code_cells()
    assert code, "the notebook has no code"
    namespace = {}
    for i, source in enumerate(code):
        exec(compile(source, f"{NOTEBOOK.name}[code cell {i}]", "exec"), namespace)
    import matplotlib.pyplot as plt

    plt.close("all")
