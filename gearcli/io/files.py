"""Atomic file writes that never silently overwrite existing results."""

from __future__ import annotations

import functools
import os
import tempfile
from pathlib import Path

from gearcli.errors import OutputError


def write_new_text(path: str | Path, text: str) -> None:
    """Write ``text`` to ``path``, refusing if it exists; atomic (temp file + link)."""
    p = Path(path)
    if p.exists():
        raise OutputError(f"{p}: already exists; expected a new path (gearcli never overwrites it)")
    if not p.parent.exists():
        raise OutputError(f"{p}: folder {p.parent} does not exist; expected an existing folder")
    tmp = _temp_with(p, text.encode("utf-8"))
    try:
        os.link(tmp, p)  # fails if p appeared meanwhile: no race, no overwrite
    except FileExistsError:
        raise OutputError(f"{p}: already exists; expected a new path") from None
    finally:
        os.unlink(tmp)


def check_no_earlier(folder: str | Path, names, force: bool, what: str) -> None:
    """Refuse to rewrite the files ``names`` of ``folder`` (an earlier ``what``) without
    ``force``: existing results are never replaced silently. Call before the work."""
    earlier = [n for n in names if (Path(folder) / n).exists()]
    if earlier and not force:
        raise OutputError(f"{folder}: already holds {', '.join(earlier)} (an earlier {what}); "
                          "use --force to replace them")


def check_new_file(path: str | Path | None, force: bool, option: str) -> None:
    """Refuse to replace an existing file named by ``option`` (e.g. ``--plot``) without
    ``force``; refuse a folder or a path in a missing folder. Call before the work."""
    if path is None:
        return
    p = Path(path)
    if str(path).strip() == "":
        raise OutputError(f"{option} '': empty path; expected a file name")
    if p.is_dir():
        raise OutputError(f"{option} {p}: is a folder; expected a file name")
    if (p.exists() or p.is_symlink()) and not force:
        raise OutputError(f"{option} {p}: already exists; use --force to replace it")
    if not p.parent.is_dir():
        raise OutputError(f"{option} {p}: folder {p.parent} does not exist; expected an "
                          "existing folder")


def save_figure(fig, path: str | Path, dpi: int) -> None:
    """Write a matplotlib figure atomically in the format of the path's suffix (.png, .svg,
    .pdf; none: png) at ``dpi``."""
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format=Path(path).suffix.lower().lstrip(".") or "png", dpi=dpi)
    write_atomic(path, buf.getvalue())


def write_atomic(path: str | Path, data: bytes | str) -> None:
    """Write ``data`` to ``path`` via a temp file in the same folder and an atomic rename."""
    p = Path(path)
    raw = data.encode("utf-8") if isinstance(data, str) else data
    tmp = _temp_with(p, raw)
    os.replace(tmp, p)


def _temp_with(p: Path, raw: bytes) -> str:
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".tmp", dir=p.parent or ".")
    except OSError as exc:
        raise OutputError(f"{p}: cannot write ({exc.strerror})") from None
    with os.fdopen(fd, "wb") as fh:
        fh.write(raw)
        fh.flush()
        os.fsync(fh.fileno())
    os.chmod(tmp, 0o666 & ~umask())  # mkstemp makes 0600; results are ordinary files
    return tmp


@functools.cache
def umask() -> int:
    """The process umask, read once (os.umask can only be read by setting it)."""
    mask = os.umask(0)
    os.umask(mask)
    return mask
