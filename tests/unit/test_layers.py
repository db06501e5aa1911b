"""Architecture: imports point downward only (architecture.md).

core imports only numpy/numba/math (+ stdlib basics); model never imports pipeline/cli/io;
the library (everything but gearcli.cli) never imports typer. No import cycles among gearcli
modules (function-level imports included), and no module uses another module's private
(``_name``) functions: a helper two modules need is public in the lower one.
"""

import ast
import itertools
from collections.abc import Iterator
from pathlib import Path

import pytest

PKG = Path(__file__).resolve().parents[2] / "gearcli"
LAYERS = ["core", "model", "case", "results", "pipeline", "io", "plotting", "report", "cli"]
# What each package may import from gearcli (besides itself and the base modules below).
ALLOWED = {
    "core": set(),
    "model": {"core"},
    "case": {"model"},
    "results": set(),  # the typed documents: a leaf that io (the JSON boundary) reads and writes
    "io": {"results"},
    "plotting": {"model"},
    "pipeline": {"core", "model", "case", "results", "io", "plotting", "report"},
    "report": {"model", "case", "results", "io", "plotting"},
    "cli": set(LAYERS),
}
# The top-level modules, placed: the base modules every layer may use import no layer package
# (only each other); the public API sits beside the CLI, over pipeline.
BASE_MODULES = {"units", "errors", "guards", "display_units", "interrupts", "usercache",
                "numba_cache", "numba_inline", "numba_ssa"}
TOP_MODULES = {"api": set(LAYERS) - {"cli"}, "__main__": {"cli"}, "__init__": set()}
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


def test_every_top_level_module_is_placed():
    """Each gearcli/*.py is a base module or a top module with its allowed layers; a new
    top-level module must be placed here."""
    found = {f.stem for f in PKG.glob("*.py")}
    assert found == BASE_MODULES | set(TOP_MODULES), found ^ (BASE_MODULES | set(TOP_MODULES))


@pytest.mark.parametrize("name", sorted(BASE_MODULES | set(TOP_MODULES)))
def test_top_level_modules_import_within_their_place(name):
    allowed = TOP_MODULES.get(name, set())
    for mod in _imports(PKG / f"{name}.py"):
        parts = mod.split(".")
        if parts[0] != "gearcli" or len(parts) < 2:
            continue
        target = parts[1]
        if target in LAYERS:
            assert target in allowed, f"{name}.py imports {mod}"
        else:
            assert target in BASE_MODULES or target == "__version__", f"{name}.py imports {mod}"


def test_only_the_cli_and_the_package_import_the_public_api():
    """gearcli/api.py sits above pipeline, like the CLI: no layer below may import it."""
    for layer in LAYERS:
        if layer == "cli":
            continue
        for f in _files(layer):
            assert "gearcli.api" not in _imports(f), f"{f.relative_to(PKG)} imports gearcli.api"


def test_core_imports_only_numpy_numba_math():
    for f in _files("core"):
        for mod in _imports(f):
            top = mod.split(".")[0]
            assert top in STDLIB_OK_IN_CORE, f"{f.relative_to(PKG)} imports {mod}"
            # the exceptions, numba's configuration in jit.py: the cache folder (set before
            # numba is imported) and the inliner's copies (gearcli/numba_inline.py)
            if top == "gearcli" and mod not in ("gearcli.numba_cache", "gearcli.numba_inline"):
                assert mod.startswith("gearcli.core"), f"{f.relative_to(PKG)} imports {mod}"


def test_library_never_imports_typer():
    for f in sorted(PKG.rglob("*.py")):
        if (PKG / "cli") in f.parents:
            continue
        for mod in _imports(f):
            assert mod.split(".")[0] not in {"typer", "click"}, (
                f"{f.relative_to(PKG)} imports {mod}"
            )



# --- the module graph: every gearcli import, module-level or inside a function -----------------


