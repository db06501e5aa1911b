"""Architecture: imports point downward only (architecture.md).

core imports only numpy/numba/math (+ stdlib basics); model never imports pipeline/cli/io;
the library (everything but gearcli.cli) never imports typer.
"""

import ast
from pathlib import Path

import pytest

PKG = Path(__file__).resolve().parents[2] / "gearcli"
LAYERS = ["core", "model", "case", "pipeline", "io", "plotting", "report", "cli"]
# What each package may import from gearcli (besides itself and top-level modules).
ALLOWED = {
    "core": set(),
    "model": {"core"},
    "case": {"model"},
    "io": set(),
    "plotting": {"model"},
    "pipeline": {"core", "model", "case", "io", "plotting", "report"},
    "report": {"model", "case", "io", "plotting"},
    "cli": set(LAYERS),
}
STDLIB_OK_IN_CORE = {"math", "functools", "numpy", "numba", "__future__", "typing", "gearcli"}


def _imports(path: Path):
    tree = ast.parse(path.read_text())
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            yield node.module


def _files(layer):
    return sorted((PKG / layer).rglob("*.py"))


@pytest.mark.parametrize("layer", LAYERS)
def test_layer_imports_point_down(layer):
    for f in _files(layer):
        for mod in _imports(f):
            parts = mod.split(".")
            if parts[0] != "gearcli" or len(parts) < 2:
                continue
            target = parts[1]
            if target in LAYERS and target != layer:
                assert target in ALLOWED[layer], f"{f.relative_to(PKG)} imports {mod}"


def test_core_imports_only_numpy_numba_math():
    for f in _files("core"):
        for mod in _imports(f):
            top = mod.split(".")[0]
            assert top in STDLIB_OK_IN_CORE, f"{f.relative_to(PKG)} imports {mod}"
            # the one exception: jit.py sets numba's cache folder before importing numba
            if top == "gearcli" and mod != "gearcli.numba_cache":
                assert mod.startswith("gearcli.core"), f"{f.relative_to(PKG)} imports {mod}"


def test_library_never_imports_typer():
    for f in sorted(PKG.rglob("*.py")):
        if (PKG / "cli") in f.parents:
            continue
        for mod in _imports(f):
            assert mod.split(".")[0] not in {"typer", "click"}, (
                f"{f.relative_to(PKG)} imports {mod}"
            )
