"""Tooth fault records (docs/theory.md, "Tooth faults"): what a fault is, checked on creation.

The physics that turns them into stiffness factors is :mod:`gearcli.model.faults.factors`.
Lengths in mm, angles in degrees (as named), shares of the face width in 0 … 1.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["GEARS", "RootCrack", "Spall", "ChippedTip", "MissingTooth", "is_void"]

#: Gear names in the order of the factor table's first axis (0 pinion, 1 gear).
GEARS = ("pinion", "gear")


def _check(gear: str, tooth: int, **shares: float) -> None:
    if gear not in GEARS:
        raise ValueError(f"a fault's gear is 'pinion' or 'gear', got {gear!r}")
    if int(tooth) != tooth or tooth < 0:
        raise ValueError(f"a fault's tooth is an index >= 0, got {tooth!r}")
    for name, v in shares.items():
        if not 0.0 <= v <= 1.0:
            raise ValueError(f"a fault's {name} is a share of the face width, 0 ... 1, got {v}")


@dataclass(frozen=True)
class RootCrack:
    """Root crack: depth q along its path [mm], path angle ν to the centreline [deg], width
    share [-] of the face it runs through."""

    gear: str
    tooth: int
    depth_mm: float
    angle_deg: float = 45.0
    width: float = 1.0

    def __post_init__(self):
        _check(self.gear, self.tooth, width=self.width)
        if not self.depth_mm >= 0.0 or not 0.0 < self.angle_deg <= 90.0:
            raise ValueError("a root crack needs depth >= 0 and 0 < angle <= 90 deg")


@dataclass(frozen=True)
class Spall:
    """Spall (pit): centre as a diameter [mm] or a roll angle of the tooth's involute [deg],
    length along the profile [mm], width share [-], depth [mm]."""

    gear: str
    tooth: int
    length_mm: float
    width: float
    depth_mm: float
    diameter_mm: float | None = None
    roll_angle_deg: float | None = None

    def __post_init__(self):
        _check(self.gear, self.tooth, width=self.width)
        if (self.diameter_mm is None) == (self.roll_angle_deg is None):
            raise ValueError("a spall's centre is a diameter or a roll angle, exactly one")
        if not (self.length_mm >= 0.0 and self.depth_mm >= 0.0):
            raise ValueError("a spall needs length >= 0 and depth >= 0")


@dataclass(frozen=True)
class ChippedTip:
    """Chipped tip: lost tip height (radial, from the tip circle) [mm] over a width share [-]."""

    gear: str
    tooth: int
    height_mm: float
    width: float = 1.0

    def __post_init__(self):
        _check(self.gear, self.tooth, width=self.width)
        if not self.height_mm >= 0.0:
            raise ValueError("a chipped tip needs height >= 0")


@dataclass(frozen=True)
class MissingTooth:
    """A tooth broken off at the root: it carries nothing."""

    gear: str
    tooth: int

    def __post_init__(self):
        _check(self.gear, self.tooth)


def is_void(fault) -> bool:
    """True for a fault of zero size (it leaves the factors at exactly 1)."""
    if isinstance(fault, RootCrack):
        return fault.depth_mm == 0.0 or fault.width == 0.0
    if isinstance(fault, Spall):
        return fault.length_mm == 0.0 or fault.width == 0.0 or fault.depth_mm == 0.0
    if isinstance(fault, ChippedTip):
        return fault.height_mm == 0.0 or fault.width == 0.0
    return False
