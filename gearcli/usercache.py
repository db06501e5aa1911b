"""gearcli's folder in the user's cache: ``$XDG_CACHE_HOME/gearcli`` (``~/.cache/gearcli``).

Holds what is slow to make and cheap to check: the compiled solver (:mod:`gearcli.numba_cache`)
and the case file's JSON Schema (:mod:`gearcli.case.schema_text`). Nothing in it is needed:
without a writable cache folder gearcli computes everything each time.
"""

from __future__ import annotations

import os
from pathlib import Path


def folder(*parts: str) -> Path | None:
    """``<cache>/gearcli/<parts>``, created; None when it cannot be created or written."""
    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    path = base.joinpath("gearcli", *parts)
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError:
        return None
    return path if os.access(path, os.W_OK) else None
