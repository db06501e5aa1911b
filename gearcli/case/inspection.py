"""The inspection dimensions of a case's gears: span W_k, balls, M_dK, chordal
tooth thickness and height of both gears at the nominal thickness and at the tooth-thickness
allowances (gearcli/model/iso6336/inspection.py; docs/theory.md, "ISO 6336 rating" §6). Used
by `gearcli geometry` (pipeline.geometry), `gearcli rate` and the report's geometry table."""

from __future__ import annotations

from dataclasses import dataclass

from gearcli.case.schema import Case
from gearcli.model.geometry import PairGeometry
from gearcli.model.iso6336.inspection import InspectionDimensions, inspection_dimensions

__all__ = ["PairInspection", "pair_inspection"]


@dataclass(frozen=True)
class PairInspection:
    """Inspection dimensions of both gears (tuples: nominal, upper, lower allowance) [mm]."""

    pinion: InspectionDimensions
    gear: InspectionDimensions
    allowances_mm: tuple[tuple[float, float], tuple[float, float]]  #: (upper, lower) per gear

    def to_dict(self) -> dict:
        return {"pinion": {**self.pinion.to_dict(),
                           "thickness_allowances_mm": list(self.allowances_mm[0])},
                "gear": {**self.gear.to_dict(),
                         "thickness_allowances_mm": list(self.allowances_mm[1])}}


def pair_inspection(case: Case, g: PairGeometry) -> PairInspection:
    """Span W_k, balls (theoretical, next standard or rating.<gear>.ball_diameter), M_dK and
    chordal tooth thickness/height of both gears at the nominal thickness and at the
    allowances rating.<gear>.thickness_allowances (default: both −gears.<gear>.
    thickness_allowance); docs/theory.md, "ISO 6336 rating" §6."""
    out, allowances = [], []
    for role in ("pinion", "gear"):
        spec, rg, gg = getattr(case.gears, role), getattr(case.rating, role), getattr(g, role)
        allow = rg.thickness_allowances or (-spec.thickness_allowance, -spec.thickness_allowance)
        allow = (float(allow[0]) + 0.0, float(allow[1]) + 0.0)  # -0.0 as 0.0
        allowances.append(allow)
        out.append(inspection_dimensions(spec.teeth, spec.profile_shift, g.module_mm,
                                         g.pressure_angle_rad, gg.d_a_mm, allow,
                                         rg.ball_diameter))
    return PairInspection(out[0], out[1], (allowances[0], allowances[1]))
