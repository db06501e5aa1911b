"""Hertz line contact and Weber's local approach: the contact part of a tooth compliance
(docs/theory.md §4b "Contact flattening" and "Finite-element check of the tooth compliance").

A cylinder pressed on a body with a line load w [N/mm] (force per face width) makes the
Hertzian strip of half width a and peak pressure p_0 (Johnson 1985, eqs 4.43 and 4.45):

    a = √(4 w R′ / (π E*)),   p_0 = 2 w / (π a),   1/R′ = 1/ρ_1 + 1/ρ_2,
    1/E* = (1 − ν_1²)/E_1 + (1 − ν_2²)/E_2.

Under that pressure the stresses on the symmetry axis at depth z of a half-plane are
(Johnson 1985, eq. 4.49 — the McEwen/Smith–Liu field on the axis):

    σ_z = −p_0 a / √(a² + z²),   σ_x = −p_0 [(a² + 2z²)/(a √(a² + z²)) − 2z/a].

Integrating the normal strain from the surface to the depth h (plane strain
ε_z = ((1 − ν²) σ_z − ν(1 + ν) σ_x)/E; with E′ = E/(1 − ν²), ν′ = ν/(1 − ν) in plane strain
and E′ = E, ν′ = ν in plane stress ε_z = (σ_z − ν′ σ_x)/E′) gives the approach of the surface
towards the point at depth h, exactly for the half-plane:

    δ(h) = 2 w / (π E′) · [asinh(h/a) − ν′ (h √(a² + h²) − h²)/a²]

which for h ≫ a is Weber's (1949) formula δ = 2 w (1 − ν²)/(π E) [ln(2h/a) − ν/(2(1 − ν))]
(plane strain), the local ("flattening") term of Weber & Banaschek (1953). It grows with
ln(1/a), i.e. it is nonlinear in the load.

Two uses: the FE model adds δ between the surface and the depth where it reads its global
displacement (:mod:`gearcli.model.fe`); the tooth law (:mod:`gearcli.model.pair_stiffness`)
adds δ between the surface and the tooth CENTRELINE, h the distance of the contact point from
it, as Weber (1949) did for his beam model of the tooth (his bending deflection is that of the
centreline; the flattening is measured to it). The law's pair then is

    1/k_c = [δ_1(h_1) + δ_2(h_2)] / (w b)       [mm/N]   (:func:`weber_pair_compliance`)

a secant compliance at the line load w.

Units: mm, N, MPa.

References
----------
K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, §4.2 (eqs 4.43–4.49).
C. Weber, "The deformation of loaded gears and the effect on their load-carrying capacity",
Sponsored Research (Germany), British Dept. of Scientific and Industrial Research, Report
No. 3, 1949.
C. Weber, K. Banaschek, *Formänderung und Profilrücknahme bei gerad- und schrägverzahnten
Rädern*, Schriftenreihe Antriebstechnik 11, Vieweg, Braunschweig, 1953.
R. W. Cornell, "Compliance and stress sensitivity of spur gear teeth", J. Mech. Des. 103(2),
447–459, 1981 (Weber's contact term to the centreline beside the beam compliance).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["contact_modulus", "hertz_half_width", "weber_approach", "weber_pair_compliance"]


def contact_modulus(e1_MPa: float, nu1: float, e2_MPa: float, nu2: float) -> float:
    """E* [MPa]: 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2 (Johnson 1985, §4.2)."""
    return 1.0 / ((1.0 - nu1 * nu1) / e1_MPa + (1.0 - nu2 * nu2) / e2_MPa)


def hertz_half_width(load_N_mm, reduced_radius_mm, contact_modulus_MPa: float):
    """Half width a = √(4 w R′/(π E*)) [mm] of a Hertz line contact (Johnson eq. 4.43)."""
    w = np.asarray(load_N_mm, float)
    return np.sqrt(4.0 * w * np.asarray(reduced_radius_mm, float)
                   / (math.pi * contact_modulus_MPa))


def weber_approach(load_N_mm, depth_mm, half_width_mm, youngs_MPa: float, poisson: float,
                   plane_strain: bool = True):
    """Approach δ [mm] of the contact surface to the point at depth h below it (one body).

    The exact half-plane value under the Hertz pressure (module notes). ``load_N_mm`` w
    [N/mm], ``depth_mm`` h [mm], ``half_width_mm`` a [mm]; arrays broadcast.
    """
    if plane_strain:
        e_p, nu_p = youngs_MPa / (1.0 - poisson**2), poisson / (1.0 - poisson)
    else:
        e_p, nu_p = youngs_MPa, poisson
    w = np.asarray(load_N_mm, float)
    h = np.asarray(depth_mm, float)
    a = np.asarray(half_width_mm, float)
    shape = (h * np.sqrt(a * a + h * h) - h * h) / (a * a)
    return 2.0 * w / (math.pi * e_p) * (np.arcsinh(h / a) - nu_p * shape)


def weber_pair_compliance(load_N_mm: float, reduced_radius_mm, depth1_mm, depth2_mm, *,
                          face_width_mm: float, E1_MPa: float, nu1: float, E2_MPa: float,
                          nu2: float, plane_strain: bool = True):
    """Contact compliance 1/k_c = [δ_1(h_1) + δ_2(h_2)]/(w b) [mm/N] of a tooth pair.

    The secant at the line load ``load_N_mm`` w [N/mm] (> 0) of the Hertz strip of reduced
    radius ``reduced_radius_mm`` R′ [mm], each body's flattening taken to its depth h_i [mm]
    (the tooth law: the distance of the contact point from the tooth centreline; module
    notes). Arrays broadcast.
    """
    if not load_N_mm > 0.0:
        raise ValueError(f"line load {load_N_mm!r} N/mm: Weber's term needs a load > 0")
    a = hertz_half_width(load_N_mm, reduced_radius_mm, contact_modulus(E1_MPa, nu1, E2_MPa, nu2))
    delta = (weber_approach(load_N_mm, depth1_mm, a, E1_MPa, nu1, plane_strain)
             + weber_approach(load_N_mm, depth2_mm, a, E2_MPa, nu2, plane_strain))
    return delta / (load_N_mm * face_width_mm)
