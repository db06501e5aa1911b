"""Manufacturing errors projected on the lines of action: pitch and profile slope deviations
and runout.

docs/theory.md §3: each pair's penetration loses e_j(t), the errors of the teeth in mesh
projected on the line of action; the kernel (core/flank.py) reads them as per-tooth flank
offsets and as a runout gap ``e sin(theta + phase)`` per gear and flank family. All lengths
in mm, angles in rad.

References
----------
ISO 1328-1:2013, Cylindrical gears - ISO system of flank tolerance classification - Part 1,
eq. (4) (single pitch tolerance) and §3 (pitch deviations close around the gear).
"""

from __future__ import annotations

import math

import numpy as np

from gearcli.core.layout import N_TABLES, TABLE_G1, TABLE_G1_COAST, TABLE_G2, TABLE_G2_COAST


def iso1328_single_pitch_tolerance_um(grade: int, d_mm: float, m_mm: float) -> float:
    """Single pitch tolerance f_pT [µm], ISO 1328-1:2013 eq. (4):
    f_pT = (0.001 d + 0.4 m_n + 5) · √2^(A − 5), A the flank tolerance class."""
    return (0.001 * d_mm + 0.4 * m_mm + 5.0) * math.sqrt(2.0) ** (grade - 5)


def cumulative_pitch_positions(values_mm, grade: int | None, seed: int | None, z: int,
                               d_mm: float, m_mm: float) -> np.ndarray:
    """Flank positions [mm] of the z teeth from single pitch deviations (zero mean).

    ``values_mm`` given: the single pitch deviations f_pt,i [mm], mean removed (they close
    around the gear, ISO 1328-1), then summed. Else an ISO grade: f_pt,i drawn from a normal
    law with σ = f_pT/3 (so nearly all lie within the tolerance) with ``seed``, then the same.
    Neither given: zeros.
    """
    if values_mm is not None:
        fpt = np.asarray(values_mm, float)
    elif grade is not None:
        tol_mm = iso1328_single_pitch_tolerance_um(grade, d_mm, m_mm) * 1e-3
        fpt = np.random.default_rng(seed).normal(0.0, tol_mm / 3.0, z)
    else:
        return np.zeros(z)
    fpt = fpt - fpt.mean()
    pos = np.cumsum(fpt)
    return pos - pos.mean()


def tooth_offsets(pos1_mm: np.ndarray, pos2_mm: np.ndarray) -> np.ndarray:
    """Per-tooth flank offsets [mm] of the kernel's tables (layout.TABLE_*, positive =
    material missing) from the teeth's flank positions of pinion and gear.

    A tooth displaced forward (in its rotation) by F: the pinion's drive flank closes on the
    gear (-F), the gear's drive flank (its trailing side) opens (+F); coast flanks opposite.
    """
    z1, z2 = len(pos1_mm), len(pos2_mm)
    offsets = np.zeros((N_TABLES, max(z1, z2)))
    offsets[TABLE_G1, :z1] = -pos1_mm
    offsets[TABLE_G2, :z2] = pos2_mm
    offsets[TABLE_G1_COAST, :z1] = pos1_mm
    offsets[TABLE_G2_COAST, :z2] = -pos2_mm
    return offsets


def profile_slope_gaps(f_ha1_mm, f_ha2_mm, x_lo_mm: float, x_hi_mm: float,
                       g_alpha_mm: float) -> np.ndarray:
    """Per-tooth profile deviation gaps [mm] of the kernel (Model.tooth_profile_gap, rows
    layout.TABLE_*, positive = material missing) at the table ends x_lo, x_hi from each
    tooth's profile slope deviation f_Hα [mm] (docs/theory.md §3.5).

    The tooth gains the material e(ρ) = f_Hα (ρ − L_α/2)/L_α of its mean profile line (ISO
    1328-1: positive f_Hα, more material at the tip), ρ the roll length from the start of its
    active profile, over the evaluation range L_α = g_α (the active profile, the path of
    contact A…E): the pinion's ρ = x (from A toward its tip at E), the gear's ρ = g_α − x
    (its tip at A); the gap is −e, linear in x, so two columns hold it exactly. Both flanks
    of a tooth have the same deviation (coast rows as drive rows).
    """
    f1 = np.asarray(f_ha1_mm, float)
    f2 = np.asarray(f_ha2_mm, float)
    ramp = (np.array([x_lo_mm, x_hi_mm]) - 0.5 * g_alpha_mm) / g_alpha_mm  # (ρ_pinion − L/2)/L
    table = np.zeros((N_TABLES, max(f1.size, f2.size), 2))
    for row in (TABLE_G1, TABLE_G1_COAST):
        table[row, :f1.size] = -np.outer(f1, ramp)
    for row in (TABLE_G2, TABLE_G2_COAST):
        table[row, :f2.size] = np.outer(f2, ramp)  # the gear's (ρ − L/2)/L = −ramp
    return table


def runout_phases(phi1_rad: float, phi2_rad: float, alpha_w_rad: float
                  ) -> dict[str, float]:
    """Phases [rad] of the runout gaps ``e sin(theta + phase)`` on the drive and coast lines
    of action (kernel parameters phase1, phase2, phase1_coast, phase2_coast).

    ``phi`` is the eccentricity's angle from the line of centres in the gear's sense of
    rotation at θ = 0; its projection on a line of action inclined by α_w (drive) or −α_w
    (coast, the mirror image about the line of centres) shifts the phase by ±α_w, and the
    gear turns the other way (signs: core/rhs.py).
    """
    return {"phase1": phi1_rad + alpha_w_rad + math.pi, "phase1_coast": phi1_rad - alpha_w_rad,
            "phase2": math.pi - phi2_rad - alpha_w_rad, "phase2_coast": alpha_w_rad - phi2_rad}
