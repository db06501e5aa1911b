"""ISO 1328-1:2013 flank tolerance classes ("accuracy grades") and seeded random deviations of
a grade (docs/theory.md §10.5).

Tolerances of flank tolerance class A (1 … 11) for a gear of reference diameter d [mm] and
(normal) module m [mm], ISO 1328-1:2013 §5.3, in µm, each the class-5 value times the step
factor √2^(A − 5) (§5.2.2):

    f_pT  = (0.001 d + 0.4 m + 5)                 single pitch            eq. (5)
    F_pT  = (0.002 d + 0.55 √d + 0.7 m + 12)      total cumulative pitch  eq. (6)
    f_HαT = (0.4 m + 0.001 d + 4)                 profile slope           eq. (7)
    f_fαT = (0.55 m + 5)                          profile form            eq. (8)
    F_αT  = √(f_HαT² + f_fαT²)                    total profile           eq. (9), unrounded terms

Rounding of the tolerance values (§5.2.3): above 10 µm to the nearest 1 µm, from 5 to 10 µm to
the nearest 0.5 µm, below 5 µm to the nearest 0.1 µm. The simulation draws from the unrounded
values (a tolerance, not a table lookup).

Random deviations of a grade (per tooth, reproducible with a seed): f_pt,i and f_Hα,i from
normal laws with σ = f_pT/3 and σ = f_HαT/3 (nearly all within the tolerance, ±3 σ), drawn in
that order from ``numpy.random.default_rng(seed)``, so the pitch deviations are exactly those
of ``errors.pitch_deviation.<gear>.iso1328_grade`` with the same seed (model/errors.py).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearcli.model.errors import iso1328_single_pitch_tolerance_um

#: Flank tolerance classes of ISO 1328-1:2013 (§5.1).
GRADES = range(1, 12)


def step_factor(grade: int) -> float:
    """√2^(A − 5), ISO 1328-1:2013 §5.2.2."""
    if grade not in GRADES:
        raise ValueError(f"ISO 1328-1:2013 flank tolerance class must be 1..11, got {grade!r}")
    return math.sqrt(2.0) ** (grade - 5)


def round_tolerance_um(value_um: float) -> float:
    """A tolerance [µm] rounded as ISO 1328-1:2013 §5.2.3 (module notes); halves away from 0."""
    def half_up(x: float) -> float:
        return math.floor(x + 0.5)

    if value_um > 10.0:
        return half_up(value_um)
    if value_um >= 5.0:
        return half_up(2.0 * value_um) / 2.0
    return half_up(10.0 * value_um) / 10.0


@dataclass(frozen=True)
class Tolerances:
    """ISO 1328-1:2013 tolerances of one gear [µm], unrounded (module notes)."""

    grade: int
    f_pT_um: float  #: single pitch, eq. (5)
    F_pT_um: float  #: total cumulative pitch, eq. (6)
    f_HalphaT_um: float  #: profile slope, eq. (7)
    f_falphaT_um: float  #: profile form, eq. (8)
    F_alphaT_um: float  #: total profile, eq. (9)

    def rounded(self) -> dict[str, float]:
        """The tolerances as the standard states them (§5.2.3), by field name."""
        return {k: round_tolerance_um(v) for k, v in vars(self).items() if k != "grade"}


def tolerances(grade: int, d_mm: float, m_mm: float) -> Tolerances:
    """The tolerances of flank tolerance class ``grade`` for reference diameter ``d_mm`` and
    module ``m_mm`` [mm] (module notes)."""
    k = step_factor(grade)
    f_h = (0.4 * m_mm + 0.001 * d_mm + 4.0) * k
    f_f = (0.55 * m_mm + 5.0) * k
    return Tolerances(
        grade=grade,
        f_pT_um=iso1328_single_pitch_tolerance_um(grade, d_mm, m_mm),
        F_pT_um=(0.002 * d_mm + 0.55 * math.sqrt(d_mm) + 0.7 * m_mm + 12.0) * k,
        f_HalphaT_um=f_h, f_falphaT_um=f_f, F_alphaT_um=math.hypot(f_h, f_f))


@dataclass(frozen=True)
class GradeDeviations:
    """Seeded random deviations of one gear of a grade, per tooth [µm] (module notes)."""

    tolerances: Tolerances
    seed: int
    single_pitch_um: np.ndarray  #: f_pt,i (as drawn; the simulation removes their mean)
    profile_slope_um: np.ndarray  #: f_Hα,i


def draw_deviations(grade: int, d_mm: float, m_mm: float, teeth: int,
                    seed: int) -> GradeDeviations:
    """Per-tooth f_pt,i and f_Hα,i of a gear of flank tolerance class ``grade`` (module notes):
    the same ``seed`` gives the same deviations."""
    tol = tolerances(grade, d_mm, m_mm)
    rng = np.random.default_rng(seed)
    f_pt = rng.normal(0.0, tol.f_pT_um / 3.0, teeth)  # first: as model/errors.py draws them
    f_h = rng.normal(0.0, tol.f_HalphaT_um / 3.0, teeth)
    return GradeDeviations(tol, seed, f_pt, f_h)


def gear_seeds(seed: int) -> tuple[int, int]:
    """(pinion, gear) seeds of a case's ``accuracy.seed``: different draws for the two gears."""
    return seed, (seed + 1) % 2**32
