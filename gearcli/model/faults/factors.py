"""Tooth faults as per-tooth, per-position stiffness factors (docs/theory.md, "Tooth faults").

A fault changes the stiffness of the tooth pairs its tooth takes part in. The kernel multiplies
a pair's stiffness k(x1) by f_P(i1, x1) f_G(i2, x1) (docs/theory.md §4b.2); this module
computes those factors from the tooth geometry, as the ratio of the faulted to the healthy pair
stiffness of the potential-energy model (:mod:`gearcli.model.pair_stiffness`,
:mod:`gearcli.model.tooth_stiffness`) at the same rigid-kinematics contact:

    1/k_pair = 1/k_h + C_1 + C_2,      f = k_pair,faulted / k_pair = 1 / (1 + k_pair ΔC)

with C_i = 1/k_b + 1/k_s + 1/k_a + 1/k_f of tooth i and ΔC the compliance the fault adds.

* ``RootCrack`` (Tian 2004; Wu, Zuo & Parey 2008; Chaari, Fakhfakh & Haddar 2009; Mohammed,
  Rantatalo & Aidanpää 2013): a straight crack of depth q [mm] starts on the loaded side's
  fillet at ISO 6336-3's 30° tangent point (y_c, h_c) (the critical section,
  :func:`gearcli.model.rating.root_section`) and runs at the angle ν to the centreline; its
  tip lies at h_q = h_c − q sin ν from the centreline. Above the crack start, every section
  whose cracked-side half thickness h(y) exceeds h_q (below the "limit line" parallel to the
  centreline through the crack tip) keeps only the ligament from the crack line to the other
  flank: thickness h + h_q instead of 2h, i.e. the half thickness h_e = (h + h_q)/2 in
  I = (2 h_e)³ b/12, A = 2 h_e b. The bending, shear and axial integrals grow by

      ΔJ_k = ∫_{y_c}^{y_P} s^k (1/h_e³ − 1/h³) dy  (k = 0, 1, 2),   ΔJ_3 = ∫ (1/h_e − 1/h) dy

  and, as the healthy compliances are linear in the same integrals (tooth_stiffness notes),
  Δ(1/k_b) = (1/k_b) ΔQ/Q with Q = s_L² J_0 − 2 s_L J_1 + J_2, Δ(1/k_s + 1/k_a) =
  (1/k_s + 1/k_a) ΔJ_3/J_3. The foundation term is unchanged (as in the cited papers). A crack
  over a share w of the face width: the pair as parallel slices along the width (Chen & Shao
  2011), f = 1 − w (1 − f_full). The crack's own height extent (q cos ν) is neglected as in
  Tian's model; a ligament thinner than 1e-6 mm counts as broken (f → 0).
* ``Spall`` (Chaari, Baccar, Abbes & Haddar 2008): over its span along the profile the pit
  removes a share of the contact width; the Hertz and the spalled tooth's bending, shear and
  axial compliances scale with 1/(1 − lost) (the foundation does not). The share lost is the
  pit's width share w when the pit is at least as deep as the pair's static deflection δ
  (the pitted strip does not touch), else w d/δ (the strip carries its penetration δ − d:
  the secant stiffness at the static load); a full-width pit deeper than δ carries nothing
  (f = 0 over the span).
* ``ChippedTip``: above the radius r_a − Δh the tooth has lost the share w of its width, the
  same width law (w = 1: no contact above the chip). The beam below the load point is intact,
  so nothing changes where the contact is below the chip.
* ``MissingTooth``: f = 0 at every position.

Positions: a fault on tooth i of a gear meets the pair at pinion roll positions x1 [mm] from
A; the faulted tooth's own roll distance (its involute's tangent length from its base circle)
is ρ = |T1A| + x1 (pinion) or |T1T2| − |T1A| − x1 (gear), extended linearly outside the path
(a tip in contact beyond E lies beyond the pinion's last involute point). Several faults on one
tooth multiply their factors; faults on both teeth of a pair multiply (the kernel's product
f_P f_G, exact for a missing tooth, a first-order approximation otherwise).

Tooth indices (docs/theory.md, "Tooth faults"; the index of the pitch deviations): tooth 0 of
each gear are the two teeth whose drive flanks touch at the pitch point C at t = 0 (θ1 = 0);
tooth i + 1 enters the mesh one mesh period after tooth i (the index follows the rotation).
:func:`tooth_index_offsets` gives the kernel's slot-0 offsets that make it so.

Units: mm, N, rad (angles in the fault records in degrees, as named).

References
----------
X. Tian, *Dynamic simulation for system response of gearbox including localized gear faults*,
M.Sc. thesis, University of Alberta, 2004.
S. Wu, M. J. Zuo, A. Parey, "Simulation of spur gear dynamics and estimation of fault growth",
J. Sound Vib. 317, 608–624, 2008.
F. Chaari, T. Fakhfakh, M. Haddar, "Analytical modelling of spur gear tooth crack and influence
on gearmesh stiffness", Eur. J. Mech. A/Solids 28(3), 461–468, 2009.
O. D. Mohammed, M. Rantatalo, J.-O. Aidanpää, "Improving mesh stiffness calculation of cracked
gears for the purpose of vibration-based fault analysis", Eng. Fail. Anal. 34, 235–251, 2013.
Z. Chen, Y. Shao, "Dynamic simulation of spur gear with tooth root crack propagating along tooth
width and crack depth", Eng. Fail. Anal. 18, 2149–2164, 2011.
F. Chaari, W. Baccar, M. S. Abbes, M. Haddar, "Effect of spalling or tooth breakage on
gearmesh stiffness and dynamic response of a one-stage spur gear transmission", Eur. J. Mech.
A/Solids 27, 691–705, 2008.
ISO 6336-3:2019, Method B (the 30° tangent critical section).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.optimize import brentq

from gearcli.core.layout import N_TABLES, TABLE_G1, TABLE_G1_COAST, TABLE_G2, TABLE_G2_COAST
from gearcli.model.faults.records import GEARS, ChippedTip, MissingTooth, RootCrack, Spall, is_void
from gearcli.model.geometry import PairGeometry
from gearcli.model.pair_stiffness import PairStiffness, pair_contact
from gearcli.model.rating import root_section
from gearcli.model.tooth_stiffness import ToothCompliance, tooth_section
from gearcli.model.toothform import ToothForm

__all__ = ["CrackSection", "crack_section", "crack_compliance", "fault_factors",
           "revolution_stiffness", "RevolutionStiffness", "MIN_LIGAMENT_MM"]

#: Thinnest ligament half thickness [mm] the crack model integrates (a thinner one is broken).
MIN_LIGAMENT_MM = 1e-6
_GAUSS = np.polynomial.legendre.leggauss(10)
#: The factor table's rows of each gear (pinion, gear) on the drive and the coast flanks.
DRIVE_ROWS = (TABLE_G1, TABLE_G2)
COAST_ROWS = (TABLE_G1_COAST, TABLE_G2_COAST)


# --- root crack: the cracked-section integrals ------------------------------------------------
@dataclass(frozen=True)
class CrackSection:
    """Added beam integrals ΔJ_k (module notes) of a cracked tooth, cumulative from the crack.

    ``cum[k, i]`` is ΔJ_k from ``y_start_mm`` to ``y_mm[i]``; between nodes the rest of the
    integral is a 10-point Gauss-Legendre rule on the exact integrand (h from the section)."""

    y0_mm: float  #: clamp of the tooth beam (tooth_stiffness.ToothSection.y0_mm)
    y_start_mm: float  #: height of the crack start (ISO 30° tangent point)
    h_start_mm: float  #: its distance from the centreline
    h_tip_mm: float  #: h_q: the crack tip's distance from the centreline (< 0: past it)
    y_mm: np.ndarray  #: nodes from the crack start to the top of the profile
    cum: np.ndarray  #: (4, n) cumulative ΔJ_k
    half_thickness: CubicSpline  #: h(y) of the healthy tooth [mm]

    def rates(self, y) -> np.ndarray:
        """(4, …) integrands of ΔJ_k at heights ``y`` (zero below the crack start)."""
        y = np.asarray(y, float)
        h = self.half_thickness(y)
        h_e = np.where(h > self.h_tip_mm,
                       np.maximum(0.5 * (h + self.h_tip_mm), MIN_LIGAMENT_MM), h)
        s = y - self.y0_mm
        d3 = np.where(y >= self.y_start_mm, 1.0 / h_e**3 - 1.0 / h**3, 0.0)
        d1 = np.where(y >= self.y_start_mm, 1.0 / h_e - 1.0 / h, 0.0)
        return np.stack([d3, s * d3, s * s * d3, d1])

    def integrals(self, y) -> np.ndarray:
        """(4, …) ΔJ_k from the crack start to heights ``y`` (0 below the crack)."""
        y = np.atleast_1d(np.asarray(y, float))
        yc = np.clip(y, self.y_start_mm, self.y_mm[-1])
        i = np.clip(np.searchsorted(self.y_mm, yc, side="right") - 1, 0, self.y_mm.size - 1)
        a = self.y_mm[i]
        x, w = _GAUSS
        half = 0.5 * (yc - a)
        nodes = (0.5 * (yc + a))[:, None] + half[:, None] * x[None, :]
        part = np.sum(self.rates(nodes) * (half[:, None] * w[None, :]), axis=-1)
        return self.cum[:, i] + part


def crack_section(gear: ToothForm, depth_mm: float, angle_deg: float) -> CrackSection:
    """The cracked-section integrals of ``gear``'s tooth (module notes).

    Raises
    ------
    ValueError
        When the crack path reaches the other flank (q sin ν ≥ 2 h_c), or the fillet has no
        30° tangent point (rating.root_section).
    """
    sec = tooth_section(gear)
    root = root_section(gear)
    y_c, h_c = root.y_F_mm, 0.5 * root.s_Fn_mm
    h_q = h_c - depth_mm * math.sin(math.radians(angle_deg))
    if h_q <= -h_c:
        raise ValueError(
            f"a crack of depth {depth_mm:g} mm at {angle_deg:g} deg runs through the "
            f"{gear.teeth}-tooth gear's tooth (root section {2 * h_c:.4g} mm)")
    spline = CubicSpline(sec.y_mm, 1.0 / sec.rate[3])
    above = sec.y_mm[sec.y_mm > y_c]
    nodes = np.concatenate([[y_c], above])
    # the limit line meets the flank where h = h_q: a kink of the integrand, made a node
    diff = spline(nodes) - h_q
    kinks = [brentq(lambda t: float(spline(t)) - h_q, nodes[k], nodes[k + 1], xtol=1e-13)
             for k in np.nonzero(np.sign(diff[:-1]) * np.sign(diff[1:]) < 0.0)[0]]
    nodes = np.unique(np.concatenate([nodes, kinks]))
    blank = CrackSection(sec.y0_mm, y_c, h_c, h_q, nodes, np.zeros((4, nodes.size)), spline)
    x, w = _GAUSS
    half = 0.5 * np.diff(nodes)
    mid = 0.5 * (nodes[1:] + nodes[:-1])
    per_panel = np.sum(blank.rates(mid[:, None] + half[:, None] * x[None, :])
                       * (half[:, None] * w[None, :]), axis=-1)
    cum = np.concatenate([np.zeros((4, 1)), np.cumsum(per_panel, axis=1)], axis=1)
    return CrackSection(sec.y0_mm, y_c, h_c, h_q, nodes, cum, spline)


def crack_compliance(gear: ToothForm, healthy: ToothCompliance, y_point_mm, y_load_mm,
                     depth_mm: float, angle_deg: float) -> np.ndarray:
    """Compliance [mm/N] a root crack adds to a tooth loaded at height ``y_point`` with the
    load line crossing the centreline at ``y_load`` (module notes): Δ(1/k_b) + Δ(1/k_s) +
    Δ(1/k_a) = (1/k_b) ΔQ/Q + (1/k_s + 1/k_a) ΔJ_3/J_3, ``healthy`` the tooth's compliances
    there (tooth_stiffness.tooth_compliance_at)."""
    sec = tooth_section(gear)
    crack = crack_section(gear, depth_mm, angle_deg)
    j, dj = sec.integrals(y_point_mm), crack.integrals(y_point_mm)
    s_l = np.asarray(y_load_mm, float) - sec.y0_mm
    q, dq = (s_l * s_l * v[0] - 2.0 * s_l * v[1] + v[2] for v in (j, dj))
    return healthy.bending_mm_N * dq / q + (healthy.shear_mm_N + healthy.axial_mm_N) * dj[3] / j[3]


def _crack_factor(pair: PairGeometry, ps: PairStiffness, contact, g: int,
                  fault: RootCrack) -> np.ndarray:
    """f = 1 − w (1 − 1/(1 + k ΔC)) (module notes)."""
    added = crack_compliance((pair.pinion, pair.gear)[g], (ps.pinion, ps.gear)[g],
                             (contact.y_point1_mm, contact.y_point2_mm)[g],
                             (contact.y_load1_mm, contact.y_load2_mm)[g],
                             fault.depth_mm, fault.angle_deg)
    full = 1.0 / (1.0 + ps.k_N_mm * added)
    return 1.0 - fault.width * (1.0 - full)


# --- width losses: spall and chipped tip ------------------------------------------------------
def _width_factor(ps: PairStiffness, g: int, lost) -> np.ndarray:
    """Factor of the pair when its contact (Hertz) and the faulted tooth's beam (bending,
    shear, axial) keep only the share 1 − lost of the width: C' = C + lost/(1 − lost) C_w,
    f = C/C' = (1 − lost) C / ((1 − lost) C + lost C_w); 0 for lost = 1."""
    tooth = (ps.pinion, ps.gear)[g]
    c = 1.0 / ps.k_N_mm
    c_w = ps.hertz_mm_N + tooth.bending_mm_N + tooth.shear_mm_N + tooth.axial_mm_N
    keep = 1.0 - np.asarray(lost, float)
    return keep * c / (keep * c + (1.0 - keep) * c_w)


