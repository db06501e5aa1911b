"""The rating document: every factor with symbol, value and clause; safeties and verdicts.

docs/theory.md, "ISO 6336 rating". Frozen dataclasses with ``to_dict()`` (plain JSON types;
an infinite life or zero damage is reported as ``None`` / 0.0 respectively, see fields).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from gearcli.model.iso6336.common import Factor
from gearcli.model.iso6336.inspection import InspectionDimensions

__all__ = ["GearRating", "RatingResult"]


def _find(rows: tuple[Factor, ...], symbol: str) -> Factor:
    for f in rows:
        if f.symbol == symbol:
            return f
    raise KeyError(symbol)


def _finite(x: float) -> float | None:
    return None if math.isinf(x) else x


@dataclass(frozen=True)
class GearRating:
    """Rating of one gear of the pair."""

    name: str  #: "pinion" or "gear"
    load_cycles: float  #: N_L over the required life [-]
    sigma_H_MPa: float  #: σ_H (Z_B or Z_D σ_H0 √K) [N/mm²]
    sigma_HG_MPa: float  #: σ_HG at N_L [N/mm²]
    sigma_HP_MPa: float  #: σ_HP = σ_HG/S_H,min [N/mm²]
    S_H: float  #: σ_HG/σ_H [-]
    S_H_min: float
    sigma_F_MPa: float  #: σ_F [N/mm²]
    sigma_FG_MPa: float  #: σ_FG at N_L [N/mm²]
    sigma_FP_MPa: float  #: σ_FP = σ_FG/S_F,min [N/mm²]
    S_F: float  #: σ_FG/σ_F [-]
    S_F_min: float
    life_pitting_h: float  #: life at which S_H falls to S_H,min [h] (inf: never)
    life_bending_h: float  #: life at which S_F falls to S_F,min [h] (inf: never)
    damage_pitting: float  #: Miner damage of the required life with S_H,min [-]
    damage_bending: float  #: same, bending [-]
    factors: tuple[Factor, ...]  #: the gear's factors and stresses, in rating order
    inspection: InspectionDimensions

    @property
    def pitting_ok(self) -> bool:
        return self.S_H >= self.S_H_min

    @property
    def bending_ok(self) -> bool:
        return self.S_F >= self.S_F_min

    def factor(self, symbol: str) -> Factor:
        """The row of ``symbol`` (KeyError when absent)."""
        return _find(self.factors, symbol)

    def to_dict(self) -> dict:
        return {
            "name": self.name, "load_cycles": self.load_cycles,
            "sigma_H_MPa": self.sigma_H_MPa, "sigma_HG_MPa": self.sigma_HG_MPa,
            "sigma_HP_MPa": self.sigma_HP_MPa, "S_H": self.S_H, "S_H_min": self.S_H_min,
            "pitting": "pass" if self.pitting_ok else "fail",
            "sigma_F_MPa": self.sigma_F_MPa, "sigma_FG_MPa": self.sigma_FG_MPa,
            "sigma_FP_MPa": self.sigma_FP_MPa, "S_F": self.S_F, "S_F_min": self.S_F_min,
            "bending": "pass" if self.bending_ok else "fail",
            "life_pitting_h": _finite(self.life_pitting_h),
            "life_bending_h": _finite(self.life_bending_h),
            "damage_pitting": _finite(self.damage_pitting),
            "damage_bending": _finite(self.damage_bending),
            "factors": [f.to_dict() for f in self.factors],
            "inspection": self.inspection.to_dict(),
        }


@dataclass(frozen=True)
class RatingResult:
    """ISO 6336 Method B rating of a spur pair."""

    edition: str  #: "2006" or "2019"
    pair_factors: tuple[Factor, ...]  #: factors common to the pair (K factors, Z_H, σ_H0, ...)
    pinion: GearRating
    gear: GearRating

    @property
    def ok(self) -> bool:
        """True when every safety is at or above its minimum."""
        return all((g.pitting_ok and g.bending_ok) for g in (self.pinion, self.gear))

    def factor(self, symbol: str) -> Factor:
        """The pair row of ``symbol`` (KeyError when absent)."""
        return _find(self.pair_factors, symbol)

    def to_dict(self) -> dict:
        return {"method": "ISO 6336 Method B", "edition": self.edition,
                "verdict": "pass" if self.ok else "fail",
                "pair": [f.to_dict() for f in self.pair_factors],
                "pinion": self.pinion.to_dict(), "gear": self.gear.to_dict()}
