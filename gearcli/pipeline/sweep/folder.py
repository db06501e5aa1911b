"""The folder of a sweep: one study's (its identity in the manifest, io.owner), no links where
the sweep writes, ``--force`` over gearcli's files only (docs/theory.md §8.1)."""

from __future__ import annotations

import contextlib
from pathlib import Path

from gearcli.errors import OutputError
from gearcli.pipeline.sweep.study import Study

SUMMARY = "summary.csv"


@contextlib.contextmanager
def study_lock(out: Path):
    """Hold ``out`` for the whole of a study (a sweep or a speed curve): the lock of
    :func:`gearcli.io.owner.folder_lock`, not waited for; a second study into the folder, or a
    command replacing it, is refused at once while this one runs (its rows never mix)."""
    from gearcli.io.owner import folder_lock

    with folder_lock(out, wait_s=0, study=True):
        yield


def claim_folder(out: Path, study: Study, columns: list[str], force: bool) -> dict:
    """Refuse links where the sweep writes, and with ``force`` files gearcli did not write
    there; returns the study's producer record (io.owner: the caller refuses a folder of
    another producer, :func:`gearcli.io.owner.check_producer`)."""
    from gearcli.io.files import refuse_links
    from gearcli.io.owner import producer, study_identity

    for name in (SUMMARY, "points", "trends.csv", "trends.md", "speed_sweep.png"):
        refuse_links(out / name)
    for q in out.glob("trend_*.png"):
        refuse_links(q)
    prod = producer("sweep", study_identity(study.name, study.design, columns,
                                            study.base_case_json))
    if force and out.is_dir():  # --force replaces gearcli's files only
        from gearcli.io.owner import check_owned, read_manifest

        if read_manifest(out) is not None:
            check_owned(out, [SUMMARY, "points", "trends.csv", "trends.md"])
        elif (out / SUMMARY).is_file() and not _is_sweep_summary(out / SUMMARY):
            raise OutputError(f"{out / SUMMARY}: not a sweep's summary (gearcli did not write "
                              "it); move it away, gearcli does not replace it")
    return prod


def _is_sweep_summary(path: Path) -> bool:
    """A summary.csv that a sweep wrote (its header: point, ..., case_hash)."""
    with open(path, encoding="utf-8", errors="replace") as fh:
        header = fh.readline().strip()
    return header.startswith("point,") and header.endswith(",case_hash")
