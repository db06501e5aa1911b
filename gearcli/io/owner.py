"""Who a results folder belongs to, and one gearcli at a time on it (docs/theory.md §8).

- The producer: ``manifest.json`` records the command that made the folder and, for a study,
  the study's identity (:func:`study_identity`); a different producer writing into it is
  refused without ``--force`` (:func:`check_producer`).
- gearcli's own files: the manifest lists the names gearcli wrote at the top of the folder
  (``outputs``, kept up to date by :func:`gearcli.io.files.record_outputs`); ``--force``
  replaces those and nothing else (:func:`owned_names`). A manifest without the list (written
  before it existed) owns :data:`RESULT_NAMES`.
- The lock: :func:`folder_lock` holds an exclusive ``flock`` on the folder's parent folder for
  the time a command reads and writes the folder (analyze, report, stress) or swaps it
  (simulate, run, sweep...). Another gearcli on the same target waits up to
  :data:`LOCK_WAIT_S` (``GEARCLI_LOCK_WAIT_S``), then refuses; so an ``analyze`` never writes
  the analysis of a run that a ``simulate --force`` replaced meanwhile into the new run.
"""

from __future__ import annotations

import contextlib
import json
import os
import time
from pathlib import Path

from gearcli.errors import OutputError

MANIFEST = "manifest.json"
#: What gearcli writes at the top of a results folder: simulate and run (pipeline/outputs.py),
#: analyze (analysis_io.ANALYSIS_FILES), stress (stress.STRESS_FILES), report, mesh -o
#: (pipeline/mesh.py), rate -o (cli/rate.py), monitor -o (pipeline/monitor.py) and speed-curve
#: studies (pipeline/speed_curve.py).
#: With ``force`` these go with the earlier results and everything else moves into the new folder;
#: tests/cli/test_force_keeps_user_files.py checks the list against what the commands write
#: (a name missing here would only be moved over, stale, never lost).
RESULT_NAMES = frozenset({
    MANIFEST, "summary.json", "timeseries.csv", "timeseries.parquet", "zoom.csv",
    "analysis.json", "spectrum.csv", "harmonics.csv", "stress.csv", "stress.json",
    "report.html", "report.md", "figures", "mesh.json", "mesh.csv", "mesh.png",
    "summary.csv", "speed_curve.json", "speed_curve.png", "rating.json", "monitor.json",
    "speed_curve_rating.png",
    "sensors.csv", "sensors.parquet", "sensors.json", "mesh_faults.csv", "mesh_faults.png",
})
#: Longest wait for another gearcli working on the same folder [s] (GEARCLI_LOCK_WAIT_S).
LOCK_WAIT_S = 120.0
_POLL_S = 0.05
#: The command that writes (set by the command line's error handler; "api" in a program).
command = ["api"]
_held: dict[str, list] = {}  # parent folder -> [fd, depth]: re-entrant within a process


def read_manifest(folder: str | Path) -> dict | None:
    """The folder's manifest as a dict; None when it has none (or an unreadable one)."""
    p = Path(folder) / MANIFEST
    try:
        if p.is_symlink() or not p.is_file():
            return None
        doc = json.loads(p.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return doc if isinstance(doc, dict) else None


def producer(command: str, study: str | None = None) -> dict:
    """The producer record of a manifest: the command and (for studies) the study's
    identity."""
    return {"command": command, **({"study": study} if study else {})}


def describe(prod: dict) -> str:
    text = f"`{prod.get('command', '?')}`"
    if prod.get("study"):
        text += f" of study {prod['study'][:12]}"
    return text


def study_identity(name: str, design: str, columns: list[str], base_case_json: str) -> str:
    """A digest of what makes a study's rows comparable: its name, design, columns and
    resolved base case (more or fewer points of the same study keep it: resuming adds
    them)."""
    import hashlib

    text = json.dumps([name, design, columns, base_case_json], sort_keys=True)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def check_producer(folder: str | Path, prod: dict, force: bool) -> None:
    """Refuse to write into ``folder`` when its manifest names another producer, unless
    ``force``. Same producer, no folder or no manifest: nothing to say here."""
    doc = read_manifest(folder)
    if doc is None or force:
        return
    earlier = doc.get("producer")
    if earlier is None or earlier == prod:
        return
    raise OutputError(f"{folder}: holds the results of {describe(earlier)}, not of "
                      f"{describe(prod)}; use --force to replace them (files gearcli did not "
                      "write stay) or choose another folder")


def owned_names(folder: str | Path, default) -> frozenset[str]:
    """The names at the top of ``folder`` that gearcli wrote (its manifest's ``outputs``);
    ``default`` for a manifest without the list."""
    doc = read_manifest(folder)
    names = doc.get("outputs") if doc else None
    if not isinstance(names, list):
        return frozenset(default)
    return frozenset(n for n in names if isinstance(n, str)) | {MANIFEST}


def check_owned(folder: str | Path, names) -> None:
    """Refuse to replace, even with ``--force``, files of ``names`` in ``folder`` that its
    manifest does not list as gearcli's (the user's own ``report.md``, ``figures``...)."""
    owned = owned_names(folder, RESULT_NAMES)
    foreign = [n for n in names if n not in owned
               and ((Path(folder) / n).exists() or (Path(folder) / n).is_symlink())]
    if foreign:
        raise OutputError(f"{folder}: {', '.join(foreign)} not written by gearcli (its "
                          "manifest does not list them); move them away, gearcli does not "
                          "replace them")


def lock_wait_s() -> float:
    try:
        return max(0.0, float(os.environ.get("GEARCLI_LOCK_WAIT_S", LOCK_WAIT_S)))
    except ValueError:
        return LOCK_WAIT_S


@contextlib.contextmanager
def folder_lock(target: str | Path, wait_s: float | None = None):
    """Hold the lock of ``target`` (an exclusive flock on its parent folder) inside the block;
    wait for another holder up to ``wait_s`` (default :func:`lock_wait_s`), then refuse.
    Re-entrant in one process; where the system has no flock, nothing is locked."""
    try:
        import fcntl
    except ImportError:  # Windows: no advisory locks here
        yield
        return
    p = Path(target)
    parent = p.parent if str(p.parent) else Path(".")
    while not parent.is_dir() and parent != parent.parent:  # a folder to be created
        parent = parent.parent
    key = str(parent.resolve())
    if key in _held:
        _held[key][1] += 1
        try:
            yield
        finally:
            _held[key][1] -= 1
        return
    try:
        fd = os.open(parent, os.O_RDONLY)
    except OSError:
        yield  # an unreadable parent: the write itself will say what is wrong
        return
    try:
        _acquire(fcntl, fd, p, lock_wait_s() if wait_s is None else wait_s)
        _held[key] = [fd, 1]
        try:
            yield
        finally:
            del _held[key]
            fcntl.flock(fd, fcntl.LOCK_UN)
    finally:
        os.close(fd)


def _acquire(fcntl, fd: int, target: Path, wait_s: float) -> None:
    deadline = time.monotonic() + wait_s
    while True:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return
        except BlockingIOError:
            if time.monotonic() >= deadline:
                raise OutputError(f"{target}: another gearcli is writing there (waited "
                                  f"{wait_s:g} s); try again when it has finished") from None
            time.sleep(_POLL_S)
        except OSError:
            return  # a file system without locks: unlocked, as before
