"""Tooth indices of the faults and the pitch deviations (docs/theory.md, "Tooth faults").

Tooth 0 of each gear are the two teeth whose drive flanks touch at the pitch point C at t = 0
(θ1 = 0); tooth i + 1 enters the mesh one mesh period after tooth i (the index follows the
rotation). Lengths in mm.
"""

from __future__ import annotations

import math

from gearcli.model import profile
from gearcli.model.geometry import PairGeometry

__all__ = ["tooth_index_offsets"]


def _slot_at(s1_mm: float, phase_mm: float, x_target_mm: float, x_lo_mm: float,
             p_b_mm: float, sign: float) -> tuple[int, int]:
    """Pitch count n and slot j of the pair at ``x_target`` when the pinion roll is ``s1``
    (core/flank.py: r = σ s1 − phase, n = floor(r/p_b), x1_j = x_lo + (r − n p_b) + j p_b)."""
    r = sign * s1_mm - phase_mm
    n = math.floor(r / p_b_mm)
    u = r - n * p_b_mm
    return n, round((x_target_mm - x_lo_mm - u) / p_b_mm)


def tooth_index_offsets(pair: PairGeometry, x_lo_mm: float, slots: dict) -> dict[str, float]:
    """The kernel's slot-0 tooth offsets (layout ``tooth_k1`` … ``tooth_k2_coast``) that make
    tooth 0 of both gears the pair whose drive flanks touch at C at θ1 = 0, and tooth i + 1 the
    one that enters after tooth i (docs/theory.md, "Tooth faults").

    Drive slot j holds pinion tooth (k1 + n − j) mod z1 (core/flank.py), so k1 = j_C − n at
    s1 = 0. The coast flank of pinion tooth 0 is at C after a pinion roll of 2 r_b1 ψ1(r_w1)
    (model.gap.coast_phase_mm, unreduced) and faces gear tooth 1 (the gear tooth behind gear
    tooth 0); coast slot j holds (k1c − n + j): k1c = n − j_C, k2c = k1c + 1.
    ``slots``: model.gap.slot_layout's ``s1_0``, ``s1c_0``.
    """
    z1, z2, p_b = pair.pinion.teeth, pair.gear.teeth, pair.p_b_mm
    x_c = pair.C_mm - pair.A_mm
    n, j = _slot_at(0.0, slots["s1_0"], x_c, x_lo_mm, p_b, 1.0)
    s_coast = 2.0 * pair.pinion.r_b_mm * float(profile.flank_half_angle(pair.pinion,
                                                                        pair.pinion.r_w_mm))
    nc, jc = _slot_at(s_coast, slots["s1c_0"], x_c, x_lo_mm, p_b, -1.0)
    return {"tooth_k1": float((j - n) % z1), "tooth_k2": float((j - n) % z2),
            "tooth_k1_coast": float((nc - jc) % z1),
            "tooth_k2_coast": float((nc - jc + 1) % z2)}
