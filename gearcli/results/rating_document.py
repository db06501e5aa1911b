"""rating.json of `gearcli rate -o` and `gearcli run` (:class:`RatingDocument`): the ISO 6336
Method B rating with every factor (symbol, value, unit, clause, name) of the pair and of each
gear, the safeties against their minimums with verdicts, the lives at the minimum safeties,
the inspection dimensions, the duty cycle's Palmgren–Miner damage, the simulated column of a
run and the edition-dependent factors under ISO 6336:2006 and :2019 (docs/theory.md, "ISO 6336
rating"). Stresses in N/mm² (MPa), lengths in mm, lives in h: the standard's units.

Built by gearcli/pipeline/rating_document.py from the model's rating
(gearcli/model/iso6336/document.py), read back by gearcli/io/results.read_rating. A value the
model has as infinite (a life that never ends, a damage) is None (JSON null), as is a factor
row whose value is not finite.
"""

from __future__ import annotations

import dataclasses
import math

from gearcli.results.fields import Document, metric_field

__all__ = ["RatingFactor", "GearInspection", "GearRatingDocument", "RatingResultDocument",
           "PeakSafety", "GearPeaks", "SimulatedRatingDocument", "IsoDynamic", "RatingLoad",
           "GearDamage", "DutyCycleDocument", "EditionRowDocument", "RatingDocument"]


def _text(key: str, label: str, default: str = ""):
    return metric_field(key, default, label=label)


def _value(key: str, label: str, unit: str, default=math.nan, **extra):
    """A number of the rating, in the standard's unit (``unit``; "–" dimensionless)."""
    return metric_field(key, default, label=label, unit=unit, **extra)


def _verdict(key: str, what: str):
    return metric_field(key, "pass", label=f"verdict {what}: pass or fail")


@dataclasses.dataclass(frozen=True)
class RatingFactor(Document):
    """One row of the rating: a factor or stress with its ISO symbol, value and source."""

    symbol: str = _text("symbol", "ISO symbol, e.g. Z_H")
    value: float | None = _value("value", "value in unit (null: not finite)", "", None)
    unit: str = _text("unit", "unit of the value (- dimensionless)")
    clause: str = _text("clause", "the standard and clause or equation it comes from")
    name: str = _text("name", "plain-language name")


@dataclasses.dataclass(frozen=True)
class GearInspection(Document):
    """Inspection dimensions of one gear (ISO 21771, DIN 3960); each triple is (nominal, upper
    allowance, lower allowance) [mm]."""

    span_teeth: int = metric_field("span_teeth", 0, label="teeth spanned k")
    span_mm: tuple[float, ...] = _value("span_mm", "span W_k", "mm", ())
    ball_theoretical_mm: float = _value("ball_theoretical_mm", "ball D_M touching on d + 2 x m",
                                        "mm")
    ball_mm: float = _value("ball_mm", "ball used (given, else the next standard size)", "mm")
    over_balls_mm: tuple[float, ...] = _value("over_balls_mm", "dimension over balls M_dK",
                                              "mm", ())
    chordal_thickness_mm: tuple[float, ...] = _value(
        "chordal_thickness_mm", "chordal tooth thickness s_c", "mm", ())
    chordal_height_mm: tuple[float, ...] = _value(
        "chordal_height_mm", "chordal height h_c from the tip diameter", "mm", ())


