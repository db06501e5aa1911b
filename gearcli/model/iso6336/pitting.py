"""ISO 6336-2 surface durability (pitting) of a spur pair: contact stress, influence factors, S_H.

docs/theory.md, "ISO 6336 rating", §2. Clause names are those of ISO 6336-2:2006 and :2019
(the same for the formulas here except Z_β, see :func:`helix_factor`):

    σ_H0 = Z_H Z_E Z_ε Z_β √(F_t/(d1 b) · (u + 1)/u)                         (basic formula)
    σ_H1,2 = Z_B,D σ_H0 √(K_A K_γ K_v K_Hβ K_Hα)
    σ_HG = σ_Hlim Z_NT Z_L Z_v Z_R Z_W Z_X,   σ_HP = σ_HG/S_H,min,   S_H = σ_HG/σ_H

Z_H, Z_E and the spur Z_ε are those of :mod:`gearcli.model.rating` (reused). Stresses in
N/mm², forces in N, lengths in mm.
"""

from __future__ import annotations

import math

from gearcli.model.iso6336.common import Edition
from gearcli.model.rating import contact_ratio_factor, elasticity_factor, zone_factor

__all__ = ["zone_factor", "elasticity_factor", "contact_ratio_factor", "helix_factor",
           "single_pair_factors", "nominal_contact_stress", "contact_stress",
           "lubricant_factor", "velocity_factor", "roughness_factor", "pitch_point_relative_radius",
           "work_hardening_factor", "SIZE_FACTOR"]

#: Z_X = 1 (ISO 6336-2, size factor: 1 for all materials unless a size effect is known).
SIZE_FACTOR = 1.0


def helix_factor(beta_rad: float = 0.0, edition: Edition = Edition.ISO2019) -> float:
    """Helix angle factor Z_β [-] (ISO 6336-2, clause "Helix angle factor").

    2006: Z_β = √(cos β); 2019: Z_β = 1/√(cos β). β reference helix angle [rad]; 1 for spur.
    """
    c = math.cos(beta_rad)
    return math.sqrt(c) if Edition(edition) is Edition.ISO2006 else 1.0 / math.sqrt(c)


def single_pair_factors(z1: int, z2: int, d_a1_mm: float, d_a2_mm: float, d_b1_mm: float,
                        d_b2_mm: float, alpha_wt_rad: float,
                        eps_alpha: float) -> tuple[float, float, float, float]:
    """(M1, M2, Z_B, Z_D) [-] of an external spur pair (ISO 6336-2, "Single pair tooth contact
    factors Z_B and Z_D", ε_β = 0).

    M1 = tan α_wt / √([√(d_a1²/d_b1² − 1) − 2π/z1] [√(d_a2²/d_b2² − 1) − (ε_α − 1) 2π/z2]),
    M2 = tan α_wt / √([√(d_a2²/d_b2² − 1) − 2π/z2] [√(d_a1²/d_b1² − 1) − (ε_α − 1) 2π/z1]),
    Z_B = max(M1, 1), Z_D = max(M2, 1). Diameters [mm] (tip d_a, base d_b), α_wt [rad].
    """
    t1 = math.sqrt((d_a1_mm / d_b1_mm) ** 2 - 1.0)
    t2 = math.sqrt((d_a2_mm / d_b2_mm) ** 2 - 1.0)
    tw = math.tan(alpha_wt_rad)
    m1 = tw / math.sqrt((t1 - 2.0 * math.pi / z1) * (t2 - (eps_alpha - 1.0) * 2.0 * math.pi / z2))
    m2 = tw / math.sqrt((t2 - 2.0 * math.pi / z2) * (t1 - (eps_alpha - 1.0) * 2.0 * math.pi / z1))
    return m1, m2, max(m1, 1.0), max(m2, 1.0)


def nominal_contact_stress(force_t_N: float, d1_mm: float, face_width_mm: float, u: float,
                           z_h: float, z_e: float, z_eps: float, z_beta: float) -> float:
    """σ_H0 = Z_H Z_E Z_ε Z_β √(F_t/(d1 b) (u + 1)/u) [N/mm²] (ISO 6336-2, basic formula).

    F_t nominal tangential load at the reference circle [N] (per mesh path), d1 pinion
    reference diameter [mm], b face width [mm], u = z2/z1 [-], Z_E [√(N/mm²)].
    """
    return z_h * z_e * z_eps * z_beta * math.sqrt(force_t_N / (d1_mm * face_width_mm)
                                                  * (u + 1.0) / u)


