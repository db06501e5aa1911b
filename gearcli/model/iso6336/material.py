"""ISO 6336-5 allowable stress numbers σ_Hlim, σ_Flim from material kind, quality and hardness.

ISO 6336-5:2016, clause 5 and Table 1 (the lines of its Figures 1-16): within each row's
hardness range

    σ_lim = A · x + B   [N/mm²],   x = surface hardness (HBW or HV, as the row states)

for the material qualities ML (modest), MQ (normal, what experienced manufacturers reach) and ME
(high demands). σ_Flim is the bending endurance limit of the standard reference test gear
(Y_ST = 2 is applied separately, ISO 6336-3); σ_Hlim the contact endurance limit.

Source of the constants: the rows below were written from ISO 6336-5's Table 1 as recalled and
cross-checked constant by constant against an independent public transcription of the 2016
Table 1 (a C# "Iso6336Material" table); where the two differed (induction hardened, bending, ME)
the transcription's row 55 (A = 0.271, B = 237) is used. Case-hardened bending, MQ has three
rows in the standard (core hardness ≥ 25 HRC with lower or higher hardenability, ≥ 30 HRC:
425, 461, 500 N/mm²); the conservative 425 is returned, give σ_Flim explicitly for the others.
KISSsoft 03/2017 prints 430 for that row (its database), which the NREL 5 MW anchor uses as a
given value (tests/unit/test_iso6336_anchor.py). docs/theory.md, "ISO 6336 rating", §5.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

__all__ = ["MaterialKind", "Quality", "AllowableStress", "allowable_stress", "sigma_limits",
           "SURFACE_HARDENED", "NITRIDED", "THROUGH_HARDENED", "GREY_IRON_LIKE"]


class MaterialKind(enum.StrEnum):
    """Material / heat treatment groups of ISO 6336-5 (ISO abbreviation in the comment)."""

    NORMALIZED_STEEL = "normalized_steel"  # St
    NORMALIZED_CAST_STEEL = "normalized_cast_steel"  # St (cast)
    BLACK_MALLEABLE_IRON = "black_malleable_iron"  # GTS (perl.)
    NODULAR_IRON = "nodular_iron"  # GGG (perl., bai.)
    GREY_IRON = "grey_iron"  # GG
    THROUGH_HARDENED_CARBON = "through_hardened_carbon"  # V (wrought carbon steel)
    THROUGH_HARDENED_ALLOY = "through_hardened_alloy"  # V (wrought alloy steel)
    THROUGH_HARDENED_CAST_CARBON = "through_hardened_cast_carbon"  # V (cast carbon)
    THROUGH_HARDENED_CAST_ALLOY = "through_hardened_cast_alloy"  # V (cast alloy)
    CASE_HARDENED = "case_hardened"  # Eh
    INDUCTION_HARDENED = "induction_hardened"  # IF (flame or induction, root hardened)
    NITRIDED = "nitrided"  # NT (nitriding steel)
    NITRIDED_THROUGH_HARDENING = "nitrided_through_hardening"  # NV (nitr.)
    NITROCARBURIZED = "nitrocarburized"  # NV (nitrocar.)


class Quality(enum.StrEnum):
    """ISO 6336-5 material quality grade."""

    ML = "ML"
    MQ = "MQ"
    ME = "ME"


K = MaterialKind
#: Eh, IF: surface-hardened steels (ISO 6336-2/-3 groups "Eh, IF").
SURFACE_HARDENED = frozenset({K.CASE_HARDENED, K.INDUCTION_HARDENED})
#: NT, NV: nitrided and nitrocarburized steels.
NITRIDED = frozenset({K.NITRIDED, K.NITRIDED_THROUGH_HARDENING, K.NITROCARBURIZED})
#: St, V, GGG, GTS: normalized and through-hardened steels, nodular and malleable irons.
THROUGH_HARDENED = frozenset({K.NORMALIZED_STEEL, K.NORMALIZED_CAST_STEEL, K.BLACK_MALLEABLE_IRON,
                              K.NODULAR_IRON, K.THROUGH_HARDENED_CARBON, K.THROUGH_HARDENED_ALLOY,
                              K.THROUGH_HARDENED_CAST_CARBON, K.THROUGH_HARDENED_CAST_ALLOY})
#: GG: grey cast iron.
GREY_IRON_LIKE = frozenset({K.GREY_IRON})

_ML_MQ_ME = (Quality.ML, Quality.MQ, Quality.ME)


#: ISO 6336-5:2016 Table 1 as text: material group, H (σ_Hlim) or F (σ_Flim), hardness scale
#: and range, then A and B of σ_lim = A x + B for ML, MQ and ME.
_TABLE_TEXT = """
normalized_steel             H HBW 110 210  1.000  190  1.000  190  1.520  250
normalized_steel             F HBW 110 210  0.455   69  0.455   69  0.386  147
normalized_cast_steel        H HBW 140 210  0.986  131  0.986  131  1.143  237
normalized_cast_steel        F HBW 140 210  0.313   62  0.313   62  0.254  137
black_malleable_iron         H HBW 135 250  1.371  143  1.371  143  1.333  267
black_malleable_iron         F HBW 135 250  0.345   77  0.345   77  0.403  128
nodular_iron                 H HBW 175 300  1.434  211  1.434  211  1.500  250
nodular_iron                 F HBW 175 300  0.350  119  0.350  119  0.380  134
grey_iron                    H HBW 150 240  1.033  132  1.033  132  1.465  122
grey_iron                    F HBW 150 240  0.256    8  0.256    8  0.200   53
through_hardened_carbon      H HV  135 210  0.963  283  0.925  360  0.838  432
through_hardened_carbon      F HV  115 215  0.250  108  0.240  163  0.283  202
through_hardened_alloy       H HV  200 360  1.313  188  1.313  373  2.213  260
through_hardened_alloy       F HV  200 360  0.423  104  0.425  187  0.358  231
through_hardened_cast_carbon H HV  130 215  0.831  300  0.831  300  0.951  345
through_hardened_cast_carbon F HV  130 215  0.224  117  0.224  117  0.286  167
through_hardened_cast_alloy  H HV  200 360  1.276  298  1.276  298  1.350  356
through_hardened_cast_alloy  F HV  200 360  0.364  161  0.364  161  0.356  186
case_hardened                H HV  600 800    0.0 1300    0.0 1500    0.0 1650
case_hardened                F HV  600 800    0.0  312    0.0  425    0.0  525
induction_hardened           H HV  485 615  0.740  602  0.541  882  0.505 1013
induction_hardened           F HV  485 615  0.305   76  0.138  290  0.271  237
nitrided                     H HV  650 900    0.0 1125    0.0 1250    0.0 1450
nitrided                     F HV  650 900    0.0  270    0.0  420    0.0  468
nitrided_through_hardening   H HV  450 650    0.0  788    0.0  998    0.0 1217
nitrided_through_hardening   F HV  450 650    0.0  258    0.0  363    0.0  432
nitrocarburized              H HV  300 650    0.0  650  1.167  425  1.167  425
nitrocarburized              F HV  300 650    0.0  224  0.653   94  0.653   94
"""


def _parse_table(text: str) -> dict:
    """{(kind, "H" | "F"): ({quality: (A, B)}, scale, h_min, h_max)} from the text table."""
    table = {}
    for line in text.strip().splitlines():
        kind, stress, scale, h_min, h_max, *ab = line.split()
        coef = [(float(ab[i]), float(ab[i + 1])) for i in (0, 2, 4)]
        table[(MaterialKind(kind), stress)] = (dict(zip(_ML_MQ_ME, coef, strict=True)), scale,
                                               float(h_min), float(h_max))
    return table


_TABLE: dict[tuple[MaterialKind, str], tuple[dict, str, float, float]] = _parse_table(_TABLE_TEXT)


@dataclass(frozen=True)
class AllowableStress:
    """σ_lim of one material line of ISO 6336-5 Table 1 at one hardness."""

    value_MPa: float  #: σ_Hlim or σ_Flim [N/mm²]
    A: float  #: slope [N/mm² per hardness unit]
    B: float  #: intercept [N/mm²]
    scale: str  #: "HV" or "HBW"
    hardness: float  #: the hardness used (clamped to the row's range)
    in_range: bool  #: False when the given hardness was outside [h_min, h_max] and was clamped


def allowable_stress(kind: MaterialKind, quality: Quality, hardness: float,
                     stress: str) -> AllowableStress:
    """σ_Hlim (``stress="H"``) or σ_Flim (``"F"``) [N/mm²] = A·x + B (ISO 6336-5:2016, Table 1).

    Parameters
    ----------
    kind : material / heat treatment group
    quality : ML, MQ or ME
    hardness : surface hardness x in the row's scale (HV or HBW, :attr:`AllowableStress.scale`)
        [HV or HBW]; outside the row's range it is clamped (ISO's lines end there) and
        ``in_range`` is False.
    """
    rows, scale, h_min, h_max = _TABLE[(MaterialKind(kind), stress)]
    a, b = rows[Quality(quality)]
    x = min(max(float(hardness), h_min), h_max)
    return AllowableStress(a * x + b, a, b, scale, x, h_min <= hardness <= h_max)


def sigma_limits(kind: MaterialKind, quality: Quality, hardness: float) -> tuple[float, float]:
    """(σ_Hlim, σ_Flim) [N/mm²] of a material at a surface hardness (:func:`allowable_stress`)."""
    return (allowable_stress(kind, quality, hardness, "H").value_MPa,
            allowable_stress(kind, quality, hardness, "F").value_MPa)
