"""Result folders written atomically: complete earlier results or complete new ones, never a mix.

Files are written into a hidden temporary folder beside the target, which replaces the target
only when everything is written (``os.replace``). Existing results are replaced only with
``force``; a folder that holds other files is never replaced.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from pathlib import Path

from gearcli.errors import OutputError

#: A folder holding this file is a gearcli result folder.
MARKER = "manifest.json"


def check_target(target: str | Path, force: bool) -> Path:
    """Refuse targets that would lose data; returns the target as a Path."""
    p = Path(target)
    if p.exists() and not p.is_dir():
        raise OutputError(f"{p}: exists and is not a folder; expected a results folder")
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
        tmp = Path(tempfile.mkdtemp(prefix=f".{p.name}.", suffix=".tmp", dir=parent))
    except OSError as exc:
        raise OutputError(f"{p}: cannot create the results folder ({exc.strerror})") from None
    try:
        yield tmp
        if p.exists():
            old = tmp.with_name(tmp.name + ".old")
            os.replace(p, old)
            os.replace(tmp, p)
            shutil.rmtree(old, ignore_errors=True)
        else:
            os.replace(tmp, p)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
