"""Tooth stresses of a spur pair: Hertz contact stress, ISO 6336-3 root stress, ISO static rating.

Contact (flank) stress of a line contact between two cylinders of radii ρ1, ρ2 (the flank
curvatures at the contact point) carrying a normal force F over a face width b:

    σ_H = √(F E* / (π b ρ_red)),  1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2,  1/ρ_red = 1/ρ1 + 1/ρ2,

the maximum Hertz pressure p0 of two cylinders in line contact (K. L. Johnson, *Contact
Mechanics*, CUP 1985, §4.3, p0 = √(P E*/(π R)) with P = F/b, R = ρ_red). On involute flanks
ρ1 = |T1P|, ρ2 = |T2P| for a contact point P on the line of action (ISO 21771; Niemann/Winter
II, §21). At the pitch point with the nominal load this is
ISO 6336-2's σ_H0 = Z_H Z_E √(F_t (u + 1)/(d1 b u)) exactly (Z_E² = E*/π).

Root (bending) stress by ISO 6336-3:2019 Method B: the critical section is the chord between the
points where a tangent inclined 30° to the tooth centreline touches the root fillets (s_Fn); the
load F_n acts along its line of action, which crosses the centreline at a height h_Fe above that
chord at an angle α_Fen to the normal of the centreline; ρ_F is the fillet radius at the 30°
points. With F_t = F_n cos α_n (reference circle, spur):

    σ_F0 = F_t/(b m) Y_F Y_S,  Y_F = 6 (h_Fe/m) cos α_Fen / ((s_Fn/m)² cos α_n),
    Y_S = (1.2 + 0.13 L) q_s^(1/(1.21 + 2.3/L)),  L = s_Fn/h_Fe,  q_s = s_Fn/(2 ρ_F),

i.e. σ_F0 = F_n · 6 h_Fe cos α_Fen / (b s_Fn²) · Y_S (nominal bending stress of the section times
the notch factor; the radial compressive part is neglected, as in ISO). Here s_Fn, ρ_F come from
the ACTUAL generated fillet of :mod:`gearcli.model.profile` (trochoid of the tool tip rounding,
undercut included) instead of ISO's closed form, and the load may sit anywhere on the flank (the
actual contact point), not only at the outer point of single contact. Y_β = Y_B = Y_DT = 1
(spur, solid rim, ordinary contact ratio).

The contact point of a loaded pair (on the path, or on a tip outside it) is found by
:mod:`gearcli.model.contact_point`; this module holds the formulas.

Units: mm, N, rad; stresses in N/mm² = MPa.

References
----------
ISO 6336-1:2019, -2:2019, -3:2019, -5:2016 Calculation of load capacity of spur and helical gears.
K. L. Johnson, *Contact Mechanics*, Cambridge University Press 1985, §4.3.
G. Niemann, H. Winter, *Maschinenelemente* Bd. II, 2. Aufl., Springer 1989 (§21 flank curvature,
§22 Zahnfußbeanspruchung: 30°-Tangente).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from gearcli.model import profile
from gearcli.model.geometry import GearGeometry, PairGeometry
from gearcli.model.roots import brent_root

if TYPE_CHECKING:
    from scipy.interpolate import CubicSpline

__all__ = [
    "effective_modulus", "hertz_line_contact_stress", "zone_factor", "elasticity_factor",
    "contact_ratio_factor", "single_pair_contact_factors", "nominal_contact_stress",
    "RootSection", "root_section", "involute_load_line", "load_line", "form_factors",
    "root_stress", "bending_face_width", "StaticRating", "GearStatic", "static_rating",
]

#: ISO 6336-3 Method B: the critical section's tangents are inclined 30° to the centreline.
TANGENT_ANGLE_RAD = math.pi / 6.0
#: Samples of the fillet for its spline (curvature error ~ (1/n)², < 1e-6 relative).
_FILLET_SAMPLES = 1601


# --- Hertz line contact ------------------------------------------------------------------------
def effective_modulus(e1: float, nu1: float, e2: float, nu2: float) -> float:
    """Contact modulus E* [N/mm²]: 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2.

    Parameters: Young's moduli E1, E2 [N/mm²], Poisson's ratios ν1, ν2 [-].
    Reference: Johnson 1985, ch. 4 (the contact modulus of two elastic bodies).
    """
    return 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2)


def hertz_line_contact_stress(force_N, face_width_mm: float, rho1_mm, rho2_mm, e_star: float):
    """Maximum Hertz pressure of a line contact, σ_H = √(F E* / (π b ρ_red)) [N/mm²].

    Parameters
    ----------
    force_N : float or array
        Normal force F [N] (negative values count as 0).
    face_width_mm : float
        Contact length b [mm].
    rho1_mm, rho2_mm : float or array
        Radii of curvature of the two convex surfaces [mm]; 1/ρ_red = 1/ρ1 + 1/ρ2.
    e_star : float
        Contact modulus E* [N/mm²] (:func:`effective_modulus`).

    Notes
    -----
    Johnson 1985, §4.3 (two-dimensional contact of cylinders): half width a² = 4 P R/(π E*),
    p0 = 2P/(π a) = √(P E*/(π R)) with P = F/b the load per unit length and R = ρ_red.
    """
    f = np.maximum(np.asarray(force_N, float), 0.0)
    r1, r2 = np.asarray(rho1_mm, float), np.asarray(rho2_mm, float)
    inv_rho = 1.0 / r1 + 1.0 / r2
    out = np.sqrt(f * e_star * inv_rho / (math.pi * face_width_mm))
    return float(out) if out.ndim == 0 else out


# --- ISO 6336-2 factors (spur: β = 0) ------------------------------------------------------------
def zone_factor(alpha_t_rad: float, alpha_wt_rad: float) -> float:
    """Zone factor Z_H = √(2 cos α_wt / (cos² α_t sin α_wt)) [-] for spur gears (β_b = 0).

    ISO 6336-2:2019, zone factor Z_H (clause 6.1). α_t reference and α_wt operating transverse
    pressure angle [rad].
    """
    return math.sqrt(2.0 * math.cos(alpha_wt_rad)
                     / (math.cos(alpha_t_rad) ** 2 * math.sin(alpha_wt_rad)))


def elasticity_factor(e1: float, nu1: float, e2: float, nu2: float) -> float:
    """Elasticity factor Z_E = √(E*/π) [√(N/mm²)] (ISO 6336-2:2019, clause 7; E [N/mm²])."""
    return math.sqrt(effective_modulus(e1, nu1, e2, nu2) / math.pi)


def contact_ratio_factor(eps_alpha: float) -> float:
    """Contact ratio factor for spur gears, Z_ε = √((4 − ε_α)/3) [-] (ISO 6336-2:2019, cl. 8)."""
    return math.sqrt((4.0 - eps_alpha) / 3.0)


def single_pair_contact_factors(geo: PairGeometry) -> tuple[float, float, float, float]:
    """ISO 6336-2 single pair tooth contact factors (M1, M2, Z_B, Z_D) [-] for spur gears.

    M1 = tan α_wt / √([√(d_a1²/d_b1² − 1) − 2π/z1] [√(d_a2²/d_b2² − 1) − (ε_α − 1) 2π/z2]),
    M2 likewise with the gears exchanged; Z_B = max(M1, 1), Z_D = max(M2, 1)
    (ISO 6336-2:2019, clause 6.2, spur gears). M1 is exactly √(ρ_red,C/ρ_red,B): it converts
    the pitch-point Hertz stress to the pinion's inner point of single contact B (M2: the
    gear's, D). The tip form diameters (the actual end of the involutes) are used for d_a.
    """
    g1, g2 = geo.pinion, geo.gear
    eps = geo.eps_alpha
    ra1 = math.sqrt((g1.d_Fa_mm / g1.d_b_mm) ** 2 - 1.0)
    ra2 = math.sqrt((g2.d_Fa_mm / g2.d_b_mm) ** 2 - 1.0)
    tan_w = math.tan(geo.alpha_w_rad)
    m1 = tan_w / math.sqrt((ra1 - 2.0 * math.pi / g1.teeth)
                           * (ra2 - (eps - 1.0) * 2.0 * math.pi / g2.teeth))
    m2 = tan_w / math.sqrt((ra2 - 2.0 * math.pi / g2.teeth)
                           * (ra1 - (eps - 1.0) * 2.0 * math.pi / g1.teeth))
    return m1, m2, max(m1, 1.0), max(m2, 1.0)


def nominal_contact_stress(force_t_N: float, d1_mm: float, face_width_mm: float, u: float,
                           z_h: float, z_e: float) -> float:
    """Pitch-point nominal contact stress σ_H0 = Z_H Z_E √(F_t (u + 1)/(d1 b u)) [N/mm²].

    F_t tangential load on the reference circle [N], d1 pinion reference diameter [mm], b face
    width [mm], u = z2/z1. ISO 6336-2:2019, clause 5 (σ_H0) with Z_ε = Z_β = 1.
    """
    return z_h * z_e * math.sqrt(force_t_N * (u + 1.0) / (d1_mm * face_width_mm * u))


# --- ISO 6336-3 Method B: critical section from the actual fillet ------------------------------
@dataclass(frozen=True)
class RootSection:
    """Critical root section of one gear (30° tangents to the actual fillet).

    Lengths in mm in the tooth frame (gear centre at the origin, tooth centreline on +y).
    """

    s_Fn_mm: float  #: chord between the two 30° tangent points
    rho_F_mm: float  #: fillet radius of curvature at the tangent points
    y_F_mm: float  #: height of the chord above the gear centre
    tangent_angle_rad: float  #: inclination of the tangents to the centreline (π/6)


def _fillet_xy(gear: GearGeometry) -> tuple[CubicSpline, CubicSpline]:
    """Splines x(t), y(t), t ∈ [0, 1], of the counter-clockwise fillet (root → form point)."""
    from scipy.interpolate import CubicSpline  # ~0.4 s to import: only for the root section

    radius, psi = profile.fillet_points(gear, _FILLET_SAMPLES)
    t = np.linspace(0.0, 1.0, radius.size)
    return CubicSpline(t, -radius * np.sin(psi)), CubicSpline(t, radius * np.cos(psi))


def root_section(gear: GearGeometry, tangent_angle_rad: float = TANGENT_ANGLE_RAD) -> RootSection:
    """The 30° tangent section of ``gear`` from its generated fillet (ISO 6336-3 Method B).

    The fillet (:func:`gearcli.model.profile.fillet_points`: envelope of the tool tip rounding)
    is splined; the point where its tangent makes ``tangent_angle_rad`` with the centreline is
    found with Brent's method; s_Fn = 2|x|, y_F = y there and ρ_F = (x'² + y'²)^1.5/|x'y'' − y'x''|.

    Raises
    ------
    ValueError
        When no fillet point has that tangent (pressure angles ≳ 30°: ISO's construction then
        lies on the involute, outside Method B's generated-fillet formulae).
    """
    sx, sy = _fillet_xy(gear)

    def excess(t):  # tangent inclination to the centreline minus the target
        return math.atan2(abs(float(sx(t, 1))), abs(float(sy(t, 1)))) - tangent_angle_rad

    grid = np.linspace(0.0, 1.0, 201)
    vals = np.array([excess(t) for t in grid])
    idx = np.nonzero((vals[:-1] > 0.0) & (vals[1:] <= 0.0))[0]
    if idx.size == 0:
        raise ValueError(
            f"no point of the root fillet of the {gear.teeth}-tooth gear has a tangent at "
            f"{math.degrees(tangent_angle_rad):g} deg to the centreline; the ISO 6336-3 "
            "Method B section is undefined for this tooth"
        )
    k = int(idx[0])
    t = brent_root(excess, grid[k], grid[k + 1], xtol=1e-14)
    x, y = float(sx(t)), float(sy(t))
    x1, y1, x2, y2 = float(sx(t, 1)), float(sy(t, 1)), float(sx(t, 2)), float(sy(t, 2))
    rho = (x1 * x1 + y1 * y1) ** 1.5 / abs(x1 * y2 - y1 * x2)
    return RootSection(2.0 * abs(x), rho, y, tangent_angle_rad)


def involute_load_line(gear: GearGeometry, radius_mm):
    """Load line of a force acting along the involute normal at a flank radius r.

    Returns (y_L [mm], α_Fen [rad]): height where the line crosses the tooth centreline and its
    angle to the normal of the centreline. ISO 6336-3:2019 Method B with d_en = 2r:
    α_en = arccos(r_b/r), γ_e = ψ(r) (half thickness angle, ISO 21771), α_Fen = α_en − γ_e,
    y_L = r (cos γ_e − sin γ_e tan α_Fen) (so h_Fe = y_L − y_F).
    """
    r = np.asarray(radius_mm, float)
    a_en = np.arccos(np.clip(gear.r_b_mm / r, -1.0, 1.0))
    gamma = profile.flank_half_angle(gear, r)
    a_fen = a_en - gamma
    y_l = r * (np.cos(gamma) - np.sin(gamma) * np.tan(a_fen))
    return y_l, a_fen


def load_line(point_mm, direction, beta_rad):
    """Load line of a force in a tooth frame, for any contact point and direction.

    Parameters
    ----------
    point_mm : array (..., 2)
        Load point relative to the gear centre [mm] (pair frame).
    direction : array (..., 2)
        Unit direction of the force ON the tooth (pointing into it) [-].
    beta_rad : float or array
        Polar angle of the tooth centreline [rad]; the loaded (drive) flank lies on its
        counter-clockwise side.

    Returns
    -------
    (y_L [mm], α_Fen [rad]) as in :func:`involute_load_line` (which this reproduces for a
    force along the involute normal; ISO 6336-3 Method B geometry).
    """
    p, d = np.asarray(point_mm, float), np.asarray(direction, float)
    beta = np.asarray(beta_rad, float)
    ec = np.stack([np.cos(beta), np.sin(beta)], axis=-1)
    ep = np.stack([-np.sin(beta), np.cos(beta)], axis=-1)
    y, s = np.sum(p * ec, axis=-1), np.sum(p * ep, axis=-1)
    dc, dp = np.sum(d * ec, axis=-1), np.sum(d * ep, axis=-1)
    tan_fen = dc / dp  # dp < 0: the force points towards the centreline
    return y - s * tan_fen, np.arctan(tan_fen)


def form_factors(gear: GearGeometry, section: RootSection, y_load_mm, alpha_fen_rad):
    """ISO 6336-3 Method B Y_F, Y_S and h_Fe [mm] for load lines (y_L, α_Fen).

    Y_F = 6 (h_Fe/m) cos α_Fen / ((s_Fn/m)² cos α_n), h_Fe = y_L − y_F;
    Y_S = (1.2 + 0.13 L) q_s^(1/(1.21 + 2.3/L)), L = s_Fn/h_Fe, q_s = s_Fn/(2 ρ_F)
    (ISO 6336-3:2019, form factor and stress correction factor, Method B; Y_S valid for
    1 ≤ q_s < 8).
    """
    m, a_n = gear.module_mm, gear.pressure_angle_rad
    h = np.asarray(y_load_mm, float) - section.y_F_mm
    a = np.asarray(alpha_fen_rad, float)
    y_f = 6.0 * (h / m) * np.cos(a) / ((section.s_Fn_mm / m) ** 2 * math.cos(a_n))
    big_l = section.s_Fn_mm / h
    q_s = section.s_Fn_mm / (2.0 * section.rho_F_mm)
    y_s = (1.2 + 0.13 * big_l) * q_s ** (1.0 / (1.21 + 2.3 / big_l))
    return y_f, y_s, h


def root_stress(force_N, face_width_mm: float, gear: GearGeometry, section: RootSection,
                y_load_mm, alpha_fen_rad):
    """Root stress σ_F = F_n cos α_n/(b m) Y_F Y_S [N/mm²] of a normal force F_n [N].

    Equal to F_n · 6 h_Fe cos α_Fen/(b s_Fn²) · Y_S (ISO 6336-3:2019 σ_F0 with F_t = F_n cos α_n,
    Y_β = Y_B = Y_DT = 1). Negative forces count as 0.
    """
    y_f, y_s, _ = form_factors(gear, section, y_load_mm, alpha_fen_rad)
    f = np.maximum(np.asarray(force_N, float), 0.0)
    return f * math.cos(gear.pressure_angle_rad) / (face_width_mm * gear.module_mm) * y_f * y_s


def bending_face_width(geo: PairGeometry, which: str) -> float:
    """Face width for the root stress of one gear [mm]: its own, at most the narrower + 2 m
    (ISO 6336-3:2019, face width b: one module of overhang on each side)."""
    narrow = geo.narrow_face_width_mm
    own = getattr(geo, which).face_width_mm
    return min(own, narrow + 2.0 * geo.module_mm)


# --- static ISO rating of the pair ---------------------------------------------------------------
@dataclass(frozen=True)
class GearStatic:
    """Static ISO values of one gear for the nominal load (stresses in N/mm²)."""

    face_width_mm: float  #: b for the root stress (:func:`bending_face_width`)
    section: RootSection
    Y_F: float  #: form factor, load at the outer point of single contact (Method B)
    Y_S: float  #: stress correction factor, same load point
    h_Fe_mm: float  #: bending moment arm, same load point
    alpha_Fen_rad: float  #: load angle, same load point
    sigma_F0_MPa: float  #: F_t/(b m) Y_F Y_S
    Y_Fa: float  #: form factor for the load at the tip (end of the active involute)
    Y_Sa: float
    sigma_F0_tip_MPa: float  #: F_t/(b m) Y_Fa Y_Sa Y_ε (tip loading)
    Z_single: float  #: Z_B (pinion) or Z_D (gear), ISO (>= 1)
    M_single: float  #: M1 (pinion) or M2 (gear) = √(ρ_red,C/ρ_red at its single-contact point)
    sigma_H_single_MPa: float  #: Hertz at its inner point of single contact (B / D), full load
    #: ISO 6336-2 σ_H with K factors 1: Z_B (Z_D) σ_H0, σ_H0 = Z_H Z_E Z_ε √(F_t (u+1)/(d1 b u))
    sigma_H_iso_MPa: float


@dataclass(frozen=True)
class StaticRating:
    """Nominal ISO 6336 stresses of the pair for the static normal force (K factors = 1)."""

    force_normal_N: float  #: F_n = T_load / r_b2
    force_tangential_N: float  #: F_t = F_n cos α (reference circle) = T_load / r2
    ratio_u: float  #: u = z2/z1
    e_star_MPa: float  #: contact modulus E*
    Z_H: float
    Z_E: float  #: [√(N/mm²)]
    Z_eps: float
    Y_eps: float  #: 0.25 + 0.75/ε_α (tip loading)
    contact_face_width_mm: float  #: the smaller face width
    sigma_H0_MPa: float  #: Z_H Z_E √(F_t (u+1)/(d1 b u)): Hertz at the pitch point, full load
    sigma_H0_iso_MPa: float  #: with Z_ε (ISO 6336-2 nominal value of a spur pair)
    pinion: GearStatic
    gear: GearStatic


def _gear_static(geo: PairGeometry, which: str, f_t: float, y_eps: float, m_single: float,
                 sigma_h0: float, z_eps: float) -> GearStatic:
    """Method B bending at the outer point of single contact (pinion D, gear B) and at the tip.

    Outer point of single contact of the pinion: |T1D| = |T1A| + p_b; of the gear:
    |T2B| = |T2E| + p_b (ISO 6336-3:2019 Method B, d_en from ε_α; ρ = base tangent length).
    Tip: the end of the active involute (E on the pinion, A on the gear).
    """
    g = getattr(geo, which)
    if which == "pinion":
        rho_single, rho_tip = geo.D_mm, geo.E_mm
    else:
        rho_single, rho_tip = geo.T1T2_mm - geo.B_mm, geo.T1T2_mm - geo.A_mm
    sec = root_section(g)
    b = bending_face_width(geo, which)
    y_l, a_fen = involute_load_line(g, math.hypot(g.r_b_mm, rho_single))
    yf, ys, h = (float(v) for v in form_factors(g, sec, y_l, a_fen))
    y_la, a_fena = involute_load_line(g, math.hypot(g.r_b_mm, rho_tip))
    yfa, ysa, _ = (float(v) for v in form_factors(g, sec, y_la, a_fena))
    nominal = f_t / (b * g.module_mm)
    return GearStatic(b, sec, yf, ys, h, float(a_fen), nominal * yf * ys, yfa, ysa,
                      nominal * yfa * ysa * y_eps, max(m_single, 1.0), m_single,
                      m_single * sigma_h0, max(m_single, 1.0) * z_eps * sigma_h0)


def static_rating(geo: PairGeometry, force_normal_N: float, youngs_mpa: tuple[float, float],
                  poisson: tuple[float, float]) -> StaticRating:
    """ISO 6336-2/-3 nominal stresses of the pair for a static normal force F_n [N].

    Parameters
    ----------
    geo : the pair geometry
    force_normal_N : F_n = T_load/r_b2 [N]; F_t = F_n cos α on the reference circle
    youngs_mpa, poisson : (pinion, gear) E [N/mm²] and ν [-]

    Notes
    -----
    ``sigma_H0_MPa`` = Z_H Z_E √(F_t (u + 1)/(d1 b u)) is exactly the Hertz stress at the pitch
    point under the full load, and M1 σ_H0 (pinion, B), M2 σ_H0 (gear, D) the exact Hertz values
    at the inner points of single contact (``sigma_H_single_MPa``). The ISO 6336-2:2019 nominal
    value (eq. 4, spur: Z_β = 1) has the contact ratio factor Z_ε = √((4 − ε_α)/3) (cl. 8):
    σ_H0,ISO = Z_ε σ_H0 [N/mm²] (``sigma_H0_iso_MPa``), and the ISO static σ_H of each gear
    (``sigma_H_iso_MPa``, K factors 1) = Z_B σ_H0,ISO (pinion), Z_D σ_H0,ISO (gear) (eq. 2, 3).
    Bending: σ_F0 = F_t/(b m) Y_F Y_S, Y_β = Y_B = Y_DT = 1 (ISO 6336-3:2019 Method B); the
    tip-load variant uses Y_Fa Y_Sa Y_ε, Y_ε = 0.25 + 0.75/ε_α (ISO 6336-3:2006, Method C).
    All K factors (K_A, K_v, K_Hα, K_Hβ, ...) are 1: the dynamic run supplies the real loads.
    """
    g1, g2 = geo.pinion, geo.gear
    f_t = force_normal_N * math.cos(geo.pressure_angle_rad)
    u = g2.teeth / g1.teeth
    e_star = effective_modulus(youngs_mpa[0], poisson[0], youngs_mpa[1], poisson[1])
    z_h = zone_factor(geo.pressure_angle_rad, geo.alpha_w_rad)
    z_e = math.sqrt(e_star / math.pi)
    z_eps = contact_ratio_factor(geo.eps_alpha)
    y_eps = 0.25 + 0.75 / geo.eps_alpha
    b_h = min(g1.face_width_mm, g2.face_width_mm)
    s_h0 = nominal_contact_stress(f_t, g1.d_mm, b_h, u, z_h, z_e)
    m1, m2, _, _ = single_pair_contact_factors(geo)
    return StaticRating(
        force_normal_N, f_t, u, e_star, z_h, z_e, z_eps, y_eps, b_h, s_h0, z_eps * s_h0,
        _gear_static(geo, "pinion", f_t, y_eps, m1, s_h0, z_eps),
        _gear_static(geo, "gear", f_t, y_eps, m2, s_h0, z_eps),
    )
