"""Stiffness of a spur tooth pair along its roll position, and of the mesh (docs/theory.md §4b).

Per pair, the two teeth (:mod:`gearcli.model.tooth_stiffness`: bending, shear, axial,
fillet-foundation) and the contact flattening act in series; the pairs in contact act in
parallel:

    1/k_pair(x) = 1/k_c(x; w) + Σ_(pinion, gear) (1/k_b + 1/k_s + 1/k_a + 1/k_f)

1/k_c is Weber's flattening of both teeth to their centrelines at the line load w, a secant
(:func:`gearcli.model.contact_compliance.weber_pair_compliance`, docs/theory.md §4b): the Hertz
half width of the reduced radius R′ = ρ1 ρ2/(ρ1 + ρ2) of the involutes, each tooth's depth
h_P the contact point's distance from its centreline; outside the path the corner's and the
mate's depths with the path end's R′. Without a load (``load_N_mm=None``) the linear term
2/(π b E*) of Yang & Sun (1985), the law of gearcli 0.1.0.
    k_mesh(x)   = Σ_j k_pair(x + j p_b)     over the pairs with 0 ≤ x + j p_b ≤ g_α

x [mm] is the pinion roll position from A along the line of action, the grid convention of
:class:`gearcli.model.gap.GapTables` (x_lo ≤ 0 ≤ g_α ≤ x_hi). The contact point of each tooth
at x is that of the unloaded rigid kinematics (:mod:`gearcli.model.contact_point`):

* 0 ≤ x ≤ g_α: involute on involute, radii r_1 = √(r_b1² + (|T1A| + x)²),
  r_2 = √(r_b2² + (|T1T2| − |T1A| − x)²), force along the line of action;
* x < 0 (gear tip) and x > g_α (pinion tip): the tip rounding circle, or the sharp tip corner
  (rounding radius 0), touches the mate's involute where the mate's involute normal passes
  through its centre; the force acts along that normal. ``contact_point.contact_points`` clamps
  a sharp corner to A/E because its Hertz STRESS is unbounded; the compliance here takes the
  path end's curvature for the contact term, so the corner is evaluated where it is
  (``contact_point.tip_contact``, for a rounding radius ρ_a ≥ 0; checked against FE, docs/theory.md
  §4b "Corner contact").

Outside the path the corner tooth is loaded at its tip with a force turned away from the
line of action and the mate is loaded below its active profile: the pair is softer there and
softer the further out, so an entering pair engages softly (its gap, docs/theory.md §3.3, still
closes first).

The slope dk/dx [N/mm²] is the central difference (k(x + δ) − k(x − δ))/(2δ), δ = 1e-5 mm, the
step and formula of the corner-gap slope of :mod:`gearcli.model.gap` (truncation δ² k'''/6,
round-off ~1e-16 k/δ, both below 1e-9 k per mm); a cubic Hermite on (k, dk/dx) reproduces k
between the nodes (checked in tests/unit/test_tooth_stiffness.py).

Coast flanks: for symmetric teeth the coast flanks are the drive flanks of the reversed motion
(docs/theory.md §3.6), so the coast pair stiffness is the same function of the coast roll
position x1c (from the coast A, towards the coast E) as the drive stiffness of x:
``family="coast"`` returns the drive values on the same grid.

Units: mm, N, MPa, rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearcli.model.contact_compliance import weber_pair_compliance
from gearcli.model.contact_point import tip_contact
from gearcli.model.geometry import PairGeometry
from gearcli.model.rating import involute_load_line, load_line
from gearcli.model.tooth_stiffness import (
    ToothCompliance,
    default_bore_diameter,
    hertz_compliance,
    tooth_compliance_at,
    tooth_point,
    tooth_section,
)

__all__ = ["PairContact", "PairStiffness", "MeshStiffness", "pair_contact",
           "pair_stiffness", "mesh_stiffness"]

_FD_STEP_MM = 1e-5  # central-difference step of dk/dx (as model.gap's corner-gap slope)


@dataclass(frozen=True)
class PairContact:
    """Contact geometry of one tooth pair at roll positions x, per tooth, in its tooth frame.

    ``y_point`` height of the contact point along the tooth centreline, ``y_load`` where the
    load line crosses it [mm], ``angle`` the load angle α_1 to the centreline's normal [rad];
    ``region`` −1 before A (gear tip), 0 on the path, +1 after E (pinion tip);
    ``h_point`` the contact point's distance from the tooth centreline [mm] (Weber's depth of
    the contact flattening), ``reduced_radius_mm`` R′ of the Hertz strip [mm].
    """

    y_point1_mm: np.ndarray
    y_load1_mm: np.ndarray
    angle1_rad: np.ndarray
    y_point2_mm: np.ndarray
    y_load2_mm: np.ndarray
    angle2_rad: np.ndarray
    region: np.ndarray
    h_point1_mm: np.ndarray
    h_point2_mm: np.ndarray
    reduced_radius_mm: np.ndarray


def _involute_contact(gear, radius):
    """(y_P, y_L, α_1, h_P) of a force along the involute normal at ``radius`` (ISO 6336-3)."""
    h, y = tooth_point(gear, radius)
    y_l, a = involute_load_line(gear, radius)
    return y, y_l, a, h


def _reduced_radius(rho1, rho2):
    """R′ = ρ1 ρ2/(ρ1 + ρ2) [mm] of two convex radii of curvature."""
    return rho1 * rho2 / (rho1 + rho2)


def pair_contact(pair: PairGeometry, x_mm) -> PairContact:
    """Rigid-kinematics contact of a tooth pair at pinion roll positions ``x_mm`` (from A).

    Raises
    ------
    ValueError
        Where a tip lies so far outside the path that the mate's involute normal through it
        does not exist (inside the mate's base circle).
    """
    x = np.asarray(x_mm, float).ravel()
    g_a = pair.g_alpha_mm
    region = np.where(x < 0.0, -1, np.where(x > g_a, 1, 0))
    rho1 = pair.A_mm + np.clip(x, 0.0, g_a)
    out1 = list(_involute_contact(pair.pinion, np.hypot(pair.pinion.r_b_mm, rho1)))
    out2 = list(_involute_contact(pair.gear, np.hypot(pair.gear.r_b_mm, pair.T1T2_mm - rho1)))
    r_red = _reduced_radius(rho1, pair.T1T2_mm - rho1)
    for side, corner in ((-1, "gear"), (1, "pinion")):
        sel = region == side
        if not sel.any():
            continue
        _, point, force, beta, r_mate = tip_contact(pair, x[sel], corner)
        if not np.all(np.isfinite(r_mate)):
            raise ValueError(
                f"roll positions {x[sel][~np.isfinite(r_mate)].min():.6g} mm: the {corner}'s tip "
                "is too far outside the path for a contact with the mate's involute"
            )
        y_l, a = load_line(point, force, beta)
        y_p = point[..., 0] * np.cos(beta) + point[..., 1] * np.sin(beta)
        h_p = np.abs(point[..., 0] * np.sin(beta) - point[..., 1] * np.cos(beta))
        own, mate = (out2, out1) if corner == "gear" else (out1, out2)
        mate_gear = pair.pinion if corner == "gear" else pair.gear
        for k, v in enumerate((y_p, y_l, a, h_p)):
            own[k][sel] = v
        for k, v in enumerate(_involute_contact(mate_gear, r_mate)):
            mate[k][sel] = v
    return PairContact(*out1[:3], *out2[:3], region, out1[3], out2[3], r_red)


@dataclass(frozen=True)
class PairStiffness:
    """Pair stiffness on a roll grid (see the module notes)."""

    x_mm: np.ndarray  #: pinion roll positions from A [mm]
    k_N_mm: np.ndarray  #: pair stiffness [N/mm]
    dk_dx_N_mm2: np.ndarray  #: its slope along x [N/mm²]
    pinion: ToothCompliance  #: pinion tooth compliances [mm/N]
    gear: ToothCompliance  #: gear tooth compliances [mm/N]
    hertz_mm_N: np.ndarray  #: contact compliance 1/k_c at x [mm/N] (Weber, or Yang & Sun)
    load_N_mm: float | None  #: line load of Weber's secant term [N/mm]; None: Yang & Sun
    region: np.ndarray  #: −1 before A, 0 on the path, +1 after E
    family: str  #: "drive" or "coast"


def _stiffness(pair, x, kw):
    c = pair_contact(pair, x)
    t1 = tooth_compliance_at(tooth_section(pair.pinion), c.y_point1_mm, c.y_load1_mm,
                             c.angle1_rad, youngs_MPa=kw["E1"], poisson=kw["nu1"],
                             bore_diameter_mm=kw["bore1"], **kw["common"])
    t2 = tooth_compliance_at(tooth_section(pair.gear), c.y_point2_mm, c.y_load2_mm,
                             c.angle2_rad, youngs_MPa=kw["E2"], poisson=kw["nu2"],
                             bore_diameter_mm=kw["bore2"], **kw["common"])
    if kw["load"] is None:
        contact = np.full(x.shape, hertz_compliance(kw["common"]["face_width_mm"], kw["E1"],
                                                    kw["nu1"], kw["E2"], kw["nu2"]))
    else:
        contact = weber_pair_compliance(
            kw["load"], c.reduced_radius_mm, c.h_point1_mm, c.h_point2_mm, E1_MPa=kw["E1"],
            nu1=kw["nu1"], E2_MPa=kw["E2"], nu2=kw["nu2"], **kw["common"])
    return 1.0 / (contact + t1.total_mm_N + t2.total_mm_N), t1, t2, c.region, contact


def pair_stiffness(pair: PairGeometry, x_mm, *, face_width_mm: float, E1_MPa: float,
                   nu1: float, E2_MPa: float, nu2: float, bore_diameter1_mm: float | None = None,
                   bore_diameter2_mm: float | None = None, family: str = "drive",
                   plane_strain: bool = True, load_N_mm: float | None = None) -> PairStiffness:
    """Stiffness k(x) [N/mm] of one tooth pair and its slope dk/dx [N/mm²] on a roll grid.

    Parameters
    ----------
    pair : PairGeometry
        The pair (:func:`gearcli.model.geometry.compute_pair_geometry`).
    x_mm : array
        Pinion roll positions from A along the line of action [mm]; may extend outside
        [0, g_α] where a tip touches the mate (the grid of ``gap.GapTables.x_mm``).
    face_width_mm : float
        Contact face width b [mm] (the narrower gear's).
    E1_MPa, nu1, E2_MPa, nu2 : float
        Young's modulus [N/mm²] and Poisson's ratio [-] of pinion (1) and gear (2).
    bore_diameter1_mm, bore_diameter2_mm : float, optional
        Bore (rim inner) diameters [mm] for the foundation term; default
        :func:`gearcli.model.tooth_stiffness.default_bore_diameter`.
    family : {"drive", "coast"}
        Flank family; for symmetric teeth the coast values equal the drive values at the coast
        roll position (module notes).
    plane_strain : bool
        E/(1 − ν²) for the tooth, body and contact terms (default), or E (plane stress).
    load_N_mm : float, optional
        Line load w [N/mm] (normal force per face width) at which Weber's contact flattening
        to the tooth centrelines is taken as a secant compliance (the law's contact term,
        docs/theory.md §4b); the case's pipeline passes its static force / b. None: the
        linear Hertz term 2/(π b E*) of Yang & Sun (1985), the law of gearcli 0.1.0, kept for
        comparison.

    Returns
    -------
    PairStiffness
    """
    if family not in ("drive", "coast"):
        raise ValueError(f"family must be 'drive' or 'coast', got {family!r}")
    x = np.asarray(x_mm, float).ravel()
    kw = {
        "E1": E1_MPa, "nu1": nu1, "E2": E2_MPa, "nu2": nu2,
        "bore1": default_bore_diameter(pair.pinion) if bore_diameter1_mm is None
        else bore_diameter1_mm,
        "bore2": default_bore_diameter(pair.gear) if bore_diameter2_mm is None
        else bore_diameter2_mm,
        "load": None if load_N_mm is None else float(load_N_mm),
        "common": {"face_width_mm": face_width_mm, "plane_strain": plane_strain},
    }
    k, t1, t2, region, contact = _stiffness(pair, x, kw)
    h = _FD_STEP_MM
    k_plus = _stiffness(pair, x + h, kw)[0]
    k_minus = _stiffness(pair, x - h, kw)[0]
    return PairStiffness(x, k, (k_plus - k_minus) / (2.0 * h), t1, t2, contact, kw["load"],
                         region, family)


@dataclass(frozen=True)
class MeshStiffness:
    """Mesh stiffness of the rigid kinematics over one base pitch (pairs on the path only)."""

    x_mm: np.ndarray  #: roll position of the leading pair from A, 0 ≤ x < p_b [mm]
    k_mesh_N_mm: np.ndarray  #: Σ k_pair over the pairs in contact [N/mm]
    pairs: np.ndarray  #: number of pairs in contact
    mean_N_mm: float  #: mean over a base pitch (compare ISO c_γα b)
    single_max_N_mm: float  #: largest mesh stiffness with one pair (compare ISO c' b)
    single_mean_N_mm: float  #: mean over the single-pair zone
    double_max_N_mm: float  #: largest with two pairs (nan if never two)
    double_mean_N_mm: float  #: mean over the double-pair zone (nan if never two)
    pair_start_N_mm: float  #: k_pair at A (start of contact)
    pair_end_N_mm: float  #: k_pair at E (end of contact)
    pair_max_N_mm: float  #: max of k_pair on the path

    @property
    def ratio_double_single(self) -> float:
        """Mean double-pair over mean single-pair mesh stiffness [-] (2 for a square wave)."""
        return self.double_mean_N_mm / self.single_mean_N_mm


def mesh_stiffness(pair: PairGeometry, *, n_points: int = 2000, **kwargs) -> MeshStiffness:
    """Mesh stiffness k_mesh(x) = Σ_j k_pair(x + j p_b) over pairs with 0 ≤ x + j p_b ≤ g_α.

    Parameters
    ----------
    pair : PairGeometry
    n_points : int
        Samples over one base pitch (uniform, 0 ≤ x < p_b).
    **kwargs
        Material, width and bore arguments of :func:`pair_stiffness`.

    Notes
    -----
    The unloaded rigid kinematics: no extended contact, no load sharing by deflection (a
    loaded mesh adds the soft tip contacts outside the path, see :func:`pair_stiffness`).
    """
    p_b, g_a = pair.p_b_mm, pair.g_alpha_mm
    x = np.linspace(0.0, p_b, n_points, endpoint=False)
    n_max = int(math.ceil(g_a / p_b)) + 1
    shifts = x[None, :] + p_b * np.arange(n_max)[:, None]
    inside = shifts <= g_a
    path = np.linspace(0.0, g_a, 4001)
    k_path = pair_stiffness(pair, np.concatenate([path, shifts[inside]]), **kwargs).k_N_mm
    k_on = np.zeros(shifts.shape)
    k_on[inside] = k_path[path.size:]
    k_mesh = k_on.sum(axis=0)
    pairs = inside.sum(axis=0)
    one, two = pairs == 1, pairs == 2
    nan = float("nan")
    return MeshStiffness(
        x, k_mesh, pairs, float(k_mesh.mean()),
        float(k_mesh[one].max()) if one.any() else nan,
        float(k_mesh[one].mean()) if one.any() else nan,
        float(k_mesh[two].max()) if two.any() else nan,
        float(k_mesh[two].mean()) if two.any() else nan,
        float(k_path[0]), float(k_path[path.size - 1]), float(k_path[:path.size].max()),
    )
