"""ISO 6336-1 Method B internal dynamic factor K_v (ISO 6336-1:2006, clause 6.3; docs/theory.md
§10.4) for spur gears: resonance speed, resonance ratio and K_v in the four speed ranges.

Equations (ISO 6336-1:2006 numbering; units as the standard writes them):

    reduced mass per face width       m_red = π/8 (d_m1/d_b1)² d_m1²
                                              / (1/((1−q1⁴)ρ1) + 1/((1−q2⁴)ρ2 u²))
                                      [kg/mm] (eq. 30), d_m = (d_a + d_f)/2 (eq. 31), q = d_i/d_m
    resonance speed                   n_E1 = 30 000/(π z1) √(c_γα / m_red)   [min⁻¹] (eq. 6),
                                      c_γα in N/(mm·µm)
    resonance ratio                   N = n1 / n_E1 (eq. 9)
    lower limit of the main resonance N_S = 0.5 + 0.35 √(F_t K_A/(100 b)) for F_t K_A/b < 100 N/mm,
                                      else 0.85 (eqs. 11, 12)
    B_p = c′ f_pb,eff/(F_t K_A/b), B_f = c′ f_f,eff/(F_t K_A/b), B_k = |1 − c′ C_a/(F_t K_A/b)|
                                      (eqs. 15-17; deviations and tip relief in µm)
    sub-critical   N ≤ N_S:           K_v = N (C_v1 B_p + C_v2 B_f + C_v3 B_k) + 1   (eqs. 13, 14)
    main resonance N_S < N ≤ 1.15:    K_v = C_v1 B_p + C_v2 B_f + C_v4 B_k + 1       (eq. 20)
    super-critical N ≥ 1.5:           K_v = C_v5 B_p + C_v6 B_f + C_v7               (eq. 21)
    intermediate 1.15 < N < 1.5:      K_v = K_v(1.5) + (K_v(1.15) − K_v(1.5)) (1.5 − N)/0.35
                                      (eq. 22)

with C_v1 … C_v7 of the standard's table as functions of the total contact ratio ε_γ (spur:
ε_γ = ε_α). The coefficients are not reproduced from the standard here (not at hand): they were
cross-checked digit by digit in three independent public implementations that cite ISO
6336-1:2006 (a C# "Iso6336DynamicFactor" citing eqs. 13-22 and its Table 4; two Python gear
rating modules) and against each other; the reduced-mass formula and N_S likewise. The chain
n_E1 → K_v reproduces KISSsoft's Method B printouts of the NREL 5 MW gearbox
(tests/unit/test_iso_kv.py). c′ and c_γα are the rating values, with ISO's low-load factor
below 100 N/mm (the caller's: pipeline/mesh_input.iso_dynamic). K_v is reported as computed
(no clamp at 1 in the super-critical range).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

#: Upper ends of the main resonance range and lower end of the super-critical range.
N_MAIN_END = 1.15
N_SUPER = 1.5


class DynamicFactorCoefficients(NamedTuple):
    cv1: float
    cv2: float
    cv3: float
    cv4: float
    cv5: float
    cv6: float
    cv7: float


def coefficients(eps_gamma: float) -> DynamicFactorCoefficients:
    """C_v1 … C_v7 [-] for the total contact ratio ``eps_gamma`` (> 1)."""
    e = float(eps_gamma)
    if not e > 1.0:
        raise ValueError(f"total contact ratio {e:g}: ISO 6336-1 Method B needs > 1")
    if e <= 2.0:
        cv = [0.32, 0.34, 0.23, 0.90, 0.47, 0.47]
    else:
        cv = [0.32, 0.57 / (e - 0.3), 0.096 / (e - 1.56), (0.57 - 0.05 * e) / (e - 1.44), 0.47,
              0.12 / (e - 1.74)]
    if e <= 1.5:
        cv7 = 0.75
    elif e <= 2.5:
        cv7 = 0.125 * math.sin(math.pi * (e - 2.0)) + 0.875
    else:
        cv7 = 1.0
    return DynamicFactorCoefficients(*cv, cv7)


def reduced_mass_kg_mm(d_m1_mm: float, d_b1_mm: float, rho1_kg_mm3: float, rho2_kg_mm3: float,
                       ratio: float, q1: float = 0.0, q2: float = 0.0) -> float:
    """m_red [kg/mm] of a solid (q = 0) or bored (q = d_i/d_m) gear pair per unit face width
    (eq. 30); ``ratio`` u = z2/z1, d_m = (d_a + d_f)/2 [mm], densities [kg/mm³]."""
    t1 = (1.0 - q1**4) * rho1_kg_mm3
    t2 = (1.0 - q2**4) * rho2_kg_mm3 * ratio**2
    return math.pi / 8.0 * (d_m1_mm / d_b1_mm) ** 2 * d_m1_mm**2 / (1.0 / t1 + 1.0 / t2)


def resonance_speed_rpm(pinion_teeth: int, c_gamma_alpha_N_mm_um: float,
                        m_red_kg_mm: float) -> float:
    """n_E1 [min⁻¹] (eq. 6); c_γα in N/(mm·µm), m_red in kg/mm."""
    return 30000.0 / (math.pi * pinion_teeth) * math.sqrt(c_gamma_alpha_N_mm_um / m_red_kg_mm)


def main_resonance_start(line_load_N_mm: float) -> float:
    """N_S [-] (eqs. 11, 12) for the line load F_t K_A / b [N/mm]."""
    w = float(line_load_N_mm)
    return 0.5 + 0.35 * math.sqrt(w / 100.0) if w < 100.0 else 0.85


class DynamicFactor(NamedTuple):
    k_v: np.ndarray  #: [-]
    range_name: np.ndarray  #: "sub-critical", "main resonance", "intermediate", "super-critical"
    n_s: float  #: lower limit of the main resonance range [-]


def dynamic_factor(ratio_N, *, eps_gamma: float, c_prime_N_mm_um: float,
                   line_load_N_mm: float, f_pb_eff_um: float = 0.0, f_f_eff_um: float = 0.0,
                   tip_relief_um: float | None = None) -> DynamicFactor:
    """K_v [-] at the resonance ratios ``ratio_N`` [-] (array or scalar), module notes.

    Parameters
    ----------
    eps_gamma : total contact ratio [-] (spur: ε_α)
    c_prime_N_mm_um : single stiffness c′ [N/(mm·µm)]
    line_load_N_mm : F_t K_A / b [N/mm] (F_t at the reference circle)
    f_pb_eff_um, f_f_eff_um : effective base pitch and profile form deviations [µm]
    tip_relief_um : C_a [µm] (designed tip relief, or the running-in amount C_ay); None or
        0: B_k = 1, the formula at C_a = 0
    """
    w = float(line_load_N_mm)
    cv = coefficients(eps_gamma)
    b_p = c_prime_N_mm_um * f_pb_eff_um / w
    b_f = c_prime_N_mm_um * f_f_eff_um / w
    b_k = 1.0 if tip_relief_um is None else abs(1.0 - c_prime_N_mm_um * tip_relief_um / w)
    n = np.asarray(ratio_N, dtype=float)
    n_s = main_resonance_start(w)
    sub = n * (cv.cv1 * b_p + cv.cv2 * b_f + cv.cv3 * b_k) + 1.0
    main = cv.cv1 * b_p + cv.cv2 * b_f + cv.cv4 * b_k + 1.0
    sup = cv.cv5 * b_p + cv.cv6 * b_f + cv.cv7
    inter = sup + (main - sup) * (N_SUPER - n) / (N_SUPER - N_MAIN_END)
    k_v = np.where(n <= n_s, sub, np.where(n <= N_MAIN_END, main,
                                            np.where(n < N_SUPER, inter, sup)))
    names = np.where(n <= n_s, "sub-critical", np.where(
        n <= N_MAIN_END, "main resonance", np.where(n < N_SUPER, "intermediate",
                                                    "super-critical")))
    return DynamicFactor(k_v, names, n_s)
