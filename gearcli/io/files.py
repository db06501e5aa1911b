"""The one writer of gearcli's output files (docs/theory.md §8, "Writing results").

Every file is written into a temporary file in its own folder, flushed, fsync'ed, closed (each
step checked: a full disk or a file-size limit is an error, never a short file) and renamed
over the target in one step; a failure removes the temporary file. A target that is a symbolic
link, or a folder on the way from ``within`` (the results folder) to it that is one, is
refused: gearcli never writes through a link, into or out of a results folder."""

from __future__ import annotations

import contextlib
import errno
import functools
import json
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
    check_writable(Path(folder) / "x")  # before the work: a read-only folder
    earlier = [n for n in names if (Path(folder) / n).exists()]
    if earlier and force:
        from gearcli.io.owner import check_owned

        check_owned(folder, earlier)  # --force replaces gearcli's files only
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
    check_writable(p)


def check_suffix(option: str, path: Path, suffixes: tuple[str, ...]) -> None:
    """A file an option writes is named for what it holds (``--force`` then never replaces a
    results folder's summary.json by a report or a sound)."""
    if Path(path).suffix.lower() not in suffixes:
        names = (", ".join(suffixes[:-1]) + " or " + suffixes[-1] if len(suffixes) > 1
                 else suffixes[0])
        raise OutputError(f"{option} {path}: expected a file name ending in {names}")


def check_writable(p: str | Path) -> None:
    """Refuse, before any work, a target whose nearest existing folder cannot be written
    (a read-only file system or folder): a probe folder is made and removed there."""
    p = Path(p)
    here = p.parent if str(p.parent) else Path(".")
    while not here.exists() and here != here.parent:
        here = here.parent
    if not here.is_dir():
        return  # not a folder: the caller's own checks say what is wrong
    try:
        os.rmdir(tempfile.mkdtemp(prefix=".gearcli-probe.", dir=here))
    except OSError as exc:
        raise OutputError(f"{p}: cannot write in {here} ({exc.strerror}); choose a writable "
                          "folder") from None


def write_stdout(text: str) -> None:
    """Write ``text`` to standard output, all of it or an error: the bytes go to the stream's
    binary layer in a loop that checks each write's count (with ``python -u`` /
    PYTHONUNBUFFERED the text layer writes straight to the file and drops the rest of a short
    write: a file-size limit or a full disk gave exit 0 and a truncated file)."""
    import sys

    stream = sys.stdout
    binary = getattr(stream, "buffer", None)
    if binary is None:  # a text-only stream (a test's capture)
        stream.write(text)
        stream.flush()
        return
    stream.flush()
    data = text.encode(getattr(stream, "encoding", None) or "utf-8",
                       getattr(stream, "errors", None) or "strict")
    view = memoryview(data)
    while view:
        n = binary.write(view)
        if not n:  # None: a non-blocking stream that would block; 0: nothing written
            raise OSError(errno.EIO, "short write to the standard output")
        view = view[n:]
    binary.flush()


def save_figure(fig, path: str | Path, dpi: int, within: str | Path | None = None) -> None:
    """Write a matplotlib figure atomically in the format of the path's suffix (.png, .svg,
    .pdf; none: png) at ``dpi`` (:func:`write_atomic`)."""
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format=Path(path).suffix.lower().lstrip(".") or "png", dpi=dpi)
    write_atomic(path, buf.getvalue(), within)


def refuse_links(path: str | Path, within: str | Path | None = None) -> Path:
    """Refuse ``path`` when it is a symbolic link, or when a folder between ``within`` and it
    is one (``within`` itself, the folder the user named, may be a link); returns it."""
    p = Path(path)
    if p.is_symlink():
        raise OutputError(f"{p}: is a symbolic link; gearcli does not write through links "
                          "(remove it or choose another folder)")
    if within is not None:
        root = Path(within)
        try:
            rel = p.parent.relative_to(root)
        except ValueError:
            raise OutputError(f"{p}: is outside the results folder {root}") from None
        q = root
        for part in rel.parts:
            q = q / part
            if q.is_symlink():
                raise OutputError(f"{q}: is a symbolic link; gearcli does not write through "
                                  "links out of the results folder (remove it or choose "
                                  "another folder)")
    return p


