"""String-keyed reads of result documents stay at the JSON boundary (issue 27).

The typed documents of gearcli/results/ are read by field everywhere but in gearcli/io/ (the
boundary that reads and writes the JSON) and gearcli/results/ itself. This test scans the
package's source (the abstract syntax tree, not text) for the two shapes such reads took:

* ``x["dynamic_factor"]`` or ``x.get("dynamic_factor")``: a subscript or ``get`` whose key is
  the name of a metric of the documents (gearcli/results/metrics.py, the label/unit registry
  their fields are made from) or of a field of theirs: a document read as a dict (the
  stress figure's ``static``, the sweep's speed plot did);
* ``manifest["resolved_case"]["gears"]...``: an entry of the resolved case read out of the
  manifest's dict instead of the typed Case (`gearcli analyze --spectra/--orders` did).
  Passing ``manifest["resolved_case"]`` whole to the case loader is the conversion into the
  typed Case, and is not flagged.

gearcli/core/ is left out (its extremum records have names of their own, core/layout.py), as
in tests/unit/test_result_documents.py.
"""

from __future__ import annotations

import ast
import dataclasses
import importlib
import inspect
import pkgutil
from pathlib import Path

import numpy as np
import pytest

from gearcli import results
from gearcli.results.fields import Document
from gearcli.results.metrics import METRICS

PKG = Path(results.__file__).resolve().parents[1]
#: Where string-keyed reads belong: the JSON boundary and the documents themselves.
BOUNDARY = {"io", "results", "core"}
#: Columns of the tables (time series, spectra: io/tables.py), read by column name by design;
#: documents have fields of the same names.
TABLE_COLUMNS = {"t_s", "frequency_Hz"}
#: Reads found that are not typed, with the reason: (file, enclosing function) -> why.
REMAINING = {
    ("pipeline/simulate.py", "energy_balance"):
        "not a result document: the energy terms before they become an EnergyBalance",
    ("model/fe/cache.py", "from_record"):
        "not a result document: a record of the FE model cache",
    ("plotting/results.py", "plot_modifications"):
        "not a result document: the report's relief panel data (report/figures.py)",
}


def _key(node: ast.AST) -> str | None:
    """The string key of ``x["key"]`` (a load) or ``x.get("key", ...)``, else None."""
    if isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) \
            and isinstance(node.slice, ast.Constant) and isinstance(node.slice.value, str):
        return node.slice.value
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
            and node.func.attr == "get" and node.args \
            and isinstance(node.args[0], ast.Constant) and isinstance(node.args[0].value, str):
        return node.args[0].value
    return None


def _inner(node: ast.AST) -> ast.AST | None:
    """What ``node`` reads from: ``x`` of ``x[...]`` and of ``x.get(...)``."""
    if isinstance(node, ast.Subscript):
        return node.value
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute):
        return node.func.value
    return None


def _document_names() -> set[str]:
    """The metric names (the registry) and every field name with an underscore of the
    documents of gearcli/results/ (``force_normal_N``, ``sigma_F0_MPa``...; one-word names
    like ``name`` or ``pinion`` are every dict's keys and are left out)."""
    names = set(METRICS)
    for info in pkgutil.iter_modules(results.__path__):
        module = importlib.import_module(f"gearcli.results.{info.name}")
        for _, cls in inspect.getmembers(module, inspect.isclass):
            if issubclass(cls, Document) and dataclasses.is_dataclass(cls):
                names |= {f.name for f in dataclasses.fields(cls) if "_" in f.name}
    return names


def string_reads(tree: ast.AST):
    """(enclosing function or "<module>", line, key) of every string-keyed read of a result
    document in ``tree`` (the two shapes of the module docstring)."""
    names = _document_names()

    def walk(node, scope):
        for child in ast.iter_child_nodes(node):
            inner = child.name if isinstance(child, ast.FunctionDef | ast.ClassDef) else scope
            key = _key(child)
            if key in names and key not in TABLE_COLUMNS:
                yield scope, child.lineno, key
            elif key is not None and _key(_inner(child)) == "resolved_case":
                yield scope, child.lineno, f"resolved_case.{key}"
            yield from walk(child, inner)

    yield from walk(tree, "<module>")


def test_no_string_keyed_reads_of_result_documents_outside_io():
    found, seen = [], set()
    for path in sorted(PKG.rglob("*.py")):
        rel = path.relative_to(PKG).as_posix()
        if rel.split("/")[0] in BOUNDARY:
            continue
        for scope, line, key in string_reads(ast.parse(path.read_text())):
            if (rel, scope) in REMAINING:
                seen.add((rel, scope))
            else:
                found.append(f"{rel}:{line} ({scope}): [{key!r}]")
    assert not found, ("result documents read by string key outside gearcli/io/ (read the "
                       "typed document's field instead):\n" + "\n".join(found))
    assert seen == set(REMAINING), f"no longer found, take out of REMAINING: " \
                                   f"{set(REMAINING) - seen}"


@pytest.mark.parametrize("source, expected", [
    ('def f(static):\n    return static["force_normal_N"]\n', [("f", 2, "force_normal_N")]),
    ("x = doc.get('dynamic_factor', 1.0)\n", [("<module>", 1, "dynamic_factor")]),
    ('t = m["resolved_case"]["gears"]["pinion"]["teeth"]\n',
     [("<module>", 1, "resolved_case.gears")]),
    ('h = m["resolved_case"].get("checks", {})\n', [("<module>", 1, "resolved_case.checks")]),
    # not reads of a document: a write, the case handed whole to the loader, another key
    ('row["dynamic_factor"] = 1.0\n', []),
    ('load(json.dumps(run.manifest["resolved_case"]))\n', []),
    ('x = cells["status"]\n', []),
])
def test_the_scan_finds_the_shapes_it_looks_for(source, expected):
    """The test above can fail: each shape it replaced is found, and only those."""
    assert list(string_reads(ast.parse(source))) == expected


def test_summary_csv_rows_are_read_as_typed_summaries():
    """The sweep's speed plot reads summary.csv rows as gearcli.results.Summary documents:
    a metric cell is the field of that name, a metric the table has no column for is the
    field's default (NaN)."""
    import pandas as pd

    from gearcli.pipeline.sweep.trends import summaries

    df = pd.DataFrame({"point": [0, 1], "status": ["ok", "ok"], "dynamic_factor": [1.25, 1.5],
                       "dte_rms_mm": [0.01, np.nan], "drive.speed [rpm]": [100.0, 200.0]})
    rows = summaries(df)
    assert [r.dynamic_factor for r in rows] == [1.25, 1.5]
    assert rows[0].dte_rms_mm == 0.01 and np.isnan(rows[1].dte_rms_mm)
    assert all(np.isnan(r.mesh_natural_frequency_Hz) for r in rows)
