"""Flank-gap tables G1(x), G2(x) of a tooth pair along its path (docs/theory.md §3).

The drive-flank penetration of a tooth pair is (docs/theory.md §3, core/rhs.py)

    p = δ − G1(x1) − G2(x2) − e,      x1 = pinion roll position, x2 = x1 − δ,

with x measured along the line of action from the start of active contact A [mm]. The
decomposition is exact for rigid involute teeth: the distance of a point Q of one gear from the
mating involute flank, measured along that involute's normal (the tangent from Q to the mate's
base circle), is r_b·(ψ_Q − ψ_flank(R_Q)) where ψ are polar angles in the mate's tooth frame
(two involutes of one base circle rotated by Δψ are a constant r_b·Δψ apart along their
common normals; ISO 21771 tooth-thickness relation for ψ_flank). That distance changes with the
mate's rotation by exactly r_b per radian, so

* G2 (a function of the GEAR's roll position) holds the gap of the gear's tip corner — or its
  tip-rounding circle, centre distance minus ρ_a — to the pinion flank before A (approach),
  and the gear's own profile modifications (tip relief near A, root relief near E);
* G1 (a function of the PINION's roll position) holds the gap of the pinion's tip corner to
  the gear flank beyond E (recess), and the pinion's modifications (tip relief near E, root
  relief near A).

Inside the path, involute meets involute and the gap is zero (plus modifications). Under load δ
closes the small gaps outside the path, so an entering pair touches before A and its force rises
from zero (extended / premature contact); forces and moment arms follow from the same G
(contact forces are gradients of one potential). ``engagement='rigid'`` keeps only the path
0 ≤ x ≤ g_α (the classic model; a pair enters with the full deflection).

Profile modifications (tip/root relief, linear or parabolic; ISO 21771 §5.5 / ISO 6336-1
Annex on profile modification): amount C at the tip (root) over a length L of the path of
contact, C·ξ^n with ξ the fraction of L (n = 1 linear, n = 2 parabolic), held at C beyond the
active profile.

All lengths in mm, angles in rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearcli.core.layout import (
    N_TABLES,
    TABLE_G1,
    TABLE_G1_COAST,
    TABLE_G2,
    TABLE_G2_COAST,
    TABLE_GAP,
    TABLE_ROWS,
    TABLE_SLOPE,
)
from gearcli.model import profile
from gearcli.model.geometry import GearGeometry, PairGeometry

_FD_STEP_MM = 1e-5  # central-difference step for the corner-gap slope (error ~ h² G''' < 1e-9)


@dataclass(frozen=True)
class Relief:
    """One profile relief [mm]: amount, and its extent as a length along the path or as the
    diameter where it starts on the gear's flank."""

    amount_mm: float
    length_mm: float | None = None
    start_diameter_mm: float | None = None
    shape: str = "linear"  # or "parabolic"


@dataclass(frozen=True)
class Modifications:
    pinion_tip: Relief | None = None
    gear_tip: Relief | None = None
    pinion_root: Relief | None = None
    gear_root: Relief | None = None


@dataclass(frozen=True)
class GapTables:
    """Tabulated gaps on one uniform grid ``x_lo … x_hi`` [mm] (roll position from A).

    ``tables[k, TABLE_GAP, i]`` is the gap [mm] and ``tables[k, TABLE_SLOPE, i]`` its slope [-]
    of table k (TABLE_G1, TABLE_G2, TABLE_G1_COAST, TABLE_G2_COAST) at ``x[i]``: the layout of
    :mod:`gearcli.core.layout`.
    """

    x_mm: np.ndarray
    tables: np.ndarray
    engagement: str

    @property
    def x_lo(self) -> float:
        return float(self.x_mm[0])

    @property
    def x_hi(self) -> float:
        return float(self.x_mm[-1])