def contact_stress(sigma_h0_MPa: float, z_single: float, k_a: float, k_gamma: float,
                   k_v: float, k_h_beta: float, k_h_alpha: float) -> float:
    """σ_H = Z_B,D σ_H0 √(K_A K_γ K_v K_Hβ K_Hα) [N/mm²] (ISO 6336-2, basic formula).

    ``z_single`` is Z_B for the pinion, Z_D for the gear [-]; all K factors [-].
    """
    return z_single * sigma_h0_MPa * math.sqrt(k_a * k_gamma * k_v * k_h_beta * k_h_alpha)


def _c_zl(sigma_h_lim_MPa: float) -> float:
    """C_ZL [-]: 0.83 below σ_Hlim = 850, 0.91 above 1200, σ_Hlim/4375 + 0.6357 between."""
    s = sigma_h_lim_MPa
    return 0.83 if s < 850.0 else 0.91 if s > 1200.0 else s / 4375.0 + 0.6357


def lubricant_factor(sigma_h_lim_MPa: float, nu40_mm2_s: float) -> float:
    """Lubricant factor Z_L [-] (ISO 6336-2, "Lubrication, speed and roughness", Method B).

    Z_L = C_ZL + 4 (1 − C_ZL)/(1.2 + 134/ν40)², C_ZL of the softer material's σ_Hlim [N/mm²];
    ν40 the lubricant's kinematic viscosity at 40 °C [mm²/s].
    """
    c = _c_zl(sigma_h_lim_MPa)
    return c + 4.0 * (1.0 - c) / (1.2 + 134.0 / nu40_mm2_s) ** 2


def velocity_factor(sigma_h_lim_MPa: float, v_m_s: float) -> float:
    """Velocity factor Z_v [-] (ISO 6336-2, Method B).

    Z_v = C_Zv + 2 (1 − C_Zv)/√(0.8 + 32/v), C_Zv = C_ZL + 0.02; v pitch-line velocity at the
    reference circle [m/s] (relative to the carrier for planetary gears).
    """
    c = _c_zl(sigma_h_lim_MPa) + 0.02
    return c + 2.0 * (1.0 - c) / math.sqrt(0.8 + 32.0 / v_m_s)


def pitch_point_relative_radius(d_b1_mm: float, d_b2_mm: float, alpha_wt_rad: float) -> float:
    """ρ_red = ρ1 ρ2/(ρ1 + ρ2) [mm] at the pitch point, ρ_1,2 = ½ d_b1,2 tan α_wt (external)."""
    r1 = 0.5 * d_b1_mm * math.tan(alpha_wt_rad)
    r2 = 0.5 * d_b2_mm * math.tan(alpha_wt_rad)
    return r1 * r2 / (r1 + r2)


def roughness_factor(sigma_h_lim_MPa: float, rz1_um: float, rz2_um: float,
                     rho_red_mm: float) -> float:
    """Roughness factor Z_R [-] (ISO 6336-2, Method B).

    Z_R = (3/R_z10)^C_ZR, R_z10 = ½(R_z1 + R_z2) (10/ρ_red)^(1/3) [µm]; C_ZR = 0.15 below
    σ_Hlim = 850, 0.08 above 1200, 0.32 − 0.0002 σ_Hlim between (softer material's σ_Hlim
    [N/mm²]); flank mean roughness R_z [µm]; ρ_red at the pitch point [mm].
    """
    s = sigma_h_lim_MPa
    c = 0.15 if s < 850.0 else 0.08 if s > 1200.0 else 0.32 - 0.0002 * s
    rz10 = 0.5 * (rz1_um + rz2_um) * (10.0 / rho_red_mm) ** (1.0 / 3.0)
    return (3.0 / rz10) ** c


def work_hardening_factor(brinell_softer: float) -> float:
    """Work hardening factor Z_W [-] of a through-hardened gear meshing with a surface-hardened,
    smooth mate (ISO 6336-2:2006, "Work hardening factor"):

    Z_W = 1.2 − (HB − 130)/1700 for 130 ≤ HB ≤ 470; 1.2 below, 1.0 above (HB the softer
    gear's Brinell hardness). 1 for a pair of equal hardness (the caller's choice). The 2019
    edition's additional roughness term is not modelled.
    """
    hb = min(max(brinell_softer, 130.0), 470.0)
    return 1.2 - (hb - 130.0) / 1700.0