def _roll_distance(pair: PairGeometry, g: int, x) -> np.ndarray:
    """The faulted tooth's own roll distance ρ [mm] at pinion roll positions x (module notes)."""
    return pair.A_mm + x if g == 0 else pair.T1T2_mm - pair.A_mm - x


def _spall_factor(pair: PairGeometry, ps: PairStiffness, g: int, fault: Spall,
                  deflection_mm: float) -> np.ndarray:
    gear = (pair.pinion, pair.gear)[g]
    r_b = gear.r_b_mm
    if fault.diameter_mm is not None:
        r = 0.5 * fault.diameter_mm
        if r < r_b:
            raise ValueError(f"a spall at d = {fault.diameter_mm:g} mm lies inside the base "
                             f"circle of the {gear.teeth}-tooth gear (d_b {2 * r_b:.6g} mm)")
        rho_c = math.sqrt(r * r - r_b * r_b)
    else:
        rho_c = r_b * math.radians(fault.roll_angle_deg)
    # involute arc length from the base circle is ρ²/(2 r_b): the span ±L/2 about the centre
    lo = math.sqrt(max(rho_c * rho_c - r_b * fault.length_mm, 0.0))
    hi = math.sqrt(rho_c * rho_c + r_b * fault.length_mm)
    rho = _roll_distance(pair, g, ps.x_mm)
    share = 1.0 if deflection_mm <= 0.0 else min(1.0, fault.depth_mm / deflection_mm)
    lost = np.where((rho >= lo) & (rho <= hi), fault.width * share, 0.0)
    return _width_factor(ps, g, lost)


