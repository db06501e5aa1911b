"""Who a results folder belongs to, and one gearcli at a time on it (docs/theory.md §8).

- The producer: ``manifest.json`` records the command that made the folder and, for a study,
  the study's identity (:func:`study_identity`); a different producer writing into it is
  refused without ``--force`` (:func:`check_producer`).
- gearcli's own files: the manifest lists the names gearcli wrote at the top of the folder
  (``outputs``, kept up to date by :func:`gearcli.io.files.record_outputs`); ``--force``
  replaces those and nothing else (:func:`owned_names`). A manifest without the list (written
  before it existed) owns :data:`RESULT_NAMES`.
- The lock: :func:`folder_lock` holds an exclusive ``flock`` on the target's lock file
  ``.NAME.lock`` beside it (:func:`lock_path`) for the time a command reads and writes the
  folder (analyze, report, stress), swaps it (simulate, run, mesh -o...) or runs a study into
  it (the whole of a sweep or a speed curve). Another gearcli on the same target waits up to
  :data:`LOCK_WAIT_S` (``GEARCLI_LOCK_WAIT_S``), then refuses (at once when the holder is a
  study: those take hours); so an ``analyze`` never writes the analysis of a run that a
  ``simulate --force`` replaced meanwhile into the new run, and two sweeps never share a
  folder. Targets in one parent folder have their own locks. The lock file stays (a stable
  file: removing it would race with a process about to lock it); it holds the holder's PID.
"""

from __future__ import annotations

import contextlib
import json
import os
import threading
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
_held: dict[str, list] = {}  # locked target -> [fd, pid, thread]: re-entrant in a thread


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


def lock_path(target: str | Path) -> Path:
    """The lock file of ``target``: ``.NAME.lock`` beside it (in its parent folder)."""
    p = Path(os.path.abspath(target))
    return p.parent / f".{p.name or 'root'}.lock"


@contextlib.contextmanager
def folder_lock(target: str | Path, wait_s: float | None = None, study: bool = False):
    """Hold the lock of ``target`` (an exclusive flock on its lock file :func:`lock_path`)
    inside the block; wait for another holder up to ``wait_s`` (default :func:`lock_wait_s`),
    then refuse. A holder that is a study (``study``: a sweep or a speed curve, hours long) is
    not waited for: the others refuse at once. Re-entrant in one process, also for targets
    inside a held one (a sweep's points); where the system has no flock, nothing is locked."""
    try:
        import fcntl
    except ImportError:  # Windows: no advisory locks here
        yield
        return
    if str(target).strip() == "":  # refused by the caller, with its own message
        yield
        return
    p = Path(os.path.abspath(target))
    if study:  # the sweep makes its folder: its parent must be there to hold the lock
        with contextlib.suppress(OSError):
            p.parent.mkdir(parents=True, exist_ok=True)
    key = _key(p)
    if key is None or _covered(key):
        yield
        return
    fd = _open_lock(key)
    if fd is None:
        yield  # an unreadable parent: the write itself will say what is wrong
        return
    try:
        _acquire(fcntl, fd, p, lock_wait_s() if wait_s is None else wait_s)
        _sign(fd, study)
        _held[key] = [fd, os.getpid(), threading.get_ident()]
        try:
            yield
        finally:
            if _held.get(key, [None, None])[1] == os.getpid():
                del _held[key]
                fcntl.flock(fd, fcntl.LOCK_UN)
    finally:
        if os.getpid() == _opened_by.pop(fd, os.getpid()):
            os.close(fd)


_opened_by: dict[int, int] = {}  # lock fd -> pid that opened it


def _key(p: Path) -> str | None:
    """The target with its parent's links resolved (one lock whatever the spelling); None when
    its parent folder does not exist (nothing to lock: the target cannot exist either)."""
    try:
        return str(p.parent.resolve(strict=True) / (p.name or "root"))
    except (OSError, RuntimeError):
        return None


def _covered(key: str) -> bool:
    """``key`` or a folder above it is held by this thread (or by the process that forked
    this one: a sweep's workers write its points under the sweep's lock). Another thread
    locks for itself (two flocks of one process on their own open files exclude each
    other)."""
    k = Path(key)
    mine = [h for h, (_fd, _pid, thread) in _held.items() if thread == threading.get_ident()]
    return any(h == key or Path(h) in k.parents for h in (*mine, *_inherited))


