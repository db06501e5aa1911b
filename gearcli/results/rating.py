"""The rating in summary.json of `gearcli run`: S_H and S_F of each gear in the ISO
column (K_v of the case) and the simulated column (K_v = the run's F_max/F_static; with the
safeties of the run's contact and root stress peaks), against their minimums, with verdicts
(:class:`RatingSummary`, summary.json's ``rating``; the full rating with every factor is
rating.json; docs/theory.md, "ISO 6336 rating" §9)."""

from __future__ import annotations

import dataclasses
import math

from gearcli.results.fields import Document, metric_field

__all__ = ["GearSafeties", "RatingColumn", "RatingSummary", "SAFETY_CHECKS"]

#: A gear's two checks as field names of its rating documents (:class:`GearSafeties`, and
#: rating.json's results.rating_document.GearRatingDocument): (safety, its minimum, verdict).
SAFETY_CHECKS = (("S_H", "S_H_min", "pitting"), ("S_F", "S_F_min", "bending"))


def _safety(key: str, label: str, default=math.nan, **extra):
    """A dimensionless safety (or minimum) field."""
    return metric_field(key, default, unit="–", label=label, **extra)


def _verdict(key: str, what: str):
    return metric_field(key, "pass", label=f"verdict {what}: pass (safety ≥ its minimum) or fail")


@dataclasses.dataclass(frozen=True)
class GearSafeties(Document):
    """S_H and S_F of one gear in one column, against their minimums (ISO 6336-2, -3)."""

    S_H: float = _safety("S_H", "safety against pitting S_H = σ_HG/σ_H", required=True)
    S_H_min: float = _safety("S_H_min", "minimum safety against pitting S_H,min",
                             required=True)
    pitting: str = _verdict("pitting", "pitting")
    S_F: float = _safety("S_F", "safety against tooth breakage S_F = σ_FG/σ_F", required=True)
    S_F_min: float = _safety("S_F_min", "minimum safety against tooth breakage S_F,min",
                             required=True)
    bending: str = _verdict("bending", "bending")
    #: from the run's stress peaks (simulated column; `gearcli stress`; pipeline/rating.py)
    S_H_peak: float | None = _safety("S_H_peak", "S_H from the run's contact stress peak "
                                     "σ_HG/(σ_H,peak √(K_A K_γ K_Hβ))", None, omit_none=True)
    S_F_peak: float | None = _safety("S_F_peak", "S_F from the run's root stress peak "
                                     "σ_FG/(σ_F,peak K_A K_γ K_Fβ Y_β Y_B Y_DT)", None,
                                     omit_none=True)


@dataclasses.dataclass(frozen=True)
class RatingColumn(Document):
    """One column of the rating: its dynamic factor and both gears' safeties."""

    dynamic_factor: float = _safety("dynamic_factor", "dynamic factor K_v of the column",
                                    required=True)
    dynamic_factor_source: str = metric_field("dynamic_factor_source", "",
                                              label="where K_v comes from")
    pinion: GearSafeties = metric_field("pinion", GearSafeties(), nested=GearSafeties)
    gear: GearSafeties = metric_field("gear", GearSafeties(), nested=GearSafeties)
    safety_pitting_min: float = _safety("safety_pitting_min", "S_H, the smaller of the gears'")
    safety_bending_min: float = _safety("safety_bending_min", "S_F, the smaller of the gears'")
    verdict: str = _verdict("verdict", "of the column")


@dataclasses.dataclass(frozen=True)
class RatingSummary(Document):
    """summary.json's ``rating`` (`gearcli run` of a case it can rate)."""

    method: str = metric_field("method", "ISO 6336 Method B", label="rating method")
    edition: str = metric_field("edition", "2019", label="ISO 6336 edition followed")
    iso: RatingColumn = metric_field("iso", RatingColumn(), nested=RatingColumn)
    simulated: RatingColumn | None = metric_field("simulated", None, nested=RatingColumn)
    verdict: str = _verdict("verdict", "of the rating (both columns, the duty cycle)")