def _chip_factor(pair: PairGeometry, ps: PairStiffness, g: int, fault: ChippedTip):
    gear = (pair.pinion, pair.gear)[g]
    r_c = gear.r_a_mm - fault.height_mm
    rho_c = math.sqrt(max(r_c * r_c - gear.r_b_mm**2, 0.0))
    lost = np.where(_roll_distance(pair, g, ps.x_mm) > rho_c, fault.width, 0.0)
    return _width_factor(ps, g, lost)


def fault_factors(pair: PairGeometry, stiffness: PairStiffness, faults, *,
                  deflection_mm: float = 0.0) -> np.ndarray:
    """The kernel's factor table f[r, i, m] (docs/theory.md §4b.2) for ``faults``.

    Rows as the kernel's (core.layout TABLE_*): drive pinion, drive gear, coast pinion, coast
    gear. A crack (on the drive side's fillet: closed under coast load) and a spall (on the
    drive flank) act on the drive rows; a missing tooth and a chipped tip on both families
    (symmetric teeth: the coast pair at its own roll position x1 is the drive pair's mirror).

    Parameters
    ----------
    pair : PairGeometry
    stiffness : PairStiffness
        The healthy pair stiffness at the table's positions ``stiffness.x_mm`` (pinion roll
        positions from A [mm], :func:`gearcli.model.pair_stiffness.pair_stiffness`; in a run
        ``pipeline.kernel_input.factor_positions``).
    faults : iterable
        :class:`RootCrack`, :class:`Spall`, :class:`ChippedTip`, :class:`MissingTooth`.
    deflection_mm : float
        The pair's static deflection [mm] that a spall's depth is compared with (0: every
        spall is deeper).

    Returns
    -------
    ndarray
        (4, max(z1, z2), n) factors [-], ones where no fault acts; zero-size faults
        (:func:`is_void`) leave exact ones.
    """
    x = np.asarray(stiffness.x_mm, float)
    teeth = (pair.pinion.teeth, pair.gear.teeth)
    table = np.ones((N_TABLES, max(teeth), x.size))
    contact = None
    for fault in faults:
        g = GEARS.index(fault.gear)
        if fault.tooth >= teeth[g]:
            raise ValueError(f"the {fault.gear} has {teeth[g]} teeth (0 ... {teeth[g] - 1}): "
                             f"no tooth {fault.tooth}")
        if is_void(fault):
            continue
        if isinstance(fault, MissingTooth):
            f = np.zeros(x.size)
        elif isinstance(fault, RootCrack):
            contact = contact or pair_contact(pair, x)
            f = _crack_factor(pair, stiffness, contact, g, fault)
        elif isinstance(fault, Spall):
            f = _spall_factor(pair, stiffness, g, fault, deflection_mm)
        elif isinstance(fault, ChippedTip):
            f = _chip_factor(pair, stiffness, g, fault)
        else:
            raise TypeError(f"not a tooth fault: {fault!r}")
        both = isinstance(fault, (MissingTooth, ChippedTip))
        for row in ((DRIVE_ROWS[g], COAST_ROWS[g]) if both else (DRIVE_ROWS[g],)):
            table[row, fault.tooth] *= f
    return table