# --- kinematics of the tooth pair that is in contact at the pitch point C when Δs = 0 --------
def tooth_angles(geo: PairGeometry, x_mm):
    """Polar angles of the centrelines of the pinion tooth (about O1 = (0, 0)) and the gear
    tooth (about O2 = (a_w, 0)) of one pair at rigid-kinematic roll position x [mm].

    The pinion turns counter-clockwise, the gear clockwise; the line of action runs from T1
    (below the line of centres) to T2. At C the pinion tooth lies clockwise of C and the gear
    tooth above it (the same layout as the drawing, plotting.geometry.mesh_layout).
    """
    ds = np.asarray(x_mm, float) - (geo.C_mm - geo.A_mm)
    psi1 = float(profile.flank_half_angle(geo.pinion, geo.pinion.r_w_mm))
    psi2 = float(profile.flank_half_angle(geo.gear, geo.gear.r_w_mm))
    beta1 = -psi1 + ds / geo.pinion.r_b_mm
    beta2 = math.pi - psi2 - ds / geo.gear.r_b_mm
    return beta1, beta2


def _flank_gap(mate: GearGeometry, centre, mate_beta, px, py, rounding_mm: float):
    """Gap [mm] of points (px, py) from the mate's drive flank, along the mate's involute normal.

    gap = r_b (ψ − ψ_flank(R)) − ρ: ψ the points' polar angle in the mate's tooth frame (drive
    flank on the +ψ side), ψ_flank(R) the flank's half angle at their radius (ISO 21771).
    NaN where the point lies inside the mate's base circle (no involute to touch).
    """
    dx, dy = px - centre[0], py - centre[1]
    radius = np.hypot(dx, dy)
    psi = np.arctan2(dy, dx) - mate_beta
    psi = (psi + math.pi) % (2.0 * math.pi) - math.pi
    ok = radius > mate.r_b_mm
    r = np.where(ok, radius, mate.r_b_mm * 2.0)
    gap = mate.r_b_mm * (psi - profile.flank_half_angle(mate, r)) - rounding_mm
    return np.where(ok, gap, np.nan)


def approach_gap(geo: PairGeometry, x_mm):
    """Gap of the gear's tip (corner or rounding) to the pinion flank at roll x ≤ 0 [mm]."""
    tip = profile.tip_corner(geo.gear)
    beta1, beta2 = tooth_angles(geo, x_mm)
    ang = beta2 + tip.angle_rad  # gear drive flank: +ψ side of its tooth
    px = geo.a_w_mm + tip.radius_mm * np.cos(ang)
    py = tip.radius_mm * np.sin(ang)
    return _flank_gap(geo.pinion, (0.0, 0.0), beta1, px, py, tip.rounding_radius_mm)


def recess_gap(geo: PairGeometry, x_mm):
    """Gap of the pinion's tip (corner or rounding) to the gear flank at roll x ≥ g_α [mm]."""
    tip = profile.tip_corner(geo.pinion)
    beta1, beta2 = tooth_angles(geo, x_mm)
    ang = beta1 + tip.angle_rad
    px = tip.radius_mm * np.cos(ang)
    py = tip.radius_mm * np.sin(ang)
    return _flank_gap(geo.gear, (geo.a_w_mm, 0.0), beta2, px, py, tip.rounding_radius_mm)


# --- profile modifications as functions of the roll position ---------------------------------
def _roll_from_A(geo: PairGeometry, gear: str, diameter_mm: float) -> float:
    """Roll position x [mm] (from A) where the path meets a diameter of one gear's flank."""
    if gear == "pinion":
        rb = geo.pinion.r_b_mm
        return math.sqrt(max((diameter_mm / 2.0) ** 2 - rb**2, 0.0)) - geo.A_mm
    rb = geo.gear.r_b_mm
    return geo.T1T2_mm - math.sqrt(max((diameter_mm / 2.0) ** 2 - rb**2, 0.0)) - geo.A_mm


def relief_profile(relief: Relief | None, end_x: float, start_x: float, x):
    """Relief [mm] and slope [-]: 0 at ``start_x``, ``amount`` at ``end_x`` (and beyond)."""
    x = np.asarray(x, float)
    if relief is None:
        return np.zeros_like(x), np.zeros_like(x)
    span = end_x - start_x  # signed: the relief grows towards end_x
    xi = np.clip((x - start_x) / span, 0.0, 1.0)
    n = 2 if relief.shape == "parabolic" else 1
    inside = (xi > 0.0) & (xi < 1.0)
    value = relief.amount_mm * xi**n
    slope = np.where(inside, relief.amount_mm * n * xi ** (n - 1) / span, 0.0)
    return value, slope


