"""The document of `gearcli stress`: stress.json (:class:`StressDocument`) with its ISO 6336
static values (:class:`StaticRatingDoc`) and each gear's peaks (:class:`GearPeaks`), and the
flat per-gear view of the Python API (:class:`GearStress`)."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping

from gearcli.results.fields import Document, metric_field


def _opt(key: str):
    """An entry written only when it has a value."""
    return metric_field(key, None, omit_none=True)


@dataclasses.dataclass(frozen=True)
class StaticGear(Document):
    """ISO 6336-2/-3 static values of one gear at the static load (the pinion's at the inner
    point of single contact B: M1, Z_B; the gear's at D: M2, Z_D)."""

    M1: float | None = _opt("M1")
    M2: float | None = _opt("M2")
    Z_B: float | None = _opt("Z_B")
    Z_D: float | None = _opt("Z_D")
    sigma_H_iso_MPa: float = metric_field("sigma_H_iso_MPa")
    sigma_H_at_B_MPa: float | None = _opt("sigma_H_at_B_MPa")
    sigma_H_at_D_MPa: float | None = _opt("sigma_H_at_D_MPa")
    face_width_bending_mm: float = metric_field("face_width_bending_mm")
    s_Fn_mm: float = metric_field("s_Fn_mm")
    rho_F_mm: float = metric_field("rho_F_mm")
    h_Fe_mm: float = metric_field("h_Fe_mm")
    alpha_Fen_deg: float = metric_field("alpha_Fen_deg")
    Y_F: float = metric_field("Y_F")
    Y_S: float = metric_field("Y_S")
    sigma_F0_MPa: float = metric_field("sigma_F0_MPa")
    Y_Fa: float = metric_field("Y_Fa")
    Y_Sa: float = metric_field("Y_Sa")
    sigma_F0_tip_MPa: float = metric_field("sigma_F0_tip_MPa")


@dataclasses.dataclass(frozen=True)
class StaticRatingDoc(Document):
    """stress.json's ``static``: the nominal ISO 6336 values for F_n = T/r_b2."""

    force_normal_N: float = metric_field("force_normal_N")
    force_tangential_N: float = metric_field("force_tangential_N")
    ratio_u: float = metric_field("ratio_u")
    E_star_MPa: float = metric_field("E_star_MPa")
    Z_H: float = metric_field("Z_H")
    Z_E_sqrt_MPa: float = metric_field("Z_E_sqrt_MPa")
    Z_eps: float = metric_field("Z_eps")
    Y_eps: float = metric_field("Y_eps")
    contact_face_width_mm: float = metric_field("contact_face_width_mm")
    sigma_H0_MPa: float = metric_field("sigma_H0_MPa")
    sigma_H0_with_Z_eps_MPa: float = metric_field("sigma_H0_with_Z_eps_MPa")
    pinion: StaticGear = metric_field("pinion", StaticGear(), nested=StaticGear)
    gear: StaticGear = metric_field("gear", StaticGear(), nested=StaticGear)
    factors_taken_as_1: str = metric_field("factors_taken_as_1", "")


@dataclasses.dataclass(frozen=True)
class StressPeak(Document):
    """The peak of a stress over the window and where it occurs (only ``MPa``, null, when no
    pair is loaded in the window)."""

    MPa: float | None = metric_field("MPa", None)
    t_s: float | None = _opt("t_s")
    slot: int | None = _opt("slot")
    tooth: int | None = _opt("tooth")
    x_from_A_mm: float | None = _opt("x_from_A_mm")
    force_N: float | None = _opt("force_N")
    zone: str | None = _opt("zone")


@dataclasses.dataclass(frozen=True)
class Safety(Document):
    """Safety factors against the material limits of the case (docs/theory.md §7.3)."""

    sigma_Hlim_MPa: float | None = metric_field("sigma_Hlim_MPa", None)
    sigma_Flim_MPa: float | None = metric_field("sigma_Flim_MPa", None)
    Y_ST: float = metric_field("Y_ST")
    S_H: float | None = metric_field("S_H", None)
    S_F: float | None = metric_field("S_F", None)
    S_H_static: float | None = metric_field("S_H_static", None)
    S_F_static: float | None = metric_field("S_F_static", None)
    note: str = metric_field("note", "")


@dataclasses.dataclass(frozen=True)
class GearPeaks(Document):
    """stress.json's ``pinion`` / ``gear``: maxima per tooth, peaks, ratios to the static
    values, safety factors (null without material limits)."""

    teeth: int = metric_field("teeth", 0)
    sigma_H_max_per_tooth_MPa: tuple[float | None, ...] = metric_field(
        "sigma_H_max_per_tooth_MPa", ())
    sigma_F_max_per_tooth_MPa: tuple[float | None, ...] = metric_field(
        "sigma_F_max_per_tooth_MPa", ())
    peak_sigma_H: StressPeak = metric_field("peak_sigma_H", StressPeak(), nested=StressPeak)
    peak_sigma_F: StressPeak = metric_field("peak_sigma_F", StressPeak(), nested=StressPeak)
    ratio_sigma_H_to_static: float | None = metric_field("ratio_sigma_H_to_static", None)
    ratio_sigma_F_to_static: float | None = metric_field("ratio_sigma_F_to_static", None)
    safety: Safety | None = metric_field("safety", None, nested=Safety)


@dataclasses.dataclass(frozen=True)
class StressDocument(Document):
    """stress.json (`gearcli stress`)."""

    schema_version: int = metric_field("schema_version", 0)
    case: str = metric_field("case", "")
    window_s: tuple[float, float] = metric_field("window_s", (math.nan, math.nan))
    window_reason: str = metric_field("window_reason", "")
    units: Mapping[str, str] = metric_field("units", {})
    static: StaticRatingDoc = metric_field("static", StaticRatingDoc(), nested=StaticRatingDoc)
    pinion: GearPeaks = metric_field("pinion", GearPeaks(), nested=GearPeaks)
    gear: GearPeaks = metric_field("gear", GearPeaks(), nested=GearPeaks)
    ratio_definition: str = metric_field("ratio_definition", "")
    run_max_MPa: Mapping[str, float] = metric_field("run_max_MPa", {})
    samples: Mapping[str, int] = metric_field("samples", {})
    warnings: tuple[str, ...] = metric_field("warnings", ())


@dataclasses.dataclass(frozen=True, repr=False)  # Document's labelled repr
class GearStress(Document):
    """Peak dynamic stresses of one gear in the window against its ISO 6336 static values: the
    Python API's flat view of a :class:`StressDocument` (:meth:`of`)."""

    teeth: int = metric_field("teeth", 0)
    sigma_H_peak_MPa: float | None = metric_field("sigma_H_peak_MPa", None)
    sigma_F_peak_MPa: float | None = metric_field("sigma_F_peak_MPa", None)
    sigma_H_iso_MPa: float | None = metric_field("sigma_H_iso_MPa", None)
    sigma_F0_MPa: float | None = metric_field("sigma_F0_MPa", None)
    ratio_sigma_H_to_static: float | None = metric_field("ratio_sigma_H_to_static", None)
    ratio_sigma_F_to_static: float | None = metric_field("ratio_sigma_F_to_static", None)
    S_H: float | None = metric_field("S_H", None)
    S_F: float | None = metric_field("S_F", None)

    @classmethod
    def of(cls, doc: StressDocument, which: str) -> GearStress:
        """The view of gear ``which`` ("pinion" or "gear") of a stress document."""
        g, st = getattr(doc, which), getattr(doc.static, which)
        safety = g.safety or Safety()
        return cls(teeth=g.teeth, sigma_H_peak_MPa=g.peak_sigma_H.MPa,
                   sigma_F_peak_MPa=g.peak_sigma_F.MPa, sigma_H_iso_MPa=st.sigma_H_iso_MPa,
                   sigma_F0_MPa=st.sigma_F0_MPa,
                   ratio_sigma_H_to_static=g.ratio_sigma_H_to_static,
                   ratio_sigma_F_to_static=g.ratio_sigma_F_to_static,
                   S_H=safety.S_H, S_F=safety.S_F)
