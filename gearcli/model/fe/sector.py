"""Outline of a gear-body sector with several teeth, for the FE tooth model (numpy only).

Tooth frame of :mod:`gearcli.model.profile` (gear centre at the origin, the loaded tooth
centred on +y, ψ measured from +y towards −x). The sector holds ``n_teeth`` (odd) whole
teeth of the generated profile (:func:`gearcli.model.profile.tooth_outline`: trochoid fillet,
undercut, involute, tip rounding), the middle one loaded on its counter-clockwise flank
(x < 0), bounded by the radial lines through the space centres at ψ = ±n_teeth π/z down to
the bore circle of radius r_int. Edge markers: 1 bore arc, 2 sector sides, 3 tooth surface.

Mesh refinement at the flanks: the loaded tooth's outline (flanks, fillets, tip and the root
arcs) is sampled at the fine spacing, the other teeth at the coarse one; the triangle mesh
grades from that boundary spacing. The load points (on the involute at the requested radii)
are inserted as vertices of the outline.

Units: mm, rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearcli.model import profile
from gearcli.model.fe.elasticity import closed_loop
from gearcli.model.toothform import ToothForm

__all__ = ["SectorOutline", "flank_point_normal", "sector_outline", "resample"]

BORE, SIDE, SURFACE = 1, 2, 3  #: edge markers


@dataclass(frozen=True)
class SectorOutline:
    """Boundary of the sector or the whole body: points, segments and their markers."""

    points_mm: np.ndarray
    segments: np.ndarray  #: (k, 2) point indices
    edge_markers: np.ndarray  #: (k,) marker of each segment
    holes_mm: np.ndarray | None  #: a point inside the bore when the body is whole
    load_vertex_ids: np.ndarray  #: indices in ``points_mm`` of the load points
    n_teeth: int
    bore_radius_mm: float


def flank_point_normal(gear: ToothForm, radius_mm) -> tuple[np.ndarray, np.ndarray]:
    """Involute point (n, 2) and its outward unit normal (n, 2) on the loaded flank [mm].

    The point is (−r sin ψ, r cos ψ), ψ = s/d + inv α − inv α_r (ISO 21771), cos α_r = r_b/r.
    With d(inv α_r)/dr = tan α_r / r the tangent is dP/dr ∝ (−sin ψ + tan α_r cos ψ,
    cos ψ + tan α_r sin ψ); the outward normal is that tangent turned by +90° (it points to
    −x, away from the tooth) and is tangent to the base circle (the line of action).
    """
    r = np.atleast_1d(np.asarray(radius_mm, float))
    psi = profile.flank_half_angle(gear, r)
    tan_a = np.sqrt(np.maximum(r * r / gear.r_b_mm**2 - 1.0, 0.0))
    p = np.column_stack([-r * np.sin(psi), r * np.cos(psi)])
    t = np.column_stack([-np.sin(psi) + tan_a * np.cos(psi), np.cos(psi) + tan_a * np.sin(psi)])
    t /= np.linalg.norm(t, axis=1)[:, None]
    n = np.column_stack([-t[:, 1], t[:, 0]])  # tangent turned +90°: points to −x on this flank
    return p, n


def resample(xy: np.ndarray, spacing_mm: float) -> np.ndarray:
    """Points at (nearly) equal arc length ≤ spacing along a polyline, both ends kept."""
    seg = np.hypot(*np.diff(xy, axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    n = max(1, int(math.ceil(s[-1] / spacing_mm)))
    t = np.linspace(0.0, s[-1], n + 1)
    return np.column_stack([np.interp(t, s, xy[:, 0]), np.interp(t, s, xy[:, 1])])


def _rotate(xy: np.ndarray, angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return xy @ np.array([[c, s], [-s, c]])


def _insert(curve: np.ndarray, pts: np.ndarray, gap: float) -> tuple[np.ndarray, np.ndarray]:
    """Insert points into a polyline at their nearest segments; drop old points within
    ``gap`` of a new one. Returns the polyline and the indices of the inserted points."""
    key = np.arange(len(curve), dtype=float)
    new_keys = []
    for p in pts:
        d = curve[1:] - curve[:-1]
        t = np.clip(np.einsum("ij,ij->i", p - curve[:-1], d) / np.einsum("ij,ij->i", d, d),
                    0.0, 1.0)
        dist = np.hypot(*(curve[:-1] + t[:, None] * d - p).T)
        i = int(np.argmin(dist))
        new_keys.append(i + min(max(t[i], 0.01), 0.99))
    near = np.zeros(len(curve), bool)
    for p in pts:
        near |= np.hypot(*(curve - p).T) < gap
    near[[0, -1]] = False
    keys = np.concatenate([key[~near], new_keys])
    allp = np.vstack([curve[~near], pts])
    order = np.argsort(keys, kind="stable")
    inserted = np.nonzero(order >= (~near).sum())[0]
    return allp[order], inserted[np.argsort(order[inserted])]


def sector_outline(gear: ToothForm, load_radii_mm, *, bore_radius_mm: float,
                   n_teeth: int | None, fine_mm: float, coarse_mm: float,
                   load_points_mm=None) -> SectorOutline:
    """Sector (module notes) with the load points at ``load_radii_mm`` on the involute, or at
    ``load_points_mm`` ((n, 2) points on the loaded tooth's outline, e.g. a tip corner, when
    given), inserted.

    ``n_teeth``: odd number of teeth of the sector, or None for the whole gear (all teeth, the
    bore a hole; no sides). ``fine_mm``: boundary spacing on the loaded tooth; ``coarse_mm``:
    elsewhere [mm].
    """
    loaded = (flank_point_normal(gear, load_radii_mm)[0] if load_points_mm is None
              else np.asarray(load_points_mm, float).reshape(-1, 2))
    if n_teeth is None:
        return _whole(gear, loaded, bore_radius_mm, fine_mm, coarse_mm)
    if n_teeth < 1 or n_teeth % 2 == 0 or n_teeth >= gear.teeth:
        raise ValueError(f"n_teeth must be odd, positive and below z, got {n_teeth}")
    half = n_teeth // 2
    rim, load_ids, tooth = _teeth(gear, loaded, bore_radius_mm, range(-half, half + 1),
                                  fine_mm, coarse_mm)
    pitch = 2.0 * math.pi / gear.teeth
    edge = [np.full(len(rim), SURFACE)]
    ang_end = (half + 0.5) * pitch  # ψ of the left space centre
    last = _rotate(tooth[-1:], half * pitch)[0]  # left end on the root circle
    r_end = float(np.hypot(*last))
    n_side = max(2, int(math.ceil((r_end - bore_radius_mm) / coarse_mm)))
    radii = np.linspace(r_end, bore_radius_mm, n_side + 1)
    left = np.column_stack([-radii * math.sin(ang_end), radii * math.cos(ang_end)])
    n_arc = max(4, int(math.ceil(2 * ang_end * bore_radius_mm / coarse_mm)))
    psi = np.linspace(ang_end, -ang_end, n_arc + 1)
    arc = np.column_stack([-bore_radius_mm * np.sin(psi), bore_radius_mm * np.cos(psi)])
    right = left[::-1] * [-1.0, 1.0]
    pts = np.vstack([rim, left, arc[1:-1], right[:-1]])
    edge += [np.full(n_side, SIDE), np.full(n_arc, BORE), np.full(n_side, SIDE)]
    return SectorOutline(pts, closed_loop(0, len(pts)), np.concatenate(edge), None, load_ids,
                         n_teeth, bore_radius_mm)


def _teeth(gear, loaded, bore_radius_mm, indices, fine_mm, coarse_mm):
    """Outline of the teeth ``indices`` (0 = the loaded one), each up to the next tooth's
    first point; the load points ``loaded`` (n, 2) inserted in tooth 0. Returns (points,
    load ids, tooth)."""
    if not 0.0 < bore_radius_mm < gear.r_f_mm:
        raise ValueError(f"the bore radius {bore_radius_mm:.4g} mm must lie in (0, r_f = "
                         f"{gear.r_f_mm:.4g} mm)")
    tx, ty = profile.tooth_outline(gear, n_per_segment=200)
    tooth = np.column_stack([tx, ty])
    mid, ids = _insert(resample(tooth, fine_mm), loaded, 0.3 * fine_mm)
    coarse = resample(tooth, coarse_mm)
    pitch = 2.0 * math.pi / gear.teeth
    parts, start, load_ids = [], 0, None
    for k in indices:
        piece = _rotate(mid if k == 0 else coarse, k * pitch)[:-1]
        if k == 0:
            load_ids = ids + start
        parts.append(piece)
        start += len(piece)
    return np.vstack(parts), load_ids, tooth


def _whole(gear, loaded, bore_radius_mm, fine_mm, coarse_mm) -> SectorOutline:
    """The whole gear: all teeth (loaded tooth 0 fine) and the bore circle as a hole."""
    half = gear.teeth // 2
    rim, load_ids, _ = _teeth(gear, loaded, bore_radius_mm,
                              range(-half, gear.teeth - half), fine_mm, coarse_mm)
    n_arc = max(12, int(math.ceil(2.0 * math.pi * bore_radius_mm / coarse_mm)))
    psi = np.linspace(0.0, 2.0 * math.pi, n_arc, endpoint=False)
    bore = np.column_stack([-bore_radius_mm * np.sin(psi), bore_radius_mm * np.cos(psi)])
    seg = np.vstack([closed_loop(0, len(rim)), closed_loop(len(rim), n_arc)])
    marks = np.concatenate([np.full(len(rim), SURFACE), np.full(n_arc, BORE)])
    return SectorOutline(np.vstack([rim, bore]), seg, marks, np.zeros((1, 2)), load_ids,
                         gear.teeth, bore_radius_mm)
