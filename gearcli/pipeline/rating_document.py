"""rating.json as its typed document (gearcli/results/rating_document.py) from a case's rating
(:class:`gearcli.pipeline.rating.CaseRating`, the model's gearcli/model/iso6336/document.py
rows): what `gearcli rate` prints and writes, and `gearcli run` writes.

Infinite values of the model (a life that never ends, a damage) become None (JSON null), as
does a factor row whose value is not finite.
"""

from __future__ import annotations

import dataclasses
import math

from gearcli.model.iso6336.common import Factor
from gearcli.model.iso6336.document import GearRating, RatingResult
from gearcli.model.iso6336.editions import EditionRow
from gearcli.model.iso6336.spectrum import DutyCycleDamage
from gearcli.model.iso6336.spectrum import GearDamage as ModelGearDamage
from gearcli.results.rating_document import (
    DutyCycleDocument,
    EditionRowDocument,
    GearDamage,
    GearInspection,
    GearPeaks,
    GearRatingDocument,
    RatingDocument,
    RatingFactor,
    RatingLoad,
    RatingResultDocument,
    SimulatedRatingDocument,
)
from gearcli.results.version import RESULTS_SCHEMA_VERSION

__all__ = ["rating_document", "column_document"]


def _finite(x: float) -> float | None:
    """None for an infinite life or damage (a NaN stays: it is no result to hide)."""
    return None if math.isinf(x) else x


def _verdict(ok: bool) -> str:
    return "pass" if ok else "fail"


def _factor(f: Factor) -> RatingFactor:
    return RatingFactor(symbol=f.symbol, value=f.value if math.isfinite(f.value) else None,
                        unit=f.unit, clause=f.clause, name=f.name)


def _gear(g: GearRating) -> GearRatingDocument:
    return GearRatingDocument(
        name=g.name, load_cycles=g.load_cycles, sigma_H_MPa=g.sigma_H_MPa,
        sigma_HG_MPa=g.sigma_HG_MPa, sigma_HP_MPa=g.sigma_HP_MPa, S_H=g.S_H, S_H_min=g.S_H_min,
        pitting=_verdict(g.pitting_ok), sigma_F_MPa=g.sigma_F_MPa,
        sigma_FG_MPa=g.sigma_FG_MPa, sigma_FP_MPa=g.sigma_FP_MPa, S_F=g.S_F, S_F_min=g.S_F_min,
        bending=_verdict(g.bending_ok), life_pitting_h=_finite(g.life_pitting_h),
        life_bending_h=_finite(g.life_bending_h), damage_pitting=_finite(g.damage_pitting),
        damage_bending=_finite(g.damage_bending),
        factors=tuple(_factor(f) for f in g.factors),
        inspection=GearInspection(**dataclasses.asdict(g.inspection)))


def column_document(result: RatingResult, cls=RatingResultDocument, **extra):
    """One column of the rating (the model's :class:`RatingResult`) as ``cls``."""
    return cls(method="ISO 6336 Method B", edition=result.edition, verdict=_verdict(result.ok),
               pair=tuple(_factor(f) for f in result.pair_factors), pinion=_gear(result.pinion),
               gear=_gear(result.gear), **extra)


def _damage(d: ModelGearDamage) -> GearDamage:
    return GearDamage(name=d.name, pitting=_finite(d.pitting), bending=_finite(d.bending),
                      pitting_per_bin=tuple(_finite(x) for x in d.pitting_per_bin),
                      bending_per_bin=tuple(_finite(x) for x in d.bending_per_bin))


def _duty(d: DutyCycleDamage | None) -> DutyCycleDocument | None:
    if d is None:
        return None
    return DutyCycleDocument(pinion=_damage(d.pinion), gear=_damage(d.gear))


def _edition(r: EditionRow) -> EditionRowDocument:
    return EditionRowDocument(symbol=r.symbol, gear=r.gear, value_2006=r.value_2006,
                              value_2019=r.value_2019, unit=r.unit, differs=r.differs)


def rating_document(rating) -> RatingDocument:
    """rating.json of ``rating``, a :class:`gearcli.pipeline.rating.CaseRating` (not imported
    here: it imports this module); ``.to_dict()`` is the file."""
    inp, sim = rating.rating_input, rating.simulated
    peaks = rating.simulated_peaks
    return RatingDocument(
        schema_version=RESULTS_SCHEMA_VERSION, case=rating.name, edition=rating.iso.edition,
        verdict=_verdict(rating.ok),
        load=RatingLoad(pinion_torque_Nm=inp.pinion_torque_Nm,
                        pinion_speed_rpm=inp.pinion_speed_rpm, life_h=inp.life_h,
                        dynamic_factor_source=rating.dynamic_factor_source,
                        iso_dynamic=rating.iso_dynamic),
        iso=column_document(rating.iso),
        duty_cycle=_duty(rating.duty_cycle),
        simulated=None if sim is None else column_document(
            sim, SimulatedRatingDocument, peaks=None if peaks is None else GearPeaks(**peaks)),
        editions=tuple(_edition(r) for r in rating.editions),
        notes=tuple(rating.notes))
