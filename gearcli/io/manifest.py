"""Provenance of a results folder: versions, case hash, resolved case, command line."""

from __future__ import annotations

import hashlib
import platform
import sys
from importlib import metadata

from gearcli.results.version import RESULTS_SCHEMA_VERSION  # noqa: F401  (the manifest's too)


def versions() -> dict[str, str]:
    out = {"python": platform.python_version(), "platform": platform.platform()}
    for dist in ("gearcli", "numpy", "numba", "scipy", "pydantic", "pint"):
        try:
            out[dist] = metadata.version(dist)
        except metadata.PackageNotFoundError:
            out[dist] = "not installed"
    return out


def sha256_of(path) -> str:
    with open(path, "rb") as fh:
        return hashlib.sha256(fh.read()).hexdigest()


def manifest(source, resolved_case: dict, overrides: list[str] | None) -> dict:
    """The manifest of a results folder. ``source`` is the case's
    :class:`gearcli.case.yamlsrc.Source`: its hash is that of the bytes that were parsed (the
    file is not read again: it may be a pipe, or have changed or gone since)."""
    import datetime

    return {
        "gearcli_manifest": 1,
        "created_utc": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "versions": versions(),
        "case_file": str(source.file),
        "case_sha256": source.sha256 or None,
        "case_text": "\n".join(source.lines) + "\n" if source.lines else None,
        "overrides": list(overrides or []),
        "command_line": sys.argv,
        "resolved_case": resolved_case,
        "units": "internal: mm, N, s, t (tonne), rad; CSV column names carry units",
    }