@dataclass(frozen=True)
class RevolutionStiffness:
    """Rigid-kinematics mesh stiffness over whole mesh periods from t = 0, faulted and healthy."""

    s1_mm: np.ndarray  #: pinion roll from t = 0, r_b1 θ1 [mm]
    k_mesh_N_mm: np.ndarray  #: Σ_j k_pair(x_j) f_P f_G over the pairs on the path [N/mm]
    healthy_N_mm: np.ndarray  #: Σ_j k_pair(x_j) [N/mm]


def revolution_stiffness(pair: PairGeometry, stiffness_at, faults, *, pitches: int | None = None,
                         points_per_pitch: int = 200,
                         deflection_mm: float = 0.0) -> RevolutionStiffness:
    """The mesh stiffness of the unloaded rigid kinematics over ``pitches`` mesh periods
    (default one pinion revolution, z1) with the faults' factors at each pair's own position.

    At pinion roll s1 the pair m (holding pinion tooth m mod z1 and gear tooth m mod z2,
    docs/theory.md "Tooth faults") is at x = x_C + s1 − m p_b; the pairs on the path
    (0 ≤ x ≤ g_α) add up (pair_stiffness.mesh_stiffness, here with the factors evaluated at
    their exact positions, not interpolated). ``stiffness_at``: x [mm] -> the healthy
    PairStiffness there (pair_stiffness.pair_stiffness with the case's material and bores).
    """
    z1, z2, p_b, g_a = pair.pinion.teeth, pair.gear.teeth, pair.p_b_mm, pair.g_alpha_mm
    pitches = z1 if pitches is None else pitches
    s1 = np.arange(pitches * points_per_pitch) * (p_b / points_per_pitch)
    x_c = pair.C_mm - pair.A_mm
    m_lo = math.floor((x_c - g_a) / p_b) - 1
    m = np.arange(m_lo, pitches + math.ceil(x_c / p_b) + 2)
    x = x_c + s1[None, :] - p_b * m[:, None]
    on = (x >= 0.0) & (x <= g_a)
    ps = stiffness_at(x[on])
    table = fault_factors(pair, ps, faults, deflection_mm=deflection_mm)
    mm = np.broadcast_to(m[:, None], x.shape)[on]
    col = np.arange(mm.size)
    k = np.zeros(x.shape)
    healthy = np.zeros(x.shape)
    healthy[on] = ps.k_N_mm
    k[on] = ps.k_N_mm * table[TABLE_G1, mm % z1, col] * table[TABLE_G2, mm % z2, col]
    return RevolutionStiffness(s1, k.sum(axis=0), healthy.sum(axis=0))
