"""Mesh stiffness of spur gears from ISO 6336-1:2019, Method B (docs/theory.md §4, "derived").

Single-pair (tooth) stiffness per unit face width, ISO 6336-1 §9.3:

    q' = C1 + C2/z_n1 + C3/z_n2 + C4 x1 + C5 x1/z_n1 + C6 x2 + C7 x2/z_n2 + C8 x1² + C9 x2²
         [mm·µm/N]  (ISO 6336-1 §9.3, Method B coefficients C1 … C9)
    c'_th = 1 / q'                                       [N/(mm·µm)]
    c' = c'_th C_M C_R C_B cos β
    C_M = 0.8 (correction factor), C_R = 1 (solid gear blanks),
    C_B = [1 + 0.5 (1.2 − h_fP/m_n)] [1 − 0.02 (20° − α_Pn)]   (basic rack factor)

The values hold for steel pairs; for other materials c' is scaled by E/E_st, E the pair's
equivalent modulus 2 E1 E2 / (E1 + E2) and E_st = 206 000 N/mm² (ISO 6336-1 §9.3), so the
stiffness scales with Young's modulus. Mean mesh stiffness c_γα = c' (0.75 ε_α + 0.25)
(ISO 6336-1 §9.4). For spur gears z_n = z and β = 0. Beware public code that writes the C9
term with x1² (docs/theory.md §4).

For a line load F_t K_A / b below 100 N/mm, ISO reduces c' by (F_t K_A / b / 100)^0.25 (same
clause) for the rating factors (K_v, K_Hα): ``c_prime_rating`` carries it; the dynamics use
the stiffness of the teeth, ``c_prime`` without it (docs/theory.md §4).

Units: c' in N/(mm·µm); times the face width b [mm] it is a pair stiffness in N/µm
(= 1000 N/mm).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

#: ISO 6336-1:2019 §9.3 (Method B), C1 … C9 (as docs/theory.md §4 lists them).
C_COEFFS = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)
C_M = 0.8  #: correction factor (theory vs measurement), ISO 6336-1 §9.3.2
E_ST_MPA = 206_000.0  #: reference modulus of steel E_st [N/mm²], ISO 6336-1 §9.3
C_R_SOLID = 1.0  #: gear blank factor for solid gears, §9.3.3


@dataclass(frozen=True)
class IsoStiffness:
    q_prime: float  #: minimum flexibility q' [mm·µm/N]
    c_th: float  #: theoretical single-pair stiffness c'_th [N/(mm·µm)]
    c_B: float  #: basic rack factor C_B
    material_factor: float  #: E/E_st
    load_factor: float  #: (F_t/b/100)^0.25 below 100 N/mm, else 1 (rating only)
    c_prime: float  #: single-pair stiffness c' [N/(mm·µm)]
    c_prime_rating: float  #: c' with the low-load factor, for rating factors [N/(mm·µm)]
    c_gamma_alpha: float  #: mean mesh stiffness c_γα [N/(mm·µm)]
    pair_stiffness_N_mm: float  #: c' b, one pair over the face width [N/mm]
    mesh_stiffness_N_mm: float  #: c_γα b, the mean mesh stiffness [N/mm]


def iso6336_stiffness(
    z1: int,
    z2: int,
    x1: float,
    x2: float,
    pressure_angle_deg: float,
    dedendum_coef: float,
    face_width_mm: float,
    eps_alpha: float,
    tangential_force_N: float,
    youngs_modulus_MPa: float = E_ST_MPA,
) -> IsoStiffness:
    """ISO 6336-1 Method B single-pair and mean mesh stiffness of a solid spur pair.

    Parameters
    ----------
    z1, z2 : tooth numbers (spur: virtual = actual)
    x1, x2 : profile shift coefficients
    pressure_angle_deg : basic rack pressure angle α_Pn [deg]
    dedendum_coef : basic rack dedendum h_fP / m_n
    face_width_mm : b [mm]
    eps_alpha : transverse contact ratio
    tangential_force_N : F_t at the reference circle (K_A = 1) [N], for the low-load factor
    youngs_modulus_MPa : the pair's equivalent E = 2 E1 E2 / (E1 + E2) [N/mm²]
    """
    c1, c2, c3, c4, c5, c6, c7, c8, c9 = C_COEFFS
    q = (c1 + c2 / z1 + c3 / z2 + c4 * x1 + c5 * x1 / z1 + c6 * x2 + c7 * x2 / z2
         + c8 * x1**2 + c9 * x2**2)
    c_th = 1.0 / q
    c_b = (1.0 + 0.5 * (1.2 - dedendum_coef)) * (1.0 - 0.02 * (20.0 - pressure_angle_deg))
    line_load = tangential_force_N / face_width_mm
    load_factor = (line_load / 100.0) ** 0.25 if 0.0 < line_load < 100.0 else 1.0
    material = youngs_modulus_MPa / E_ST_MPA
    c_prime = c_th * C_M * C_R_SOLID * c_b * material
    c_gamma_alpha = c_prime * (0.75 * eps_alpha + 0.25)
    return IsoStiffness(
        q_prime=q,
        c_th=c_th,
        c_B=c_b,
        material_factor=material,
        load_factor=load_factor,
        c_prime=c_prime,
        c_prime_rating=c_prime * load_factor,
        c_gamma_alpha=c_gamma_alpha,
        pair_stiffness_N_mm=c_prime * face_width_mm * 1000.0,  # N/µm -> N/mm
        mesh_stiffness_N_mm=c_gamma_alpha * face_width_mm * 1000.0,
    )


def derived_pair_stiffness(geo, rack_dedendum_coef: float, torque_gear_Nmm: float,
                           youngs_modulus_MPa: float = E_ST_MPA) -> IsoStiffness:
    """ISO stiffness of a checked pair geometry at the gear's load torque (F_t = T / r_2) for
    gears of Young's modulus E [N/mm²] (one material: the equivalent modulus is E)."""
    f_t = abs(torque_gear_Nmm) / (0.5 * geo.gear.d_mm)
    width = geo.narrow_face_width_mm
    return iso6336_stiffness(geo.pinion.teeth, geo.gear.teeth, geo.pinion.profile_shift,
                             geo.gear.profile_shift, math.degrees(geo.pressure_angle_rad),
                             rack_dedendum_coef, width, geo.eps_alpha, f_t, youngs_modulus_MPa)
