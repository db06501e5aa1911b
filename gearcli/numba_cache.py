"""Where numba caches the compiled solver: a user folder keyed by a hash of the core sources.

numba's on-disk cache does not notice edits in modules a kernel depends on (numba issue #6845)
and cannot write into a read-only site-packages. Keying the cache folder by the content of
``gearcli/core/*.py`` solves both: a changed core gets a fresh folder. Must run before
``gearcli.core`` is imported; an explicit ``NUMBA_CACHE_DIR`` is respected.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

from gearcli import usercache


def configure() -> None:
    if "NUMBA_CACHE_DIR" in os.environ:
        return
    core = Path(__file__).parent / "core"
    digest = hashlib.sha256()
    for src in sorted(core.glob("*.py")):
        digest.update(src.name.encode())
        digest.update(src.read_bytes())
    folder = usercache.folder("numba", digest.hexdigest()[:16])
    if folder is not None:  # else no writable user cache: numba's default locators decide
        os.environ["NUMBA_CACHE_DIR"] = str(folder)
