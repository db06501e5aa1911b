"""The executed example notebook, examples/first_pair.ipynb, runs from top to bottom.

nbmake's runner (what ``pytest --nbmake examples/first_pair.ipynb`` uses) executes a fresh copy
of the notebook in a Jupyter kernel, with the stored outputs cleared; the notebook asserts that
both of its runs are valid and that every analysis check passes, so a change of the API it uses
fails here. The stored outputs are checked for size (the notebook stays small in git) and, for
the geometry cell, whose numbers do not depend on the solver, against the fresh run.
"""

from pathlib import Path

import pytest

NOTEBOOK = Path(__file__).resolve().parents[2] / "examples" / "first_pair.ipynb"
#: the stored notebook with its outputs and one small figure is ~55 kB
MAX_BYTES = 150_000


def _stdout(cell) -> str:
    return "".join(o.get("text", "") for o in cell.outputs
                   if o.output_type == "stream" and o.name == "stdout")


@pytest.mark.slow
def test_first_pair_notebook_runs():
    nb_run = pytest.importorskip("nbmake.nb_run")
    nbformat = pytest.importorskip("nbformat")
    result = nb_run.NotebookRun(NOTEBOOK, default_timeout=600).execute()
    assert result.error is None, result.error.trace

    stored = nbformat.read(str(NOTEBOOK), as_version=4)
    code = [i for i, c in enumerate(stored.cells) if c.cell_type == "code"]
    assert all(stored.cells[i].outputs for i in code), "store the notebook executed"
    geometry = next(i for i in code if "gearcli.geometry(" in stored.cells[i].source)
    fresh = _stdout(result.nb.cells[geometry])
    assert "contact ratio = " in fresh
    assert _stdout(stored.cells[geometry]) == fresh


def test_notebook_is_small():
    assert NOTEBOOK.stat().st_size < MAX_BYTES
