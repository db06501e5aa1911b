"""The text of ``gearcli schema`` (the case file's JSON Schema), cached between calls.

Generating it needs pydantic and the schema's ~30 models: ~0.3 s of imports and class
building for a text that changes only with the code. The first call stores it in the user
cache with the size and modification time of every module file that was loaded to make it
(gearcli's, pydantic's, ...); later calls print it when all of them are unchanged (the check
Python's own bytecode cache makes) and generate it again otherwise.
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
import tempfile
from pathlib import Path

from gearcli import usercache


def _cache_name() -> str:
    """One cache file per installed copy of gearcli (worktrees, venvs do not share it)."""
    package = str(Path(__file__).resolve().parents[1])
    return f"case-schema-{hashlib.sha256(package.encode()).hexdigest()[:16]}.json"


def _stamp(path: str) -> list[int] | None:
    try:
        st = os.stat(path)
    except OSError:
        return None
    return [st.st_size, st.st_mtime_ns]


def _module_files() -> dict[str, list[int] | None]:
    files = {}
    for mod in list(sys.modules.values()):
        path = getattr(mod, "__file__", None)
        if isinstance(path, str):
            files[path] = _stamp(path)
    return files


def generate() -> str:
    """The JSON Schema of :class:`gearcli.case.schema.Case`, indented, without caching."""
    from gearcli.case.schema import Case

    return json.dumps(Case.model_json_schema(), indent=2)


def schema_text() -> str:
    """The JSON Schema text: from the cache when its sources are unchanged, else generated
    (and cached when the user cache folder is writable)."""
    folder = usercache.folder()
    path = folder / _cache_name() if folder is not None else None
    cached = _read(path) if path is not None else None
    if cached is not None:
        return cached
    text = generate()
    if path is not None:  # every loaded module counts as a source: a superset is only stricter
        sources = {src: stamp for src, stamp in _module_files().items() if stamp is not None}
        _write(path, {"python": sys.version, "sources": sources, "schema": text})
    return text


def _read(path: Path) -> str | None:
    try:
        doc = json.loads(path.read_text())
        if doc["python"] != sys.version:
            return None
        for src, stamp in doc["sources"].items():
            if _stamp(src) != stamp:
                return None
        return doc["schema"]
    except (OSError, ValueError, KeyError, TypeError):
        return None


def _write(path: Path, doc: dict) -> None:
    """Atomically (a temporary file renamed): concurrent calls never read half a file."""
    try:
        fd, tmp = tempfile.mkstemp(prefix=".case-schema-", dir=path.parent)
        with os.fdopen(fd, "w") as fh:
            json.dump(doc, fh)
        os.replace(tmp, path)
    except OSError:
        pass
