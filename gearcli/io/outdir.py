"""Result folders written atomically: complete earlier results or complete new ones, never a mix.

Files are written into a hidden temporary folder ``.NAME.PID.XXXXXXXX.tmp`` beside the target,
which replaces the target only when everything is written. Existing results are replaced only
with ``force``; a folder that holds other files is never replaced. The earlier folder is
swapped out in one step where the system allows it (Linux ``renameat2(RENAME_EXCHANGE)``),
else moved aside and the new one moved in.

``force`` replaces gearcli's results, never the user's files: whatever else the earlier folder
holds (notes, a figure written there with ``--plot``: every name not in :data:`RESULT_NAMES`)
is moved into the new folder right after the swap, keeping owners, modes and links, with
SIGINT, SIGTERM and SIGHUP held back meanwhile; then the earlier results are deleted. A new
folder gets the permissions of an ordinary new folder (the umask), not mkdtemp's 0700; a
replacing one the earlier folder's. A failure or a signal (see
:func:`gearcli.cli.common.handle_errors`) removes the temporary folder unless it holds the
user's files; such a folder, left by a write that was killed or could not move them, makes
later writes to the target refuse and name it (:func:`stranded`).
"""

from __future__ import annotations

import contextlib
import ctypes
import ctypes.util
import os
import re
import shutil
import stat
import sys
import tempfile
from pathlib import Path

from gearcli.errors import OutputError
from gearcli.interrupts import deferred
from gearcli.io.files import check_writable, record_outputs, umask
from gearcli.io.owner import RESULT_NAMES  # noqa: F401  (importers: outdir.RESULT_NAMES)

#: A folder holding this file is a gearcli result folder.
MARKER = "manifest.json"



def check_target(target: str | Path, force: bool) -> Path:
    """Refuse targets that would lose data or cannot be replaced; returns the target as a
    Path."""
    if str(target).strip() == "":
        raise OutputError("-o '': empty path; expected the name of a results folder")
    p = Path(target)
    from gearcli.io.owner import refuse_if_a_study_runs

    refuse_if_a_study_runs(p)  # a running sweep's folder: at once, not after the work
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
    parent = p.parent if str(p.parent) else Path(".")
    kept = stranded(parent, p.name) if parent.is_dir() else []
    if kept:
        raise OutputError(f"{p}: {kept[0]} beside it holds your files from the earlier results "
                          "folder (an interrupted or failed --force write moved the folder "
                          "aside); move them where they belong, delete that folder, then run "
                          "again")
    check_writable(p)
    if p.is_dir() and any(p.iterdir()):
        if not (p / MARKER).exists():
            raise OutputError(f"{p}: folder holds other files; expected a new or empty folder "
                              "or an earlier gearcli results folder")
        if not force:
            raise OutputError(f"{p}: already holds results; use --force to replace them")
    return p


@contextlib.contextmanager
def atomic_dir(target: str | Path, force: bool, producer: dict | None = None):
    """Yield a temporary folder; on success it becomes ``target`` (replacing it with force).
    The manifest written into it gets the list of its files and ``producer``
    (:mod:`gearcli.io.owner`); the swap holds the target's lock."""
    from gearcli.io.owner import MANIFEST, command, folder_lock
    from gearcli.io.owner import producer as make_producer

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
        if (tmp / MANIFEST).is_file():
            record_outputs(tmp, [q.name for q in tmp.iterdir()],
                           producer or make_producer(command[0]))
        with folder_lock(p):
            check_target(p, force)  # nothing else appeared there meanwhile
            _install(tmp, p)
    except BaseException:
        _discard(tmp)
        raise


def _discard(tmp: Path) -> None:
    """Remove the temporary folder of a failed write, unless it holds the user's files (after
    the swap of :func:`_install` it is the earlier folder: what could not be moved stays)."""
    for q in (tmp, tmp.with_name(tmp.name + ".old")):  # .old: the rename fallback's
        try:
            if q.is_dir() and not q.is_symlink() and not user_entries(q):
                _remove_tree(q)
        except OSError:
            pass


def remove_stale(parent: Path, name: str) -> list[Path]:
    """Remove the temporary folders ``.NAME.PID.XXXXXXXX.tmp`` (and ``.tmp.old``) that a
    killed gearcli left beside ``parent/NAME`` (kill -9 cannot be cleaned up at the time):
    those whose process ``PID`` is gone and that hold gearcli's results only. Folders of a
    running process, of another target (``.NAME.2024.PID.X.tmp`` belongs to ``NAME.2024``),
    or holding anything else (the user's files of a replaced folder, see :func:`_install`)
    are left alone. Returns the removed paths."""
    removed = []
    for q in _dead_temporaries(parent, name):
        try:
            if user_entries(q):
                continue
        except OSError:
            continue
        _remove_tree(q)
        removed.append(q)
    return removed


def stranded(parent: Path, name: str) -> list[Path]:
    """Temporary folders of ended gearcli processes beside ``parent/NAME`` that hold the
    user's files: an earlier results folder swapped out by a ``--force`` write that was killed
    (or could not move them) before they were back in ``NAME`` (:func:`_install`)."""
    out = []
    for q in _dead_temporaries(parent, name):
        with contextlib.suppress(OSError):
            if user_entries(q):
                out.append(q)
    return sorted(out)


def _dead_temporaries(parent: Path, name: str) -> list[Path]:
    """The folders ``.NAME.PID.XXXXXXXX.tmp`` / ``.tmp.old`` of processes that have ended."""
    pattern = re.compile(rf"\.{re.escape(name)}\.(\d+)\.[A-Za-z0-9_]+\.tmp(\.old)?")
    out = []
    for q in parent.glob(f".{glob_escape(name)}.*.tmp*"):
        m = pattern.fullmatch(q.name)
        if m is not None and q.is_dir() and not q.is_symlink() and not _alive(int(m.group(1))):
            out.append(q)
    return out


