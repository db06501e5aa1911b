"""Where a loaded tooth pair touches: flank curvatures and load lines at roll position x.

On the path of contact (0 ≤ x ≤ g_α, x the pinion roll position from A [mm]) the contact point P
lies on the line of action: ρ1 = |T1P| = |T1A| + x, ρ2 = |T2P| = |T1T2| − ρ1 (involute radius
of curvature = length of the base tangent; ISO 21771, Litvin & Fuentes 2004 §10.2), and the
force acts along the line of action at the flank radii r_i = √(r_bi² + ρ_i²).

Outside the path (extended contact under load, docs/theory.md §3) a tip touches the mate's flank:

* with a tip rounding ρ_a, the rounding circle (centre Q) touches the mate's involute where the
  mate's involute normal through Q (the tangent from Q to the mate's base circle, at T')
  meets it: ρ_mate = |T'Q| − ρ_a, ρ_corner = ρ_a, P = Q − ρ_a (Q − T')/|T'Q|, force along
  T'Q (the envelope of a circle; the same distance model.gap tabulates). Positions use the
  rigid kinematics of the pair at the pinion roll x, the layout of model.gap / plotting.geometry
  (O1 = 0, O2 = (a_w, 0), line of action T1 + s n, n = (sin α_w, cos α_w)).
* a SHARP tip corner gives ρ → 0 and an unbounded Hertz stress: those samples are evaluated at
  the end of the path (A before, E after) and flagged ``clamped``.

All lengths in mm, angles in rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearcli.model import profile
from gearcli.model.gap import tooth_angles  # the pair's tooth positions (one source)
from gearcli.model.geometry import PairGeometry
from gearcli.model.rating import involute_load_line, load_line

__all__ = ["ContactPoints", "contact_points", "pair_frame", "tip_contact", "tooth_angles"]


@dataclass(frozen=True)
class ContactPoints:
    """Contact geometry of tooth pairs at pinion roll positions x (from A) [mm, rad].

    ``region``: −1 before A (gear tip on the pinion flank), 0 on the path, +1 after E (pinion
    tip on the gear flank). ``clamped``: a sharp tip corner, evaluated at A or E instead.
    Load lines are in each gear's tooth frame (see :func:`gearcli.model.rating.load_line`).
    """

    rho1_mm: np.ndarray  #: pinion flank curvature radius (ρ_a on its tip rounding)
    rho2_mm: np.ndarray  #: gear flank curvature radius (ρ_a on its tip rounding)
    y_load1_mm: np.ndarray  #: pinion load line: height of its crossing of the centreline
    alpha_fen1_rad: np.ndarray  #: pinion load line: angle to the centreline's normal
    y_load2_mm: np.ndarray  #: gear load line
    alpha_fen2_rad: np.ndarray
    region: np.ndarray
    clamped: np.ndarray


def pair_frame(geo: PairGeometry):
    """(O1, O2, T1, n) of the pair frame [mm]: O1 = 0, O2 = (a_w, 0), T1 = r_b1 (cos α_w,
    −sin α_w), n = (sin α_w, cos α_w) (plotting.geometry.mesh_layout, model.gap)."""
    a = geo.alpha_w_rad
    n = np.array([math.sin(a), math.cos(a)])
    t1 = geo.pinion.r_b_mm * np.array([math.cos(a), -math.sin(a)])
    return np.zeros(2), np.array([geo.a_w_mm, 0.0]), t1, n


def tip_contact(geo: PairGeometry, x, corner: str):
    """Tip rounding (radius ρ_a ≥ 0; 0: the sharp corner itself) of ``corner`` ('gear' before
    A, 'pinion' after E) on the mate's involute at pinion roll positions ``x`` [mm].

    The rounding centre Q touches the mate's involute where the mate's involute normal through
    Q, the tangent from Q to the mate's base circle at T', meets it: ρ_mate = |T'Q| − ρ_a,
    P = Q − ρ_a (Q − T')/|T'Q| (the envelope of a circle; the distance model.gap tabulates).

    Returns ρ_mate [mm], the contact point relative to the corner gear's centre [mm], the unit
    force on the corner tooth, its centreline angle β [rad] and the mate's flank radius at P
    [mm] (NaN where Q lies inside the mate's base circle).
    """
    o1, o2, _, _ = pair_frame(geo)
    b1, b2 = tooth_angles(geo, x)
    if corner == "gear":
        tip, own_c, mate_c, beta, mate = profile.tip_corner(geo.gear), o2, o1, b2, geo.pinion
    else:
        tip, own_c, mate_c, beta, mate = profile.tip_corner(geo.pinion), o1, o2, b1, geo.gear
    ang = beta + tip.angle_rad  # rounding centre of the drive flank (+ψ side)
    q = own_c + tip.radius_mm * np.stack([np.cos(ang), np.sin(ang)], axis=-1)
    rel = q - mate_c
    big_r = np.hypot(rel[..., 0], rel[..., 1])
    # drive-side tangent point T' lies clockwise of Q by arccos(r_b/R) (as T1 from P on the LoA)
    with np.errstate(invalid="ignore"):
        phi_t = np.arctan2(rel[..., 1], rel[..., 0]) - np.arccos(mate.r_b_mm / big_r)
        length = np.sqrt(big_r**2 - mate.r_b_mm**2)
    tangent = mate_c + mate.r_b_mm * np.stack([np.cos(phi_t), np.sin(phi_t)], axis=-1)
    unit = (q - tangent) / length[..., None]  # the mate's flank normal, away from its base
    point = q - tip.rounding_radius_mm * unit
    rho_mate = length - tip.rounding_radius_mm
    r_mate = np.sqrt(mate.r_b_mm**2 + rho_mate**2)
    # the driving pinion pushes the gear's tip along +unit; the gear pushes the pinion's tip
    # back along −unit
    force_dir = unit if corner == "gear" else -unit
    return rho_mate, point - own_c, force_dir, beta, r_mate


def contact_points(geo: PairGeometry, x_mm) -> ContactPoints:
    """Curvature radii and load lines of pairs at pinion roll positions ``x_mm`` (from A).

    See the module notes: involute contact on the path, tip-rounding contact outside it, or a
    sharp corner clamped to A/E (flagged). ``x_mm`` is flattened.
    """
    x = np.asarray(x_mm, float).ravel()
    g_a = geo.g_alpha_mm
    region = np.where(x < 0.0, -1, np.where(x > g_a, 1, 0))
    corners = ((-1, "gear", geo.gear.tip_rounding_mm), (1, "pinion", geo.pinion.tip_rounding_mm))
    clamped = np.zeros(x.size, bool)
    for side, _, rounding in corners:
        if rounding <= 0.0:
            clamped |= region == side
    rho1 = geo.A_mm + np.clip(x, 0.0, g_a)
    rho2 = geo.T1T2_mm - rho1
    y1, a1 = involute_load_line(geo.pinion, np.hypot(geo.pinion.r_b_mm, rho1))
    y2, a2 = involute_load_line(geo.gear, np.hypot(geo.gear.r_b_mm, rho2))
    for side, corner, rounding in corners:
        sel = (region == side) & ~clamped
        if not sel.any():
            continue
        rho_m, point, force_dir, beta, r_m = tip_contact(geo, x[sel], corner)
        y_c, a_c = load_line(point, force_dir, beta)
        if corner == "gear":
            rho1[sel], rho2[sel] = rho_m, rounding
            y1[sel], a1[sel] = involute_load_line(geo.pinion, r_m)
            y2[sel], a2[sel] = y_c, a_c
        else:
            rho1[sel], rho2[sel] = rounding, rho_m
            y2[sel], a2[sel] = involute_load_line(geo.gear, r_m)
            y1[sel], a1[sel] = y_c, a_c
    return ContactPoints(rho1, rho2, y1, a1, y2, a2, region, clamped)
