"""Cache of FE influence coefficients (tooth compliances) per geometry, in memory and beyond.

The key is :func:`gearcli.model.fe.tooth.geometry_key`: a hash of the generating data, the
contact radii, the bore, the material, the plane state and the mesh control, so a change of
any of them is a new entry. The model layer does no I/O: a persistent (on-disk) store is two
callbacks handed in from above (the CLI or io layer), ``load(key) -> dict | None`` and
``store(key, dict)``; the dict holds only numbers and numpy arrays (``np.savez`` friendly).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from gearcli.model.fe.tooth import FEToothCompliance

__all__ = ["ComplianceCache", "DEFAULT_CACHE", "to_record", "from_record"]


def to_record(c: FEToothCompliance) -> dict:
    """Plain dict of arrays and numbers for a persistent store."""
    return {"radius_mm": c.radius_mm, "compliance_mm2_N": c.compliance_mm2_N,
            "depth_mm": c.depth_mm, "n_dofs": c.n_dofs, "n_teeth": c.n_teeth,
            "bore_diameter_mm": c.bore_diameter_mm, "plane_strain": c.plane_strain,
            "seconds": c.seconds}


def from_record(rec: dict) -> FEToothCompliance:
    """Inverse of :func:`to_record` (accepts numpy scalars and 0-d arrays)."""
    return FEToothCompliance(
        np.asarray(rec["radius_mm"], float), np.asarray(rec["compliance_mm2_N"], float),
        float(rec["depth_mm"]), int(rec["n_dofs"]), int(rec["n_teeth"]),
        float(rec["bore_diameter_mm"]), bool(rec["plane_strain"]), float(rec["seconds"]))


@dataclass
class ComplianceCache:
    """In-memory cache with optional persistent callbacks (module notes)."""

    load: Callable[[str], dict | None] | None = None
    store: Callable[[str, dict], None] | None = None
    entries: dict[str, FEToothCompliance] = field(default_factory=dict)
    hits: int = 0  #: lookups answered from memory or the persistent store
    misses: int = 0  #: lookups that needed an FE solve

    def get_or_compute(self, key: str, compute: Callable[[], FEToothCompliance]
                       ) -> FEToothCompliance:
        """The cached compliance for ``key``, or ``compute()`` stored under it."""
        if key in self.entries:
            self.hits += 1
            return self.entries[key]
        rec = self.load(key) if self.load is not None else None
        if rec is not None:
            self.hits += 1
            value = from_record(rec)
        else:
            self.misses += 1
            value = compute()
            if self.store is not None:
                self.store(key, to_record(value))
        self.entries[key] = value
        return value


#: Process-wide in-memory cache used when no cache is passed.
DEFAULT_CACHE = ComplianceCache()