@dataclasses.dataclass(frozen=True)
class GearRatingDocument(Document):
    """The rating of one gear of the pair: stresses, strengths, safeties, lives, factors."""

    name: str = _text("name", "pinion or gear")
    load_cycles: float = _value("load_cycles", "load cycles N_L over the required life", "–")
    sigma_H_MPa: float = _value("sigma_H_MPa", "contact stress σ_H", "MPa")
    sigma_HG_MPa: float = _value("sigma_HG_MPa", "pitting stress limit σ_HG at N_L", "MPa")
    sigma_HP_MPa: float = _value("sigma_HP_MPa", "permissible contact stress σ_HP", "MPa")
    S_H: float = _value("S_H", "safety against pitting S_H = σ_HG/σ_H", "–")
    S_H_min: float = _value("S_H_min", "minimum safety against pitting S_H,min", "–")
    pitting: str = _verdict("pitting", "pitting (S_H ≥ S_H,min)")
    sigma_F_MPa: float = _value("sigma_F_MPa", "tooth root stress σ_F", "MPa")
    sigma_FG_MPa: float = _value("sigma_FG_MPa", "tooth root stress limit σ_FG at N_L", "MPa")
    sigma_FP_MPa: float = _value("sigma_FP_MPa", "permissible root stress σ_FP", "MPa")
    S_F: float = _value("S_F", "safety against tooth breakage S_F = σ_FG/σ_F", "–")
    S_F_min: float = _value("S_F_min", "minimum safety against tooth breakage S_F,min", "–")
    bending: str = _verdict("bending", "bending (S_F ≥ S_F,min)")
    life_pitting_h: float | None = _value("life_pitting_h", "life at which S_H falls to "
                                          "S_H,min (null: never)", "h", None)
    life_bending_h: float | None = _value("life_bending_h", "life at which S_F falls to "
                                          "S_F,min (null: never)", "h", None)
    damage_pitting: float | None = _value("damage_pitting", "Miner damage of the required "
                                          "life at S_H,min", "–", None)
    damage_bending: float | None = _value("damage_bending", "Miner damage of the required "
                                          "life at S_F,min", "–", None)
    factors: tuple[RatingFactor, ...] = metric_field("factors", (), nested=RatingFactor)
    inspection: GearInspection = metric_field("inspection", GearInspection(),
                                              nested=GearInspection)


@dataclasses.dataclass(frozen=True)
class RatingResultDocument(Document):
    """One column of the rating (rating.json's ``iso``): the pair's factors and both gears."""

    method: str = _text("method", "rating method", "ISO 6336 Method B")
    edition: str = _text("edition", "ISO 6336 edition followed", "2019")
    verdict: str = _verdict("verdict", "of the column")
    pair: tuple[RatingFactor, ...] = metric_field("pair", (), nested=RatingFactor)
    pinion: GearRatingDocument = metric_field("pinion", GearRatingDocument(),
                                              nested=GearRatingDocument)
    gear: GearRatingDocument = metric_field("gear", GearRatingDocument(),
                                            nested=GearRatingDocument)


def _peak(key: str, label: str, unit: str = "MPa"):
    return _value(key, label, unit, None, omit_none=True)


@dataclasses.dataclass(frozen=True)
class PeakSafety(Document):
    """One gear's safeties from a run's peak stresses (gearcli/pipeline/rating._peaks); a
    field is None, and left out of the JSON, when the run has no loaded sample of that
    stress."""

    sigma_H_peak_MPa: float | None = _peak("sigma_H_peak_MPa", "σ_H peak of gearcli stress")
    sigma_H_MPa: float | None = _peak("sigma_H_MPa", "σ_H,sim = σ_H,peak √(K_A K_γ K_Hβ)")
    S_H: float | None = _peak("S_H", "S_H = σ_HG/σ_H,sim", "–")
    S_H_min: float | None = _peak("S_H_min", "minimum safety against pitting S_H,min", "–")
    sigma_F_peak_MPa: float | None = _peak("sigma_F_peak_MPa", "σ_F peak of gearcli stress")
    sigma_F_MPa: float | None = _peak("sigma_F_MPa", "σ_F,sim = σ_F,peak K_A K_γ K_Fβ Y_β Y_B "
                                      "Y_DT")
    S_F: float | None = _peak("S_F", "S_F = σ_FG/σ_F,sim", "–")
    S_F_min: float | None = _peak("S_F_min", "minimum safety against tooth breakage S_F,min",
                                  "–")


@dataclasses.dataclass(frozen=True)
class GearPeaks(Document):
    """rating.json's ``simulated.peaks``: the peak stresses' safeties of both gears."""

    pinion: PeakSafety = metric_field("pinion", PeakSafety(), nested=PeakSafety)
    gear: PeakSafety = metric_field("gear", PeakSafety(), nested=PeakSafety)


@dataclasses.dataclass(frozen=True)
class SimulatedRatingDocument(RatingResultDocument):
    """rating.json's ``simulated``: the column with K_v (and K_γ) of the run, and the safeties
    of its peak stresses (None: the run has no stress peaks)."""

    peaks: GearPeaks | None = metric_field("peaks", None, nested=GearPeaks)