def make_folder(path: str | Path, within: str | Path) -> Path:
    """Create the folder ``path`` inside ``within`` (parents too), refusing links on the
    way (:func:`refuse_links`)."""
    p = Path(path)
    refuse_links(p / "x", within)
    try:
        p.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(f"{p}: cannot create the folder ({exc.strerror})") from None
    refuse_links(p / "x", within)  # nothing replaced it by a link meanwhile
    return p


def write_atomic(path: str | Path, data: bytes | str, within: str | Path | None = None) -> None:
    """Write ``data`` to ``path`` via a temp file in the same folder and an atomic rename;
    links refused (:func:`refuse_links`), every step checked, no temp file left on failure."""
    p = refuse_links(path, within)
    raw = data.encode("utf-8") if isinstance(data, str) else data
    tmp = _temp_with(p, raw)
    try:
        refuse_links(p, within)
        os.replace(tmp, p)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def write_atomic_files(files: dict, within: str | Path | None = None) -> None:
    """Write a set of files ({path: data}) that belong together (analyze's analysis.json,
    spectrum.csv and harmonics.csv): every one to its temporary file first, then the renames;
    a full disk while writing any of them changes none (no temporary file left), rather than
    leaving a new analysis.json beside the old spectrum.csv."""
    staged: list[tuple[str, Path]] = []
    try:
        for path, data in files.items():
            p = refuse_links(path, within)
            staged.append((_temp_with(p, data.encode("utf-8") if isinstance(data, str)
                                      else data), p))
        for _tmp, p in staged:
            refuse_links(p, within)
        for tmp, p in staged:
            os.replace(tmp, p)
    except BaseException:
        for tmp, _p in staged:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
        raise


def _temp_with(p: Path, raw: bytes) -> str:
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".tmp", dir=p.parent or ".")
    except OSError as exc:
        raise OutputError(f"{p}: cannot write ({exc.strerror})") from None
    try:
        with os.fdopen(fd, "wb") as fh:  # the close is checked too (it raises on failure)
            view = memoryview(raw)
            while view:  # a short write (a file-size limit) is retried, then raises
                n = fh.raw.write(view) if hasattr(fh, "raw") else fh.write(view)
                if not n:
                    raise OSError(errno.EIO, "short write", str(p))
                view = view[n:]
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o666 & ~umask())  # mkstemp makes 0600; results are ordinary files
    except BaseException as exc:  # a full disk, a signal: no hidden leftover
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        if isinstance(exc, OSError):
            raise OutputError(f"{p}: cannot write ({exc.strerror or exc}); nothing was "
                              "changed") from None
        raise
    return tmp


def record_outputs(folder: str | Path, names, prod: dict | None = None) -> None:
    """Add ``names`` to the ``outputs`` of ``folder``'s manifest (and set its producer when
    given); a folder without a manifest gets one naming the producer."""
    from gearcli.io.owner import MANIFEST, RESULT_NAMES, read_manifest

    doc = read_manifest(folder) or {"gearcli_manifest": 1}
    listed = doc.get("outputs") if isinstance(doc.get("outputs"), list) else None
    if listed is None:  # an older manifest: the result names its folder holds
        listed = [q.name for q in Path(folder).iterdir() if q.name in RESULT_NAMES]
    doc["outputs"] = sorted((set(listed) | {str(n) for n in names}) - {MANIFEST})
    if prod is not None:
        doc["producer"] = prod
    write_atomic(Path(folder) / MANIFEST, json.dumps(doc, indent=2) + "\n", folder)


@functools.cache
def umask() -> int:
    """The process umask, read once (os.umask can only be read by setting it)."""
    mask = os.umask(0)
    os.umask(mask)
    return mask