def _relief_extent(geo: PairGeometry, relief: Relief, gear: str, end_x: float, sign: float):
    """Start of a relief: ``end_x − sign·length`` or the roll position of its start diameter."""
    if relief.length_mm is not None:
        return end_x - sign * relief.length_mm
    return _roll_from_A(geo, gear, relief.start_diameter_mm)


def modification_gaps(geo: PairGeometry, mods: Modifications, x):
    """(G1 mods, slope), (G2 mods, slope): reliefs of pinion (G1) and gear (G2) at roll x."""
    g_a = geo.g_alpha_mm
    out = []
    for gear, tip, root, tip_end, root_end in (
        ("pinion", mods.pinion_tip, mods.pinion_root, g_a, 0.0),
        ("gear", mods.gear_tip, mods.gear_root, 0.0, g_a),
    ):
        value = np.zeros_like(np.asarray(x, float))
        slope = np.zeros_like(value)
        for relief, end in ((tip, tip_end), (root, root_end)):
            if relief is None:
                continue
            sign = 1.0 if end > 0.5 * g_a else -1.0  # relief grows towards its end of the path
            start = _relief_extent(geo, relief, gear, end, sign)
            v, s = relief_profile(relief, end, start, x)
            value, slope = value + v, slope + s
        out.append((value, slope))
    return out[0], out[1]


# --- the tables -------------------------------------------------------------------------------
def _extent(gap_fn, geo: PairGeometry, start: float, direction: float, cap_mm: float) -> float:
    """Farthest roll position from ``start`` in ``direction`` where the tip gap stays ≤ cap.

    A walk in steps of p_b/2000, never more than one base pitch outside the path. The walk's
    positions (accumulated step by step, as the walk adds them) have their gaps evaluated as
    one array to find where it stops; its last steps are then walked point by point, so the
    result is the walk's to the bit even where an array evaluation rounds differently from a
    scalar one (~300 scalar evaluations took 0.1 s).
    """
    step = geo.p_b_mm / 2000.0
    reach = abs(start + direction * geo.p_b_mm - start)
    n = int(reach / step) + 3
    xs = np.add.accumulate(np.concatenate(([start], np.full(n, direction * step))))
    last = int(np.argmax(~(np.abs(xs - start) < reach)))  # first position past the reach
    gaps = np.asarray(gap_fn(geo, xs[1:last + 1]), float)  # gaps[k]: the step from xs[k]
    over = np.nonzero(~np.isfinite(gaps) | (gaps > cap_mm))[0]
    stop = int(over[0]) if over.size else last
    return _walk(gap_fn, geo, float(xs[max(stop - 2, 0)]), start, direction, step, reach, cap_mm)


def _walk(gap_fn, geo: PairGeometry, x: float, start: float, direction: float, step: float,
          reach: float, cap_mm: float) -> float:
    """Step from ``x`` while within ``reach`` of ``start`` and the next gap is finite, ≤ cap."""
    while abs(x - start) < reach:
        g = float(gap_fn(geo, x + direction * step))
        if not math.isfinite(g) or g > cap_mm:
            break
        x += direction * step
    return x


def _corner_with_slope(gap_fn, geo: PairGeometry, x):
    h = _FD_STEP_MM
    value = gap_fn(geo, x)
    slope = (gap_fn(geo, x + h) - gap_fn(geo, x - h)) / (2.0 * h)
    return value, slope


