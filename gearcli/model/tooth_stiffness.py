"""Compliance of one generated spur-gear tooth and of a Hertz line contact (docs/theory.md §4b).

One tooth is a variable-section cantilever on an elastic gear body. Its compliance at a contact
point follows from the potential (strain) energy of bending, shear and axial compression of the
tooth (Yang & Lin 1987; Tian 2004; Chaari, Fakhfakh & Haddar 2009), integrated over the ACTUAL
generated profile of :mod:`gearcli.model.profile` (trochoid fillet, undercut, involute, tip
rounding; the fillet is part of the beam as in Ma et al. 2015), plus the fillet-foundation
(gear-body) compliance of Sainsot, Velex & Duverger (2004). The pair module
:mod:`gearcli.model.pair_stiffness` puts two teeth and the Hertz contact in series.

Figure in words (tooth frame of :mod:`gearcli.model.profile`: gear centre O at the origin,
tooth centreline along +y; a point is (h, y) with h its distance from the centreline, positive
on the loaded flank):

* the fillets of the tooth meet the root circle (radius r_f) at the two points (±r_f sin θ_f,
  r_f cos θ_f): θ_f [rad] is the half angle of the tooth at the root circle, the
  "fillet-foundation point" of Sainsot et al.; S_f = 2 r_f θ_f [mm] the tooth thickness there
  (arc; the chord 2 r_f sin θ_f differs by < 0.6 % for θ_f < 0.19 rad);
* the beam is clamped on the chord through those two points, y0 = r_f cos θ_f, and runs up the
  centreline; s = y − y0 [mm] is the distance from the clamp, h(s) the half thickness of the
  generated profile at that height, A(s) = 2 h b and I(s) = (2h)³ b / 12 [mm², mm⁴];
* the contact point P = (h_P, y_P) on the flank (involute, tip rounding or tip corner) carries
  the normal force F; its line of action crosses the centreline at y_L and makes the angle α_1
  with the normal of the centreline (ISO 6336-3's α_Fen; α_1 > 0 when the force also pushes
  towards the root). F cos α_1 bends, F sin α_1 compresses;
* u_f = y_L − r_f [mm] is the distance from the load line's crossing of the centreline to the
  root circle; h_fi = r_f / r_int with r_int the bore (rim inner) radius.

Equations (compliances in mm/N; E' = E/(1 − ν²) in plane strain, E in plane stress;
G = E/(2(1 + ν)); s_L = y_L − y0):

    1/k_b = ∫0^s_P [(s_P − s) cos α_1 − h_P sin α_1]² / (E' I) ds
          = ∫0^s_P (s_L − s)² cos² α_1 / (E' I) ds                        (bending)
    1/k_s = ∫0^s_P 1.2 cos² α_1 / (G A) ds                                 (shear)
    1/k_a = ∫0^s_P sin² α_1 / (E' A) ds                                    (axial)
    1/k_f = cos² α_1 / (E' b) [L* (u_f/S_f)² + M* (u_f/S_f) + P* (1 + Q* tan² α_1)]
    X*(h_fi, θ_f) = A_X/θ_f² + B_X h_fi² + C_X h_fi/θ_f + D_X/θ_f + E_X h_fi + F_X

The two bending forms are equal because (s_P − s) cos α_1 − h_P sin α_1 = (s_L − s) cos α_1 on
the load line. The tooth law's contact term is Weber's flattening to the tooth centrelines
(:mod:`gearcli.model.contact_compliance`, docs/theory.md §4b); :func:`hertz_compliance` here is
the linear Hertz line contact of Yang & Sun (1985), k_h = π E b / (4 (1 − ν²)) for one
material, 2/(π b E*) in compliance with the contact modulus 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2
(Johnson 1985, ch. 4), the law's term in gearcli 0.1.0 (1.7–3.9 times stiffer than Weber's at
the load, docs/theory.md, FE section), kept for comparison.

Plane strain (E' = E/(1 − ν²)) is the default: the face width of a spur gear is usually large
compared with its tooth thickness (the seed: b = 100 mm, s = 15.7 mm), and a wide tooth is in
plane strain (Cornell 1981; Cooley et al. 2016 use plane strain to compare these formulas with
finite elements). Plane stress (E' = E) is a keyword away for narrow teeth. The shear modulus
is the same in both.

The Sainsot coefficients below are the ones commonly reproduced from the paper's table; the
paper itself was not accessible here. They were checked digit by digit against two independent
public implementations that cite Sainsot et al. (2004): the ROSS rotordynamics library
(``GearElementTVMS``, petrobras/ross) and the PHM-BGU gear simulation (Ben-Gurion University,
``calcInvFilletFoundationStiff``); both agree with the table below (BGU writes D_L = 4.77021e-3).
The fit's range as reproduced in ROSS is 1.4 ≤ h_fi ≤ 7, 0.01 ≤ θ_f ≤ 0.12 rad; outside it the
polynomial is extrapolated, not clamped (a 17-tooth gear has θ_f ≈ 0.18 rad).

All lengths mm, forces N, moduli MPa = N/mm², angles rad, compliances mm/N.

References
----------
D. C. H. Yang, J. Y. Lin, "Hertzian damping, tooth friction and bending elasticity in gear
impact dynamics", J. Mech. Transm. Autom. Des. 109(2), 189–196, 1987.
D. C. H. Yang, Z. S. Sun, "A rotary model for spur gear dynamics", J. Mech. Transm. Autom. Des.
107(4), 529–535, 1985.
X. Tian, *Dynamic simulation for system response of gearbox including localized gear faults*,
M.Sc. thesis, University of Alberta, 2004.
F. Chaari, T. Fakhfakh, M. Haddar, "Analytical modelling of spur gear tooth crack and influence
on gearmesh stiffness", Eur. J. Mech. A/Solids 28(3), 461–468, 2009.
H. Ma, X. Pang, R. Feng, J. Zeng, B. Wen, "Improved time-varying mesh stiffness model of cracked
spur gears", Eng. Fail. Anal. 55, 271–287, 2015 (fillet included in the beam).
P. Sainsot, P. Velex, O. Duverger, "Contribution of gear body to tooth deflections — a new
bidimensional analytical formula", J. Mech. Des. 126(4), 748–752, 2004.
R. W. Cornell, "Compliance and stress sensitivity of spur gear teeth", J. Mech. Des. 103(2),
447–459, 1981.
C. G. Cooley, C. Liu, X. Dai, R. G. Parker, "Gear tooth mesh stiffness: a comparison of
calculation approaches", Mech. Mach. Theory 105, 540–553, 2016.
K. L. Johnson, *Contact Mechanics*, Cambridge University Press, 1985, ch. 4.
ISO 6336-3:2019 (rim thickness factor Y_B); ANSI/AGMA 2101-D04 (rim thickness factor K_B).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline

from gearcli.model import profile
from gearcli.model.toothform import ToothForm

__all__ = [
    "SAINSOT_COEFFS",
    "SHEAR_FACTOR",
    "ToothSection",
    "ToothCompliance",
    "tooth_section",
    "tooth_point",
    "sainsot_coefficients",
    "tooth_compliance",
    "tooth_compliance_at",
    "hertz_compliance",
    "default_bore_diameter",
    "effective_modulus",
]

#: Sainsot, Velex & Duverger (2004), X* = A/θ_f² + B h_fi² + C h_fi/θ_f + D/θ_f + E h_fi + F:
#: (A, B, C, D, E, F) for X = L, M, P, Q (see the module notes for how they were checked).
SAINSOT_COEFFS = {
    "L": (-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3, 0.0271, 6.8045),
    "M": (60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3, 0.1624, 0.9086),
    "P": (-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3, 0.2895, 0.9236),
    "Q": (-6.2042e-5, 9.0889e-3, -4.0964e-4, 7.8297e-3, -0.1472, 0.6904),
}
#: Shear correction factor of a rectangular section in the energy method (Yang & Lin 1987).
SHEAR_FACTOR = 1.2
#: Body depth h_fi = r_f / r_int of the default bore (:func:`default_bore_diameter`).
DEFAULT_H_FI = 3.0
#: Lower end of the Sainsot fit in h_fi = r_f / r_int (as reproduced in ROSS).
SAINSOT_H_MIN = 1.4
#: Upper end of the fit: beyond it the polynomial is extrapolated and the body compliance grows
#: fast (iso_pair's pinion, mesh mean stiffness: 1.03e6 N/mm at h_fi 2.3, 0.74e6 at 6.1,
#: 0.42e6 at 11.5, 0.13e6 at 23).
SAINSOT_H_MAX = 7.0


class ContactOutsideTooth(ValueError):
    """A contact point asked for lies beyond the tooth's profile (for the dynamics: a
    deflection so large that the extended tables reach past the tip, pipeline/mesh_input)."""


_FILLET_SAMPLES = 2001  # fillet samples for its spline (as rating.py; error ~ (1/n)^4)
_GAUSS = np.polynomial.legendre.leggauss(10)  # 10-point Gauss-Legendre per panel
_PANELS = (160, 480, 64)  # panels on the fillet, the involute and the tip rounding


@dataclass(frozen=True)
class ToothSection:
    """Cumulative beam integrals of one generated tooth, tabulated along its centreline.

    ``cum[k, i]`` is the integral from the clamp y0 to ``y_mm[i]`` of, for k = 0, 1, 2,
    s^k / h³ [mm^(k−2)] (bending) and, for k = 3, 1/h [-] (shear and axial); ``rate[k, i]``
    is the integrand at ``y_mm[i]``. Between nodes the integrals are cubic Hermite in y with
    these exact derivatives (error ~ Δy⁴ f'''/384, below 1e-9 relative here).
    """

    teeth: int
    r_f_mm: float  #: root circle radius
    theta_f_rad: float  #: half angle of the tooth at the root circle (fillet-foundation point)
    y0_mm: float  #: clamp: chord through the fillet-root points, r_f cos θ_f
    y_mm: np.ndarray  #: nodes along the centreline, y0 … top of the profile
    cum: np.ndarray  #: (4, n) cumulative integrals
    rate: np.ndarray  #: (4, n) integrands

    @property
    def S_f_mm(self) -> float:
        """Tooth thickness at the root circle, S_f = 2 r_f θ_f [mm] (arc)."""
        return 2.0 * self.r_f_mm * self.theta_f_rad

    def integrals(self, y_mm) -> np.ndarray:
        """(4, …) cumulative integrals at heights ``y_mm`` (y0 ≤ y ≤ top) by cubic Hermite."""
        y = np.asarray(y_mm, float)
        top = self.y_mm[-1]
        if np.any(y < self.y0_mm - 1e-9) or np.any(y > top + 1e-9):
            raise ContactOutsideTooth(
                f"contact height outside the tooth of the {self.teeth}-tooth gear: "
                f"{y.min():.6g} … {y.max():.6g} mm, the profile spans {self.y0_mm:.6g} … "
                f"{top:.6g} mm"
            )
        y = np.clip(y, self.y0_mm, top)
        i = np.clip(np.searchsorted(self.y_mm, y, side="right") - 1, 0, self.y_mm.size - 2)
        dy = self.y_mm[i + 1] - self.y_mm[i]
        t = (y - self.y_mm[i]) / dy
        h00, h10 = (1 + 2 * t) * (1 - t) ** 2, t * (1 - t) ** 2
        h01, h11 = t * t * (3 - 2 * t), t * t * (t - 1)
        c, f = self.cum, self.rate
        return (h00 * c[:, i] + h10 * dy * f[:, i] + h01 * c[:, i + 1]
                + h11 * dy * f[:, i + 1])


def _panel_nodes(t0: float, t1: float, n: int):
    """Panel boundaries and Gauss nodes/weights of n equal panels on [t0, t1]."""
    edges = np.linspace(t0, t1, n + 1)
    x, w = _GAUSS
    half = 0.5 * (edges[1:] - edges[:-1])
    mid = 0.5 * (edges[1:] + edges[:-1])
    nodes = mid[:, None] + half[:, None] * x[None, :]
    return edges, nodes, half[:, None] * w[None, :]


def _accumulate(curve, t0: float, t1: float, n: int, y0: float):
    """Integrate one profile piece given as t -> (y, h, dy/dt) over n panels.

    Returns y, cumulative integrals (from the piece's start) and integrands at the panel
    edges.
    """
    edges, nodes, weights = _panel_nodes(t0, t1, n)
    y, h, dy = curve(nodes)
    s = y - y0
    f = np.stack([1.0 / h**3, s / h**3, s * s / h**3, 1.0 / h])
    per_panel = np.sum(f * dy * weights, axis=-1)  # (4, n)
    cum = np.concatenate([np.zeros((4, 1)), np.cumsum(per_panel, axis=1)], axis=1)
    ye, he, _ = curve(edges)
    se = ye - y0
    rate = np.stack([1.0 / he**3, se / he**3, se * se / he**3, 1.0 / he])
    return ye, cum, rate


def _involute_curve(gear: ToothForm):
    r_b = gear.r_b_mm

    def curve(r):
        psi = profile.flank_half_angle(gear, r)
        root = np.sqrt(np.maximum(r * r - r_b * r_b, 0.0))
        return r * np.cos(psi), r * np.sin(psi), np.cos(psi) + np.sin(psi) * root / r_b

    return curve


def _rounding_curve(q_h: float, q_y: float, rho: float, psi_q: float, phi_end: float):
    """Tip-rounding arc, parameter t = φ_end − φ (φ = 0 at the tip-circle tangency)."""

    def curve(t):
        phi = phi_end - t
        return (q_y + rho * np.cos(phi + psi_q), q_h + rho * np.sin(phi + psi_q),
                rho * np.sin(phi + psi_q))

    return curve


@functools.lru_cache(maxsize=64)
def tooth_section(gear: ToothForm) -> ToothSection:
    """Tabulate the beam integrals of ``gear``'s generated tooth (fillet, involute, rounding).

    Parameters
    ----------
    gear : ToothForm
        The gear (a :class:`~gearcli.model.geometry.GearGeometry` works as well).

    Returns
    -------
    ToothSection

    Raises
    ------
    ValueError
        For a pointed tooth (the half thickness vanishes at the tip) or a profile whose height
        along the centreline is not monotonic (no beam section defined).
    """
    radius, psi = profile.fillet_points(gear, _FILLET_SAMPLES)
    r_f, theta_f = float(radius[0]), float(psi[0])
    y0 = r_f * math.cos(theta_f)
    t = np.linspace(0.0, 1.0, radius.size)
    sy, sh = CubicSpline(t, radius * np.cos(psi)), CubicSpline(t, radius * np.sin(psi))
    pieces = [(lambda u: (sy(u), sh(u), sy(u, 1)), 0.0, 1.0, _PANELS[0])]
    r_fa = profile.tip_form_radius(gear)
    if r_fa < gear.r_a_mm and gear.tip_rounding_mm <= 0.0:
        raise ValueError(f"the {gear.teeth}-tooth gear is pointed: no tooth compliance at its tip")
    r_start = max(float(radius[-1]), gear.r_b_mm)
    pieces.append((_involute_curve(gear), r_start, r_fa, _PANELS[1]))
    tip = profile.tip_corner(gear)
    if tip.rounding_radius_mm > 0.0:
        rho, psi_q = tip.rounding_radius_mm, tip.angle_rad
        q_h, q_y = tip.radius_mm * math.sin(psi_q), tip.radius_mm * math.cos(psi_q)
        psi_e = float(profile.flank_half_angle(gear, r_fa))
        e_h, e_y = r_fa * math.sin(psi_e), r_fa * math.cos(psi_e)
        # angle of E − Q from the radial direction of Q towards the flank (φ = 0: the top)
        phi_end = math.atan2((e_h - q_h) * math.cos(psi_q) - (e_y - q_y) * math.sin(psi_q),
                             (e_h - q_h) * math.sin(psi_q) + (e_y - q_y) * math.cos(psi_q))
        pieces.append((_rounding_curve(q_h, q_y, rho, psi_q, phi_end), 0.0, phi_end,
                       _PANELS[2]))
    ys, cums, rates = [], [], []
    offset = np.zeros((4, 1))
    for k, (curve, a, b, n) in enumerate(pieces):
        ye, cum, rate = _accumulate(curve, a, b, n, y0)
        start = 0 if k == 0 else 1  # the first edge repeats the previous piece's last
        ys.append(ye[start:])
        cums.append(cum[:, start:] + offset)
        rates.append(rate[:, start:])
        offset = cums[-1][:, -1:]
    y = np.concatenate(ys)
    if np.any(np.diff(y) <= 0.0):
        raise ValueError(
            f"the profile of the {gear.teeth}-tooth gear is not monotonic along its centreline"
        )
    return ToothSection(gear.teeth, r_f, theta_f, y0, y, np.concatenate(cums, axis=1),
                        np.concatenate(rates, axis=1))


def tooth_point(gear: ToothForm, radius_mm):
    """Contact point (h [mm], y [mm]) on the loaded flank at a radius, in the tooth frame.

    On the involute (r ≤ r_Fa): h = r sin ψ(r), y = r cos ψ(r) (ISO 21771 half thickness angle
    ψ). On a tip rounding (r_Fa < r ≤ r_a): the point of the rounding circle (centre Q, radius
    ρ_a) at that radius, on the flank side.
    """
    r = np.asarray(radius_mm, float)
    r_fa = profile.tip_form_radius(gear)
    psi = profile.flank_half_angle(gear, np.minimum(r, r_fa))
    h, y = r * np.sin(psi), r * np.cos(psi)
    tip = profile.tip_corner(gear)
    if tip.rounding_radius_mm > 0.0:
        on_arc = r > r_fa
        if np.any(on_arc):
            rho, r_q, psi_q = tip.rounding_radius_mm, tip.radius_mm, tip.angle_rad
            cos_phi = np.clip((r * r - r_q * r_q - rho * rho) / (2.0 * rho * r_q), -1.0, 1.0)
            ang = np.arccos(cos_phi) + psi_q
            h = np.where(on_arc, r_q * math.sin(psi_q) + rho * np.sin(ang), h)
            y = np.where(on_arc, r_q * math.cos(psi_q) + rho * np.cos(ang), y)
    return h, y


def sainsot_coefficients(h_fi, theta_f_rad):
    """L*, M*, P*, Q* of Sainsot et al. (2004) at h_fi = r_f/r_int [-] and θ_f [rad]."""
    out = []
    for name in ("L", "M", "P", "Q"):
        a, b, c, d, e, f = SAINSOT_COEFFS[name]
        out.append(a / theta_f_rad**2 + b * h_fi**2 + c * h_fi / theta_f_rad
                   + d / theta_f_rad + e * h_fi + f)
    return tuple(out)


@dataclass(frozen=True)
class ToothCompliance:
    """Compliances of one tooth at its contact points [mm/N] (arrays of one shape)."""

    bending_mm_N: np.ndarray
    shear_mm_N: np.ndarray
    axial_mm_N: np.ndarray
    foundation_mm_N: np.ndarray

    @property
    def total_mm_N(self) -> np.ndarray:
        """Sum of the four (series springs) [mm/N]."""
        return self.bending_mm_N + self.shear_mm_N + self.axial_mm_N + self.foundation_mm_N


def tooth_compliance_at(section: ToothSection, y_point_mm, y_load_mm, load_angle_rad, *,
                        face_width_mm: float, youngs_MPa: float, poisson: float,
                        bore_diameter_mm: float, plane_strain: bool = True) -> ToothCompliance:
    """Single-tooth compliances for a contact height and a load line (see module notes).

    Parameters
    ----------
    section : ToothSection
        The tooth's beam table (:func:`tooth_section`).
    y_point_mm : float or array
        Height y_P [mm] of the contact point along the centreline (from the gear centre).
    y_load_mm : float or array
        Height y_L [mm] where the load line crosses the centreline.
    load_angle_rad : float or array
        α_1 [rad]: angle of the normal force to the normal of the centreline (ISO α_Fen).
    face_width_mm : float
        b [mm].
    youngs_MPa, poisson : float
        E [N/mm²] and ν [-] of the gear.
    bore_diameter_mm : float
        2 r_int [mm], the bore (or rim inner) diameter of the gear body.
    plane_strain : bool
        E' = E/(1 − ν²) (default, wide teeth) or E' = E (plane stress).

    Returns
    -------
    ToothCompliance
        1/k_b, 1/k_s, 1/k_a, 1/k_f [mm/N].
    """
    cum = section.integrals(y_point_mm)
    s_l = np.asarray(y_load_mm, float) - section.y0_mm
    a1 = np.asarray(load_angle_rad, float)
    cos2, sin2 = np.cos(a1) ** 2, np.sin(a1) ** 2
    e_eff = youngs_MPa / (1.0 - poisson**2) if plane_strain else youngs_MPa
    g = youngs_MPa / (2.0 * (1.0 + poisson))
    b = face_width_mm
    bending = cos2 / (e_eff * b) * 1.5 * (s_l * s_l * cum[0] - 2.0 * s_l * cum[1] + cum[2])
    shear = SHEAR_FACTOR * cos2 / (g * 2.0 * b) * cum[3]
    axial = sin2 / (e_eff * 2.0 * b) * cum[3]
    h_fi = section.r_f_mm / (0.5 * bore_diameter_mm)
    lc, mc, pc, qc = sainsot_coefficients(h_fi, section.theta_f_rad)
    u = (np.asarray(y_load_mm, float) - section.r_f_mm) / section.S_f_mm
    foundation = cos2 / (e_eff * b) * (lc * u * u + mc * u + pc * (1.0 + qc * np.tan(a1) ** 2))
    return ToothCompliance(bending, shear, axial, foundation)


def tooth_compliance(gear: ToothForm, radius_mm, load_angle_rad, *, face_width_mm: float,
                     youngs_MPa: float, poisson: float, bore_diameter_mm: float | None = None,
                     plane_strain: bool = True) -> ToothCompliance:
    """Single-tooth compliances of ``gear`` at contact radius r and load angle α_1.

    Parameters
    ----------
    gear : ToothForm
        The gear (generated profile of :mod:`gearcli.model.profile`).
    radius_mm : float or array
        Radius r [mm] of the contact point: on the involute (r ≤ r_Fa) or on the tip rounding
        (r_Fa < r ≤ r_a); a sharp corner is r = r_a.
    load_angle_rad : float or array
        α_1 [rad], angle of the normal force to the normal of the tooth centreline (for a force
        along the involute normal: α_1 = arccos(r_b/r) − ψ(r), ISO 6336-3's α_Fen).
    face_width_mm, youngs_MPa, poisson, plane_strain
        As :func:`tooth_compliance_at`.
    bore_diameter_mm : float, optional
        Bore (rim inner) diameter [mm]; default :func:`default_bore_diameter`.

    Returns
    -------
    ToothCompliance
        1/k_b, 1/k_s, 1/k_a, 1/k_f [mm/N] with the shape of the inputs (broadcast).
    """
    h, y = tooth_point(gear, radius_mm)
    a1 = np.asarray(load_angle_rad, float)
    y_load = y - h * np.tan(a1)
    bore = default_bore_diameter(gear) if bore_diameter_mm is None else bore_diameter_mm
    return tooth_compliance_at(tooth_section(gear), y, y_load, a1, face_width_mm=face_width_mm,
                               youngs_MPa=youngs_MPa, poisson=poisson, bore_diameter_mm=bore,
                               plane_strain=plane_strain)


def effective_modulus(e1: float, nu1: float, e2: float, nu2: float) -> float:
    """Contact modulus E* [N/mm²]: 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2 (Johnson 1985, ch. 4)."""
    return 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2)


def hertz_compliance(face_width_mm: float, e1_MPa: float, nu1: float, e2_MPa: float,
                     nu2: float) -> float:
    """Linearised Hertz line-contact compliance of a tooth pair, 1/k_h [mm/N].

    1/k_h = 2/(π b E*), which for equal materials is Yang & Sun's (1985)
    k_h = π E b / (4 (1 − ν²)); E* the contact modulus (:func:`effective_modulus`).
    Independent of the radii of curvature, so it applies unchanged at a tip rounding or corner.
    """
    return 2.0 / (math.pi * face_width_mm * effective_modulus(e1_MPa, nu1, e2_MPa, nu2))


def default_bore_diameter(gear: ToothForm) -> float:
    """Default bore (rim inner) diameter 2 r_int of a gear body, for the foundation term [mm]:
    r_int = r_f / 3 (h_fi = 3, inside Sainsot et al.'s fit range 1.4 … 7).

    Sainsot et al. (2004) clamp the gear body at r_int (a rigid shaft), so their foundation
    compliance GROWS with the body depth r_f − r_int. A case that gives no bore is taken as a
    solid gear on a shaft one third of its root diameter, the body depth at which the
    potential-energy law reproduces ISO 6336-1's stiffness of solid gears, which is measured
    (c′ with C_M = 0.8, §9.3): single-pair maximum within 0.95 … 1.13 of c′b and the mean
    within 0.96 … 1.12 of c_γα b for nine pairs (z 14 … 100, x −0.2 … 0.4, ε_α 1.49 … 1.79,
    tests/unit/test_tooth_stiffness.py). A body rigid just below the teeth (h_fi 1.4 … 1.8) is
    19-41 % stiffer than c′b (docs/theory.md §4b gives the sensitivity): give the real bore
    where it is known.
    """
    return 2.0 * gear.r_f_mm / DEFAULT_H_FI