@dataclasses.dataclass(frozen=True)
class IsoDynamic(Document):
    """K_v by ISO 6336-1 Method B at the case's pinion speed (rating.json's
    ``load.iso_dynamic``; gearcli/model/iso_kv.py)."""

    resonance_speed_rpm: float = metric_field("resonance_speed_rpm")
    resonance_ratio: float = metric_field("resonance_ratio")
    speed_range: str = _text("speed_range", "speed range of ISO 6336-1 (sub-critical, ...)")
    line_load_N_mm: float = _value("line_load_N_mm", "line load F_t K_A/b", "N/mm")
    c_prime_N_mm_um: float = _value("c_prime_N_mm_um", "single-pair stiffness c′", "N/(mm·µm)")
    f_pb_eff_um: float = _value("f_pb_eff_um", "effective base pitch deviation f_pb,eff", "µm")
    tip_relief_um: float = _value("tip_relief_um", "tip relief C_a", "µm")
    k_v: float = metric_field("k_v")


@dataclasses.dataclass(frozen=True)
class RatingLoad(Document):
    """The load rated (rating.json's ``load``): per mesh path, at the pinion."""

    pinion_torque_Nm: float = _value("pinion_torque_Nm", "pinion torque T1 per mesh path",
                                     "N*m")
    pinion_speed_rpm: float = _value("pinion_speed_rpm", "pinion speed n1", "rpm")
    life_h: float = _value("life_h", "required life", "h")
    dynamic_factor_source: str = _text("dynamic_factor_source", "where K_v comes from")
    iso_dynamic: IsoDynamic | None = metric_field("iso_dynamic", None, nested=IsoDynamic)


@dataclasses.dataclass(frozen=True)
class GearDamage(Document):
    """Palmgren–Miner damage of one gear over the required life, in total and per bin
    (ISO 6336-6); None: infinite."""

    name: str = _text("name", "pinion or gear")
    pitting: float | None = _value("pitting", "damage D_H", "–", None)
    bending: float | None = _value("bending", "damage D_F", "–", None)
    pitting_per_bin: tuple[float | None, ...] = _value("pitting_per_bin", "D_H per bin", "–",
                                                       ())
    bending_per_bin: tuple[float | None, ...] = _value("bending_per_bin", "D_F per bin", "–",
                                                       ())


@dataclasses.dataclass(frozen=True)
class DutyCycleDocument(Document):
    """rating.json's ``duty_cycle`` (with rating.duty_cycle)."""

    method: str = _text("method", "damage method", "ISO 6336-6 Palmgren-Miner")
    pinion: GearDamage = metric_field("pinion", GearDamage(), nested=GearDamage)
    gear: GearDamage = metric_field("gear", GearDamage(), nested=GearDamage)


@dataclasses.dataclass(frozen=True)
class EditionRowDocument(Document):
    """One edition-dependent factor under ISO 6336:2006 and :2019 (JSON keys "2006",
    "2019")."""

    symbol: str = _text("symbol", "ISO symbol")
    gear: str = _text("gear", "pair, pinion or gear")
    value_2006: float = _value("value_2006", "value under ISO 6336:2006", "", json_key="2006")
    value_2019: float = _value("value_2019", "value under ISO 6336:2019", "", json_key="2019")
    unit: str = _text("unit", "unit of the values (- dimensionless)")
    differs: bool = metric_field("differs", False, label="the values differ beyond rounding")


@dataclasses.dataclass(frozen=True)
class RatingDocument(Document):
    """rating.json: the case's ISO column, its duty cycle, a run's simulated column, both
    editions, notes and the verdict of them all."""

    schema_version: int = metric_field("schema_version", 0)
    case: str = _text("case", "case name")
    method: str = _text("method", "rating method", "ISO 6336 Method B")
    edition: str = _text("edition", "ISO 6336 edition followed", "2019")
    verdict: str = _verdict("verdict", "of the rating (both columns, the duty cycle)")
    load: RatingLoad = metric_field("load", RatingLoad(), nested=RatingLoad)
    iso: RatingResultDocument = metric_field("iso", RatingResultDocument(),
                                             nested=RatingResultDocument)
    duty_cycle: DutyCycleDocument | None = metric_field("duty_cycle", None,
                                                        nested=DutyCycleDocument)
    simulated: SimulatedRatingDocument | None = metric_field("simulated", None,
                                                             nested=SimulatedRatingDocument)
    editions: tuple[EditionRowDocument, ...] = metric_field("editions", (),
                                                            nested=EditionRowDocument)
    notes: tuple[str, ...] = metric_field("notes", ())