def _remove_tree(q: Path) -> None:
    """Delete a folder of gearcli's results, also where a read-only folder inside (or the
    folder itself) would stop ``shutil.rmtree``: write permission is added where needed."""
    def retry(func, path, _exc):
        try:
            parent = os.path.dirname(path)
            os.chmod(parent, os.stat(parent).st_mode | 0o700)
            if os.path.isdir(path) and not os.path.islink(path):
                os.chmod(path, os.stat(path).st_mode | 0o700)
            func(path)
        except OSError:
            pass

    with contextlib.suppress(OSError):
        os.chmod(q, os.stat(q).st_mode | 0o700)
    if sys.version_info >= (3, 12):
        shutil.rmtree(q, onexc=retry)
    else:  # onerror: deprecated from 3.12 on
        shutil.rmtree(q, onerror=retry)


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
    """The entries at the top of a results folder that gearcli did not write (sorted): not
    listed in its manifest's ``outputs`` (:func:`gearcli.io.owner.owned_names`; without the
    list, not in :data:`RESULT_NAMES`), nor the temporary ``.NAME.XXXXXXXX.tmp`` of one of
    them (io.files.write_atomic, left by a killed write)."""
    from gearcli.io.owner import owned_names

    owned = owned_names(folder, RESULT_NAMES)
    return sorted(q for q in folder.iterdir()
                  if q.name not in owned and not _result_temporary(q.name, owned))


def _result_temporary(name: str, owned=RESULT_NAMES) -> bool:
    m = re.fullmatch(r"\.(.+)\.[a-z0-9_]{8}\.tmp", name)  # tempfile.mkstemp's 8 characters
    return m is not None and m.group(1) in owned


def _move_user_entries(old: Path, new: Path) -> list[str]:
    """Move the user's entries of the replaced results folder ``old`` into ``new`` (renames
    in one folder: owners, modes, links and hard links stay; a folder without write
    permission gets it for the move, then its mode back); returns the names that could not
    be moved."""
    left = []
    for q in user_entries(old):
        dest = new / q.name
        mode = None
        try:
            if dest.exists() or dest.is_symlink():
                raise FileExistsError(q.name)  # never over a new result
            if q.is_dir() and not q.is_symlink() and not os.access(q, os.W_OK):
                mode = stat.S_IMODE(q.stat().st_mode)  # renaming a folder rewrites its ".."
                os.chmod(q, mode | 0o200)
            os.replace(q, dest)
        except OSError:
            left.append(q.name)
            dest = q
        if mode is not None:
            with contextlib.suppress(OSError):
                os.chmod(dest, mode)
    return left


def _apply_mode(st: os.stat_result, new: Path) -> None:
    """Give ``new`` the permission bits and group of the folder it replaced (best effort: a
    group the user does not belong to stays the default)."""
    with contextlib.suppress(OSError):
        os.chmod(new, stat.S_IMODE(st.st_mode))
        if new.stat().st_gid != st.st_gid:
            os.chown(new, -1, st.st_gid)


def _install(tmp: Path, p: Path) -> None:
    """Move the finished ``tmp`` to ``p``. An earlier ``p`` is swapped out whole and the
    user's entries in it move into the new folder, with signals held back
    (:func:`gearcli.interrupts.deferred`); then gearcli's earlier results are deleted, what a
    program working inside the earlier folder wrote meanwhile moves over too
    (:func:`_empty_out`), and the new folder gets the earlier one's mode. Entries that cannot
    be moved stay in the swapped-out folder, which is then kept and named in the error (and
    later writes refuse until it is dealt with, :func:`stranded`)."""
    if not p.exists():
        try:
            os.replace(tmp, p)
        except OSError as exc:
            raise OutputError(f"{p}: cannot move the new results into place "
                              f"({exc.strerror})") from None
        return
    with deferred():
        try:
            st = p.stat()
            if _exchange(tmp, p):  # p is now the new folder, tmp the old one
                old = tmp
            else:
                old = tmp.with_name(tmp.name + ".old")
                os.replace(p, old)
                try:
                    os.replace(tmp, p)
                except BaseException:
                    os.replace(old, p)  # put the earlier results back
                    raise
        except OSError as exc:
            raise OutputError(f"{p}: cannot move the new results into place ({exc.strerror}); "
                              "the earlier results are unchanged") from None
        with contextlib.suppress(OSError):  # moving out of a read-only earlier folder
            os.chmod(old, os.stat(old).st_mode | 0o700)
        left = _move_user_entries(old, p)
        _apply_mode(st, p)  # after the moves: the earlier folder may have been read-only
    if not left:
        left = _empty_out(old, p)
    if left:
        raise OutputError(f"{p}: new results written, but {len(left)} of your files could not "
                          f"be moved over from the earlier folder; they are in {old}")


def _empty_out(old: Path, new: Path, passes: int = 3) -> list[str]:
    """Delete gearcli's earlier results in ``old``, move over what appeared there since (a
    program working inside the folder), and remove ``old`` once it is empty; returns the
    names still left in it (then it stays, named by the caller and by :func:`stranded`)."""
    from gearcli.io.owner import owned_names

    owned = owned_names(old, RESULT_NAMES)
    for q in old.iterdir():
        if q.name in owned or _result_temporary(q.name, owned):
            if q.is_dir() and not q.is_symlink():
                _remove_tree(q)
            else:
                with contextlib.suppress(OSError):
                    q.unlink()
    for _ in range(passes):
        left = _move_user_entries(old, new)
        try:
            old.rmdir()
            return []
        except OSError:
            continue
    return left or [q.name for q in user_entries(old)]


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
