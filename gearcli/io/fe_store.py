"""The on-disk store of the finite-element influence coefficients (docs/theory.md,
"Finite-element check of the tooth compliance"): one ``<key>.npz`` per gear model in
``<user cache>/gearcli/fe`` (gearcli/usercache.py), the key the geometry hash of
:func:`gearcli.model.fe.tooth.geometry_key`.

Handed to :class:`gearcli.model.fe.ComplianceCache` as its ``load``/``store`` callbacks (the
model layer does no I/O). Writes are atomic (a temporary file renamed over the entry); an entry
that cannot be read (truncated, corrupt, another format) is ignored and recomputed; without a
writable cache folder nothing is stored.
"""

from __future__ import annotations

import os
import re
import tempfile
from pathlib import Path

import numpy as np

from gearcli import usercache

__all__ = ["FEStore"]

_KEY = re.compile(r"^[0-9a-f]{8,64}$")  # geometry_key: a hex digest


class FEStore:
    """``load(key) -> dict | None`` and ``store(key, record)`` over a folder (module notes);
    ``folder`` None: the user cache's ``gearcli/fe`` (None there too: a store that keeps
    nothing)."""

    def __init__(self, folder: str | Path | None = None) -> None:
        self.folder = Path(folder) if folder is not None else usercache.folder("fe")
        if self.folder is not None:
            try:
                self.folder.mkdir(parents=True, exist_ok=True)
            except OSError:
                self.folder = None

    def _path(self, key: str) -> Path | None:
        if self.folder is None or not _KEY.match(key):
            return None
        return self.folder / f"{key}.npz"

    def load(self, key: str) -> dict | None:
        """The stored record of ``key``; None when absent or unreadable."""
        path = self._path(key)
        if path is None or not path.is_file():
            return None
        try:
            with np.load(path, allow_pickle=False) as data:
                return {name: data[name] for name in data.files}
        except Exception:  # noqa: BLE001 - a corrupt entry is a cache miss, never an error
            return None

    def store(self, key: str, record: dict) -> None:
        """Write ``record`` (numbers and arrays) under ``key``, atomically; a failure to write
        leaves the store as it was."""
        path = self._path(key)
        if path is None:
            return
        fd, tmp = tempfile.mkstemp(prefix=f".{key}.", suffix=".tmp", dir=path.parent)
        try:
            with os.fdopen(fd, "wb") as f:
                np.savez(f, **{k: np.asarray(v) for k, v in record.items()})
            os.replace(tmp, path)
        except OSError:
            Path(tmp).unlink(missing_ok=True)