def gap_tables(
    geo: PairGeometry,
    mods: Modifications = Modifications(),
    engagement: str = "extended",
    cap_mm: float | None = None,
    spacing_mm: float | None = None,
) -> GapTables:
    """Tabulate G1, G2 (drive) and their coast twins (the same for symmetric teeth).

    Parameters
    ----------
    geo : the pair geometry
    mods : profile modifications
    engagement : "extended" (tip gaps outside the path) or "rigid" (path 0 … g_α only)
    cap_mm : largest tip gap tabulated outside the path [mm] (default 0.05 m); beyond it a
        pair is out of contact. Must exceed any deflection the run can reach.
    spacing_mm : grid spacing (default p_b/1500, ~0.02 mm for m = 10 mm)
    """
    if engagement not in ("extended", "rigid"):
        raise ValueError(f"engagement must be 'extended' or 'rigid', got {engagement!r}")
    m = geo.module_mm
    cap = 0.05 * m if cap_mm is None else cap_mm
    h = geo.p_b_mm / 1500.0 if spacing_mm is None else spacing_mm
    g_a = geo.g_alpha_mm
    if engagement == "extended":
        x_lo = _extent(approach_gap, geo, 0.0, -1.0, cap)
        x_hi = _extent(recess_gap, geo, g_a, +1.0, cap)
    else:
        x_lo, x_hi = 0.0, g_a
    n = max(int(math.ceil((x_hi - x_lo) / h)) + 1, 2)
    x = np.linspace(x_lo, x_hi, n)
    (g1, s1), (g2, s2) = modification_gaps(geo, mods, x)
    if engagement == "extended":
        before, after = x < 0.0, x > g_a
        if before.any():
            v, s = _corner_with_slope(approach_gap, geo, x[before])
            g2[before] += np.maximum(v, 0.0)
            s2[before] += np.where(v > 0.0, s, 0.0)
        if after.any():
            v, s = _corner_with_slope(recess_gap, geo, x[after])
            g1[after] += np.maximum(v, 0.0)
            s1[after] += np.where(v > 0.0, s, 0.0)
    tables = np.empty((N_TABLES, len(TABLE_ROWS), n))
    tables[TABLE_G1, TABLE_GAP], tables[TABLE_G1, TABLE_SLOPE] = g1, s1
    tables[TABLE_G2, TABLE_GAP], tables[TABLE_G2, TABLE_SLOPE] = g2, s2
    tables[TABLE_G1_COAST] = tables[TABLE_G1]  # symmetric teeth: coast flanks are mirror images
    tables[TABLE_G2_COAST] = tables[TABLE_G2]
    return GapTables(x, tables, engagement)


def coast_phase_mm(geo: PairGeometry) -> float:
    """Pinion roll [mm] from 'drive pair at C' to 'coast pair at C' (mod p_b).

    The drive flank of a pinion tooth is at C when its centreline is ψ1(r_w1) clockwise of
    the line of centres; its coast flank when it is ψ1(r_w1) counter-clockwise: a rotation of
    2 ψ1(r_w1), i.e. a roll of 2 r_b1 ψ1(r_w1) (ISO 21771 tooth-thickness half angle). With
    backlash the coast contact happens j_n later along δ; the timing uses the pinion's flank.
    """
    psi1 = float(profile.flank_half_angle(geo.pinion, geo.pinion.r_w_mm))
    return (2.0 * geo.pinion.r_b_mm * psi1) % geo.p_b_mm


def slot_layout(geo: PairGeometry, tables: GapTables) -> dict[str, float]:
    """Pair slots of the kernel (core/rhs.py) for the grid of ``tables``: their number
    ``n_slots`` = ceil((x_hi − x_lo)/p_b) + 1 (every pair inside the grid has a slot) and the
    slot phases [mm] ``s1_0``, ``s1c_0`` that put a drive pair (and, ``coast_phase_mm``
    later, a coast pair) at the pitch point C when the pinion roll s1 = r_b1 θ1 = 0."""
    x_c = geo.C_mm - geo.A_mm  # pitch point, from A
    return {"n_slots": math.ceil((tables.x_hi - tables.x_lo) / geo.p_b_mm) + 1,
            "s1_0": (-(x_c - tables.x_lo)) % geo.p_b_mm,
            "s1c_0": (-coast_phase_mm(geo) - (x_c - tables.x_lo)) % geo.p_b_mm}