def _module_names() -> dict[str, Path]:
    """Dotted name -> file of every gearcli module (a package is its ``__init__.py``)."""
    out = {}
    for f in sorted(PKG.rglob("*.py")):
        parts = f.relative_to(PKG.parent).with_suffix("").parts
        out[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = f
    return out


MODULES = _module_names()


def _is_private(name: str) -> bool:
    """``_name`` (one leading underscore); dunders such as ``__version__`` are public."""
    return name.startswith("_") and not name.startswith("__")


def _from_base(module: str, node: ast.ImportFrom, modules: dict[str, Path]) -> str | None:
    """The absolute module of ``from BASE import ...`` in ``module`` (relative imports too)."""
    if node.level == 0:
        return node.module
    package = module if modules[module].name == "__init__.py" else module.rpartition(".")[0]
    parts = package.split(".")
    parts = parts[: len(parts) - (node.level - 1)]
    return ".".join(parts + ([node.module] if node.module else []))


def _gearcli_imports(
    module: str, tree: ast.AST, modules: dict[str, Path] = MODULES
) -> Iterator[tuple[str, str | None, int]]:
    """(imported gearcli module, name imported from it or None, line) of each import.

    ``from gearcli.x import y`` is module ``gearcli.x.y`` when y is a submodule, else the name
    y of ``gearcli.x``. Imports anywhere in the file count: a function-level import still
    forms a cycle when the function runs, and one under ``if TYPE_CHECKING:`` still ties the
    two modules together.
    """
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name in modules:
                    yield alias.name, None, node.lineno
        elif isinstance(node, ast.ImportFrom):
            base = _from_base(module, node, modules)
            if base not in modules:
                continue
            for alias in node.names:
                sub = f"{base}.{alias.name}"
                if sub in modules:
                    yield sub, None, node.lineno
                else:
                    yield base, alias.name, node.lineno


def _graph() -> dict[str, dict[str, int]]:
    """importer -> {imported gearcli module: line of the first such import}."""
    graph: dict[str, dict[str, int]] = {m: {} for m in MODULES}
    for module, path in MODULES.items():
        for target, _, line in _gearcli_imports(module, ast.parse(path.read_text())):
            if target != module:
                graph[module].setdefault(target, line)
    return graph


def _cycles(graph: dict[str, dict[str, int]]) -> list[list[str]]:
    """A shortest cycle [a, b, ..., a] through each strongly connected group (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    groups: list[set[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = {stack.pop()}
            while v not in group:
                group.add(stack.pop())
            if len(group) > 1:
                groups.append(group)

    for v in sorted(graph):
        if v not in index:
            visit(v)
    cycles = []
    for group in groups:  # breadth-first from the group's first module back to it
        start = min(group)
        paths = {start: [start]}
        queue = [start]
        for v in queue:
            if start in graph[v]:
                cycles.append([*paths[v], start])
                break
            for w in sorted(graph[v]):
                if w in group and w not in paths:
                    paths[w] = [*paths[v], w]
                    queue.append(w)
    return sorted(cycles)


def _describe(cycle: list[str], graph: dict[str, dict[str, int]]) -> str:
    """``a -> b -> a (gearcli/a.py:12 imports b; gearcli/b.py:40 imports a)``."""
    steps = [
        f"{MODULES[a].relative_to(PKG.parent)}:{graph[a][b]} imports {b}"
        for a, b in itertools.pairwise(cycle)
    ]
    return " -> ".join(cycle) + " (" + "; ".join(steps) + ")"


def test_no_import_cycles():
    graph = _graph()
    cycles = _cycles(graph)
    assert not cycles, "import cycles among gearcli modules:\n" + "\n".join(
        _describe(c, graph) for c in cycles
    )


def test_cycle_finder_on_a_made_up_graph():
    graph = {"a": {"b": 1}, "b": {"c": 2, "d": 2}, "c": {"a": 3}, "d": {"a": 4, "e": 4},
             "e": {}, "f": {"g": 5}, "g": {"f": 6}}
    assert _cycles(graph) == [["a", "b", "c", "a"], ["f", "g", "f"]]
    modules = {m: Path(f"{m}.py") for m in ("gearcli.x", "gearcli.x.y", "gearcli.x.z")}
    modules["gearcli.x"] = Path("x/__init__.py")
    tree = ast.parse("from gearcli.x import y, w\ndef f():\n    from . import z\n")
    assert list(_gearcli_imports("gearcli.x.y", tree, modules)) == [
        ("gearcli.x.y", None, 1), ("gearcli.x", "w", 1), ("gearcli.x.z", None, 3)
    ]


# --- no module uses another module's private names ---------------------------------------------


def _module_aliases(module: str, tree: ast.AST) -> dict[str, str]:
    """Local name -> the gearcli module it is bound to (``import gearcli.x as m``, ...)."""
    aliases = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name in MODULES and alias.asname:
                    aliases[alias.asname] = alias.name
                elif alias.name in MODULES:  # `import gearcli.x.y` binds `gearcli`
                    aliases[alias.name.partition(".")[0]] = alias.name.partition(".")[0]
        elif isinstance(node, ast.ImportFrom):
            base = _from_base(module, node, MODULES)
            for alias in node.names:
                if f"{base}.{alias.name}" in MODULES:
                    aliases[alias.asname or alias.name] = f"{base}.{alias.name}"
    return aliases


def _dotted(node: ast.expr, aliases: dict[str, str]) -> str | None:
    """``m.sub`` -> 'gearcli.x.sub' when ``m`` names a gearcli module, else None."""
    if isinstance(node, ast.Name):
        return aliases.get(node.id)
    if isinstance(node, ast.Attribute):
        base = _dotted(node.value, aliases)
        return f"{base}.{node.attr}" if base else None
    return None


def _private_uses(module: str) -> Iterator[str]:
    """``from gearcli.x import _name`` and ``x._name`` in ``module``, x another gearcli module."""
    tree = ast.parse(MODULES[module].read_text())
    where = MODULES[module].relative_to(PKG.parent)
    for target, name, line in _gearcli_imports(module, tree):
        if name is not None and _is_private(name) and target != module:
            yield f"{where}:{line}: from {target} import {name}"
    aliases = _module_aliases(module, tree)
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and _is_private(node.attr):
            owner = _dotted(node.value, aliases)
            if owner in MODULES and owner != module:
                yield f"{where}:{node.lineno}: uses {owner}.{node.attr}"


def test_no_private_names_across_modules():
    found = [u for m in MODULES for u in _private_uses(m)]
    assert not found, "gearcli modules using another module's private names (make the helper " \
        "public in the lower module):\n" + "\n".join(found)


def test_no_compiled_function_takes_more_than_ten_parameters():
    """Narrow kernel interfaces (architecture habit 11): a numba function takes named bundles,
    not long positional lists; more than 10 parameters means a bundle is missing."""
    long = []
    for f in _files("core"):
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.FunctionDef) and node.decorator_list \
                    and len(node.args.args) > 10:
                long.append(f"{f.relative_to(PKG)}:{node.name} ({len(node.args.args)})")
    assert long == []