_inherited: set[str] = set()


def _forget_in_child() -> None:
    """After fork: the parent holds the locks; the child closes its copies (a killed sweep's
    workers must not keep its lock) and works under them (:func:`_covered`)."""
    for key, (fd, _pid, _thread) in list(_held.items()):
        with contextlib.suppress(OSError):
            os.close(fd)
        _inherited.add(key)
    _held.clear()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forget_in_child)


def _open_lock(key: str) -> int | None:
    """An open file of the lock: the lock file (created, mode 0666 less the umask, and left
    for the next gearcli: removing a lock file races with a process about to lock it), or
    where it cannot be created or is not a plain file (a read-only or foreign parent, a link),
    the parent folder itself."""
    path = lock_path(key)
    nofollow = getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
    for flags in (os.O_RDWR | os.O_CREAT, os.O_RDONLY, None):
        try:
            fd = os.open(path.parent if flags is None else path,
                         (os.O_RDONLY if flags is None else flags) | nofollow, 0o666)
        except OSError:
            continue
        if flags is not None and not _plain_file(fd):
            os.close(fd)
            continue
        _opened_by[fd] = os.getpid()
        return fd
    return None


def _plain_file(fd: int) -> bool:
    import stat

    return stat.S_ISREG(os.fstat(fd).st_mode)


def _sign(fd: int, study: bool) -> None:
    """Write who holds the lock into the lock file (for the message of the one refused)."""
    with contextlib.suppress(OSError):
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"{os.getpid()} {'study' if study else command[0]}\n".encode(), 0)


def _holder(fd: int) -> tuple[str, bool]:
    """(``process PID``, whether the holder is a study) from the lock file; ("", False) for
    an unsigned one."""
    try:
        text = os.pread(fd, 200, 0).decode("utf-8", "replace").split()
    except OSError:
        return "", False
    if len(text) < 2 or not text[0].isdigit():
        return "", False
    try:  # a study's signature outlives it until the next holder signs
        os.kill(int(text[0]), 0)
        alive = True
    except PermissionError:
        alive = True
    except (OSError, OverflowError):
        alive = False
    return f" (process {text[0]})", alive and text[1] == "study"


def refuse_if_a_study_runs(target: str | Path) -> None:
    """Refuse at once, before any work, to write ``target`` while a study (a sweep, a speed
    curve) holds its lock: ``simulate --force`` into a running sweep's folder would otherwise
    solve first and be refused at the swap. Only reads the lock file's signature; it locks
    (shared, without waiting) just to confirm a live study's signature."""
    try:
        import fcntl
    except ImportError:
        return
    if str(target).strip() == "":
        return
    key = _key(Path(os.path.abspath(target)))
    if key is None or _covered(key):
        return
    try:
        fd = os.open(lock_path(key), os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0)
                     | getattr(os, "O_CLOEXEC", 0))
    except OSError:
        return
    try:
        who, is_study = _holder(fd)
        if not is_study:
            return
        try:
            fcntl.flock(fd, fcntl.LOCK_SH | fcntl.LOCK_NB)
            fcntl.flock(fd, fcntl.LOCK_UN)
        except BlockingIOError:
            raise OutputError(_study_message(Path(target), who)) from None
        except OSError:
            return
    finally:
        os.close(fd)


def _study_message(target: Path, who: str) -> str:
    return (f"{target}: a study is running there{who}, holding the lock {lock_path(target)}; "
            "wait for it to finish or choose another folder")


def _acquire(fcntl, fd: int, target: Path, wait_s: float) -> None:
    deadline = time.monotonic() + wait_s
    lock = lock_path(target)
    while True:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            return
        except BlockingIOError:
            who, is_study = _holder(fd)
            if is_study:
                raise OutputError(_study_message(target, who)) from None
            if time.monotonic() >= deadline:
                raise OutputError(f"{target}: another gearcli is working there{who}, holding "
                                  f"the lock {lock} (waited {wait_s:g} s); try again when it "
                                  "has finished") from None
            time.sleep(_POLL_S)
        except OSError:
            return  # a file system without locks: unlocked, as before
