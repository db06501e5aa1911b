"""Result folders written atomically: complete earlier results or complete new ones, never a mix.

Files are written into a hidden temporary folder beside the target, which replaces the target
only when everything is written. Existing results are replaced only with ``force``; a folder
that holds other files is never replaced. ``force`` replaces gearcli's results, never the
user's files: whatever else an earlier results folder holds (notes, a figure written there
with ``--plot``) is copied into the new folder before the swap (:data:`RESULT_NAMES`). The
earlier folder is swapped out in one step where
the system allows it (Linux ``renameat2(RENAME_EXCHANGE)``), else moved aside, the new one moved
in, the old one deleted. A failure or a signal (SIGTERM, SIGHUP, Ctrl-C: see
:func:`gearcli.cli.common.handle_errors`) removes the temporary folder; the folder gets the
permissions of an ordinary new folder (the umask), not mkdtemp's 0700.
"""

from __future__ import annotations

import contextlib
import ctypes
import ctypes.util
import os
import shutil
import tempfile
from pathlib import Path

from gearcli.errors import OutputError
from gearcli.io.files import umask

#: A folder holding this file is a gearcli result folder.
MARKER = "manifest.json"

#: What gearcli writes at the top of a results folder: simulate and run (pipeline/outputs.py),
#: analyze (analysis_io.ANALYSIS_FILES), stress (stress.STRESS_FILES), report, mesh -o
#: (pipeline/mesh.py) and speed-curve studies (pipeline/speed_curve.py). With ``force`` these
#: go with the earlier results and everything else is carried over into the new folder;
#: tests/cli/test_force_keeps_user_files.py checks the list against what the commands write
#: (a name missing here would only be carried over, stale, never lost).
RESULT_NAMES = frozenset({
    MARKER, "summary.json", "timeseries.csv", "timeseries.parquet", "zoom.csv",
    "analysis.json", "spectrum.csv", "harmonics.csv", "stress.csv", "stress.json",
    "report.html", "report.md", "figures", "mesh.json", "mesh.csv", "mesh.png",
    "summary.csv", "speed_curve.json", "speed_curve.png",
})


def check_target(target: str | Path, force: bool) -> Path:
    """Refuse targets that would lose data or cannot be replaced; returns the target as a
    Path."""
    if str(target).strip() == "":
        raise OutputError("-o '': empty path; expected the name of a results folder")
    p = Path(target)
    if p.is_symlink():
        state = "a dangling symbolic link" if not p.exists() else "a symbolic link"
        raise OutputError(f"{p}: is {state}; expected a folder name (give the link's target "
                          "itself)")
    if p.exists() and not p.is_dir():
        raise OutputError(f"{p}: exists and is not a folder; expected a results folder")
    if p.is_dir():
        here = p.resolve()
        if here == Path.cwd().resolve() or here in Path.cwd().resolve().parents \
                or here.parent == here:
            raise OutputError(f"{p}: is the current folder or one of its parents; expected "
                              "a new folder name")
    if p.is_dir() and any(p.iterdir()):
        if not (p / MARKER).exists():
            raise OutputError(f"{p}: folder holds other files; expected a new or empty folder "
                              "or an earlier gearcli results folder")
        if not force:
            raise OutputError(f"{p}: already holds results; use --force to replace them")
    return p


@contextlib.contextmanager
def atomic_dir(target: str | Path, force: bool):
    """Yield a temporary folder; on success it becomes ``target`` (replacing it with force)."""
    p = check_target(target, force)
    parent = p.parent if str(p.parent) else Path(".")
    try:
        parent.mkdir(parents=True, exist_ok=True)
        remove_stale(parent, p.name)
        tmp = Path(tempfile.mkdtemp(prefix=f".{p.name}.{os.getpid()}.", suffix=".tmp",
                                    dir=parent))
        os.chmod(tmp, 0o777 & ~umask())
    except OSError as exc:
        raise OutputError(f"{p}: cannot create the results folder ({exc.strerror})") from None
    try:
        yield tmp
        check_target(p, force)  # nothing else appeared there meanwhile
        _install(tmp, p)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise


def remove_stale(parent: Path, name: str) -> list[Path]:
    """Remove the temporary folders ``.NAME.PID.*.tmp`` (and ``*.tmp.old``) that a killed
    gearcli left beside ``parent/NAME`` (kill -9 cannot be cleaned up at the time): those whose
    process ``PID`` is gone. Folders of a running process, or not named so, are left alone.
    Returns the removed paths."""
    removed = []
    for q in parent.glob(f".{glob_escape(name)}.*.tmp*"):
        rest = q.name[len(name) + 2:]
        pid_text = rest.split(".", 1)[0]
        if not (q.is_dir() and pid_text.isdigit() and (q.name.endswith(".tmp")
                                                       or q.name.endswith(".tmp.old"))):
            continue
        if _alive(int(pid_text)):
            continue
        shutil.rmtree(q, ignore_errors=True)
        removed.append(q)
    return removed


def glob_escape(text: str) -> str:
    """``text`` with glob's special characters taken literally."""
    import glob

    return glob.escape(text)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process
        return True
    return True


def user_entries(folder: Path) -> list[Path]:
    """The entries at the top of a results folder that gearcli did not write (sorted)."""
    return sorted(q for q in folder.iterdir() if q.name not in RESULT_NAMES)


def _carry_over(old: Path, new: Path) -> None:
    """Copy the user's entries of the earlier results folder ``old`` into ``new`` (copies, so
    that ``old`` stays complete until the swap; links stay links)."""
    for q in user_entries(old):
        dest = new / q.name
        if dest.exists() or dest.is_symlink():
            continue  # cannot happen with RESULT_NAMES complete; never overwrite new results
        try:
            if q.is_symlink():
                os.symlink(os.readlink(q), dest)
            elif q.is_dir():
                shutil.copytree(q, dest, symlinks=True)
            else:
                shutil.copy2(q, dest)
        except OSError as exc:
            raise OutputError(f"{old}: cannot carry {q.name} (not written by gearcli) over into "
                              f"the new results ({exc}); the earlier results are unchanged; "
                              "move it out and run again") from None


def _install(tmp: Path, p: Path) -> None:
    """Move the finished ``tmp`` to ``p``; an earlier ``p`` is removed only afterwards, and
    what else it held is carried over first (:func:`_carry_over`)."""
    try:
        if not p.exists():
            os.replace(tmp, p)
            return
        _carry_over(p, tmp)
        if _exchange(tmp, p):  # p is now the new folder, tmp the old one
            shutil.rmtree(tmp, ignore_errors=True)
            return
        old = tmp.with_name(tmp.name + ".old")
        os.replace(p, old)
        try:
            os.replace(tmp, p)
        except BaseException:
            os.replace(old, p)  # put the earlier results back
            raise
        shutil.rmtree(old, ignore_errors=True)
    except OSError as exc:
        raise OutputError(f"{p}: cannot move the new results into place ({exc.strerror}); "
                          "the earlier results are unchanged") from None


_RENAME_EXCHANGE = 2


def _exchange(a: Path, b: Path) -> bool:
    """Swap two paths atomically (Linux renameat2 RENAME_EXCHANGE); False where unsupported."""
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or None, use_errno=True)
        renameat2 = libc.renameat2
    except (OSError, AttributeError):
        return False
    at_fdcwd = -100
    renameat2.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p,
                          ctypes.c_uint]
    rc = renameat2(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), _RENAME_EXCHANGE)
    return rc == 0
