"""Tooth faults: records, tooth indices and (in :mod:`.factors`, which loads scipy) the
stiffness factors they give (docs/theory.md, "Tooth faults")."""

from gearcli.model.faults.indexing import tooth_index_offsets
from gearcli.model.faults.records import (
    GEARS,
    ChippedTip,
    MissingTooth,
    RootCrack,
    Spall,
    is_void,
)

__all__ = ["GEARS", "RootCrack", "Spall", "ChippedTip", "MissingTooth", "is_void",
           "tooth_index_offsets"]
