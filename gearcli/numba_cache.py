"""Where numba caches the compiled solver: a user folder keyed by a hash of the core sources.

numba's on-disk cache does not notice edits in modules a kernel depends on (numba issue #6845)
and cannot write into a read-only site-packages. Keying the cache folder by the content of
``gearcli/core/*.py`` solves both: a changed core gets a fresh folder. Must run before
``gearcli.core`` is imported; an explicit ``NUMBA_CACHE_DIR`` is respected.
"""

from __future__ import annotations

import hashlib
import os
import pickle
import subprocess
import sys
import time
from pathlib import Path

from gearcli import usercache

#: A process waiting for the other one's cache entry gives up after this long [s].
HELPER_WAIT_S = 900.0


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


# --- two processes compiling one program (gearcli.core.timeloop, first run) -------------------
# numba writes each compiled function to the cache as soon as it is compiled, and looks in the
# cache before it compiles one. Two processes can therefore split a program's functions: each
# compiles its share and takes the other's from the cache, waiting for it where needed.
def parallel_compile_wanted() -> bool:
    """Two or more cores available and GEARCLI_PARALLEL_COMPILE not 0."""
    if os.environ.get("GEARCLI_PARALLEL_COMPILE", "1") == "0":
        return False
    try:
        return len(os.sched_getaffinity(0)) >= 2
    except AttributeError:  # no sched_getaffinity (macOS, Windows)
        return (os.cpu_count() or 1) >= 2


def wait_in_cache_lookup(dispatcher, keep_waiting):
    """Make ``dispatcher``'s cache lookups wait (polling) while its entry is missing and
    ``keep_waiting()`` is true; returns a function that undoes it."""
    cache = dispatcher._cache
    load = cache.load_overload

    def load_when_ready(sig, target_context):
        deadline = time.monotonic() + HELPER_WAIT_S
        while True:
            cres = load(sig, target_context)
            if cres is not None or not keep_waiting() or time.monotonic() > deadline:
                return cres
            time.sleep(0.2)

    cache.load_overload = load_when_ready

    def restore() -> None:
        cache.load_overload = load

    return restore


def start_helper(module: str, function: str, payload) -> subprocess.Popen | None:
    """``module.function(payload)`` in a new Python process (same interpreter, same cache
    folder); None when it cannot be started."""
    try:
        proc = subprocess.Popen(
            [sys.executable, "-c", "from gearcli.numba_cache import helper_main; helper_main()"],
            stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
            env={**os.environ, "GEARCLI_HELPER_PARENT": str(os.getpid())})
        proc.stdin.write(pickle.dumps((module, function, payload)))
        proc.stdin.close()
    except Exception:
        return None
    return proc


def stop_helper(proc: subprocess.Popen) -> None:
    if proc.poll() is None:
        proc.kill()
    proc.wait()


def parent_alive() -> bool:
    """In a helper: the process that started it is still running."""
    return str(os.getppid()) == os.environ.get("GEARCLI_HELPER_PARENT")


def helper_main() -> None:
    """Entry of a helper process: (module, function, payload) pickled on stdin."""
    import importlib

    module, function, payload = pickle.load(sys.stdin.buffer)
    getattr(importlib.import_module(module), function)(payload)
