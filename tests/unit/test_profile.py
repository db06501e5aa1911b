"""Tooth profile: involute exactness, fillet generation, closed and clean outlines.

Tolerances: exact constructions (involute, tangencies) are checked to 1e-9 mm, far above
double-precision round-off (~1e-13 mm at these radii) and far below anything visible or
mechanically relevant. Quantities read off a polyline carry the chord error of the sampling
(~(Δs)² κ / 8), stated where used.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcli.model import profile
from gearcli.model.geometry import GearSpec, PairSpec, compute_pair_geometry

DEG20 = math.radians(20.0)


def gear_of(z: int, x: float = 0.0, **kw):
    """The pinion of a pair with a 40-tooth mate (m 10 mm, α 20°)."""
    spec = PairSpec(10.0, DEG20, GearSpec(z, 100.0, x, **kw), GearSpec(40, 100.0))
    return compute_pair_geometry(spec).pinion


def polar(x, y):
    """Tooth-frame polar coordinates (R, ψ), ψ from +y towards −x."""
    return np.hypot(x, y), np.arctan2(-np.asarray(x), np.asarray(y))


def self_intersections(x, y) -> int:
    """Number of proper crossings between non-adjacent segments of a polyline."""
    p = np.column_stack([x, y])
    a, b = p[:-1], p[1:]
    n = len(a)

    def orient(p0, p1, q):
        return (p1[..., 0] - p0[..., 0]) * (q[..., 1] - p0[..., 1]) - (
            p1[..., 1] - p0[..., 1]) * (q[..., 0] - p0[..., 0])

    i, j = np.triu_indices(n, k=2)
    closed = np.allclose(p[0], p[-1])
    keep = ~(closed & (i == 0) & (j == n - 1))  # first and last segments share a point
    i, j = i[keep], j[keep]
    d1, d2 = orient(a[i], b[i], a[j]), orient(a[i], b[i], b[j])
    d3, d4 = orient(a[j], b[j], a[i]), orient(a[j], b[j], b[i])
    return int(np.count_nonzero((d1 * d2 < 0) & (d3 * d4 < 0)))


@pytest.mark.parametrize("z, x, allowance", [(17, 0.0, 0.0), (25, 0.4, 0.3), (12, 0.3, 0.0)])
def test_involute_points_satisfy_the_string_property(z, x, allowance):
    g = gear_of(z, x, thickness_allowance_mm=allowance)
    px, py = profile.involute_flank_points(g, 200)
    r_b = g.d_b_mm / 2
    radius, psi = polar(px, py)
    theta_p = 0.5 * math.pi + psi  # standard polar angle (counter-clockwise flank)
    # involute origin on the base circle (independent: ISO 21771 thickness s_b = d_b (s/d + inv α))
    s = 10.0 * (math.pi / 2 + 2 * x * math.tan(DEG20)) - allowance
    theta_0 = 0.5 * math.pi + s / (10.0 * z) + (math.tan(DEG20) - DEG20)
    # tangency point T of the base tangent through P, on the side the string unwinds to
    theta_t = theta_p - np.arccos(r_b / radius)
    tangent_length = np.sqrt(radius**2 - r_b**2)
    unwound_arc = r_b * (theta_0 - theta_t)
    assert np.max(np.abs(tangent_length - unwound_arc)) < 1e-9  # mm
    assert radius[0] == pytest.approx(max(g.d_Ff_mm, g.d_b_mm) / 2, abs=1e-9)
    assert radius[-1] == pytest.approx(g.d_a_mm / 2, abs=1e-9)
    mx, my = profile.involute_flank_points(g, 200, side=-1)
    np.testing.assert_allclose(mx, -px, atol=1e-12)
    np.testing.assert_allclose(my, py, atol=1e-12)


@pytest.mark.parametrize(
    "z, x, kw", [(17, 0.0, {}), (8, 0.0, {}), (25, 0.2, {"tip_rounding_mm": 2.0}), (10, 0.9, {})]
)
def test_outline_closed_symmetric_and_within_root_and_tip(z, x, kw):
    g = gear_of(z, x, **kw)
    tx, ty = profile.tooth_outline(g, 60)
    np.testing.assert_allclose(tx[::-1], -tx, atol=1e-9)  # mirror symmetric about the y axis
    np.testing.assert_allclose(ty[::-1], ty, atol=1e-9)
    radius, psi = polar(tx, ty)
    assert psi[0] == pytest.approx(-math.pi / z, abs=1e-12)  # space centre to space centre
    assert psi[-1] == pytest.approx(math.pi / z, abs=1e-12)
    assert self_intersections(tx, ty) == 0
    # whole gear, coarse sampling to keep the O(N²) crossing test fast
    tx, ty = profile.tooth_outline(g, 10)
    gx, gy = profile.gear_outline(g, rotation_rad=0.3, n_per_segment=10, centre_mm=(5.0, -2.0))
    assert (gx[0], gy[0]) == (gx[-1], gy[-1])  # closed
    assert len(gx) == z * (len(tx) - 1) + 1
    gr = np.hypot(gx - 5.0, gy + 2.0)
    assert gr.min() >= g.d_f_mm / 2 - 1e-9 and gr.max() <= g.d_a_mm / 2 + 1e-9
    assert self_intersections(gx, gy) == 0


@pytest.mark.parametrize("z, x, allowance", [(17, 0.0, 0.0), (25, 0.4, 0.3), (8, 0.0, 0.2)])
def test_tooth_thickness_at_reference_circle_from_outline(z, x, allowance):
    g = gear_of(z, x, thickness_allowance_mm=allowance)
    tx, ty = profile.tooth_outline(g, 4000)
    radius, psi = polar(tx, ty)
    r = g.d_mm / 2
    # the two crossings of the outline with the reference circle (linear interpolation; the
    # involute segment has ~4000 points over ~20 mm: interpolation error ~1e-8 rad)
    k = np.nonzero(np.diff(np.sign(radius - r)) != 0)[0]
    assert len(k) == 2
    w = (r - radius[k]) / (radius[k + 1] - radius[k])
    psi_cross = psi[k] + w * (psi[k + 1] - psi[k])
    s_outline = r * (psi_cross.max() - psi_cross.min())
    s_expected = 10.0 * (math.pi / 2 + 2 * x * math.tan(DEG20)) - allowance  # ISO 21771
    assert s_outline == pytest.approx(s_expected, abs=1e-6)  # mm


@pytest.mark.parametrize("z, x", [(25, 0.0), (40, -0.5), (12, 0.35), (17, 0.5)])
def test_fillet_meets_involute_tangentially_without_undercut(z, x):
    g = gear_of(z, x)
    assert not g.undercut
    r_ff = g.d_Ff_mm / 2
    # closed form (Niemann/Winter): the straight tool flank ends at height
    # Y_t = r_f + ρ (1 − sin α) and touches on the rack line of action at (r − Y_t)/sin α from I
    r, r_b = g.d_mm / 2, g.d_b_mm / 2
    y_t = g.d_f_mm / 2 + 3.8 * (1 - math.sin(DEG20))
    assert r_ff == pytest.approx(math.hypot(r_b, r * math.sin(DEG20) - (r - y_t) / math.sin(DEG20)),
                                 abs=1e-9)
    fr, fpsi = profile.fillet_points(g, 20001)
    assert fr[0] == pytest.approx(g.d_f_mm / 2, abs=1e-9)  # starts on the root circle
    assert fr[-1] == pytest.approx(r_ff, abs=1e-12)
    assert fpsi[-1] == pytest.approx(profile.flank_half_angle(g, r_ff), abs=1e-12)  # on the flank
    # tangent directions at the junction: fillet end vs involute start (finite differences
    # over ~1e-4 mm: direction error ~ h κ < 1e-4 rad; a corner would be > 1e-2 rad)
    fx, fy = -fr[-2:] * np.sin(fpsi[-2:]), fr[-2:] * np.cos(fpsi[-2:])
    ix, iy = profile.involute_flank_points(g, 2, r_start_mm=r_ff, r_end_mm=r_ff + 1e-4)
    t_fillet = math.atan2(fy[1] - fy[0], fx[1] - fx[0])
    t_flank = math.atan2(iy[1] - iy[0], ix[1] - ix[0])
    assert abs(math.remainder(t_fillet - t_flank, 2 * math.pi)) < 1e-3


@pytest.mark.parametrize("z", [6, 8, 12])
def test_undercut_fillet_cuts_the_involute_cleanly(z):
    g = gear_of(z)
    assert g.undercut and g.d_Ff_mm > g.d_b_mm
    fr, fpsi = profile.fillet_points(g, 200)
    assert fpsi[-1] == pytest.approx(profile.flank_half_angle(g, fr[-1]), abs=1e-12)
    # below the crossing the undercut lies inside the involute (less material)
    above_base = fr[:-1] > g.d_b_mm / 2
    assert np.all(fpsi[:-1][above_base] <= profile.flank_half_angle(g, fr[:-1][above_base]))
    tx, ty = profile.tooth_outline(g, 200)
    assert self_intersections(tx, ty) == 0


def test_tip_rounding_is_tangent_to_flank_and_tip_circle():
    g = gear_of(25, 0.0, tip_rounding_mm=2.0)
    corner = profile.tip_corner(g)
    assert corner.rounding_radius_mm == 2.0
    assert corner.radius_mm == pytest.approx(g.d_a_mm / 2 - 2.0, abs=1e-12)  # tip circle
    r_fa = corner.flank_end_radius_mm
    assert r_fa == pytest.approx(g.d_Fa_mm / 2, abs=1e-12)
    px, py = profile.involute_flank_points(g, 2, r_start_mm=r_fa - 1e-6, r_end_mm=r_fa)
    qx = -corner.radius_mm * math.sin(corner.angle_rad)
    qy = corner.radius_mm * math.cos(corner.angle_rad)
    assert math.hypot(px[-1] - qx, py[-1] - qy) == pytest.approx(2.0, abs=1e-9)
    # the centre lies on the flank normal (base tangent) through the junction point
    tangent = np.array([px[-1] - px[0], py[-1] - py[0]])
    to_centre = np.array([qx - px[-1], qy - py[-1]])
    cos_angle = tangent @ to_centre / np.linalg.norm(tangent) / np.linalg.norm(to_centre)
    assert abs(cos_angle) < 1e-5  # finite-difference tangent over 1e-6 mm
    tx, ty = profile.tooth_outline(g, 100)
    assert np.hypot(tx, ty).max() == pytest.approx(g.d_a_mm / 2, abs=1e-9)


def test_sharp_and_pointed_tip_corners():
    g = gear_of(17)
    corner = profile.tip_corner(g)
    assert corner.rounding_radius_mm == 0.0
    assert corner.radius_mm == pytest.approx(g.d_a_mm / 2)
    assert 2 * corner.radius_mm * corner.angle_rad == pytest.approx(g.s_a_mm, rel=1e-12)
    pointed = gear_of(10, 0.9)
    assert pointed.s_a_mm < 0.0
    corner = profile.tip_corner(pointed)
    assert corner.angle_rad == 0.0 and corner.radius_mm < pointed.d_a_mm / 2
    assert profile.flank_half_angle(pointed, corner.radius_mm) == pytest.approx(0.0, abs=1e-14)
    tx, ty = profile.tooth_outline(pointed, 50)
    assert np.hypot(tx, ty).max() == pytest.approx(corner.radius_mm, abs=1e-9)


def _line_crossings(x, y, point, direction) -> np.ndarray:
    """Parameters t where the polyline crosses the line point + t·direction [mm]."""
    px, py = x - point[0], y - point[1]
    side = direction[0] * py - direction[1] * px
    k = np.nonzero(np.sign(side[:-1]) * np.sign(side[1:]) < 0)[0]
    w = side[k] / (side[k] - side[k + 1])
    cx, cy = px[k] + w * (px[k + 1] - px[k]), py[k] + w * (py[k + 1] - py[k])
    return cx * direction[0] + cy * direction[1]


@pytest.mark.parametrize("centre_distance, allowance", [(None, 0.0), (211.0, 0.0), (None, 0.4)])
def test_gears_in_mesh_touch_on_drive_flanks_and_show_backlash_on_coast_flanks(
    centre_distance, allowance
):
    """Second method for the backlash: measure it on the outlines placed in mesh.

    The plot's layout puts a tooth pair in contact at C: both outlines cross the drive line of
    action at C. Along the coast line of action (its mirror through C) each coast-flank pair
    is separated by the normal backlash j_n (ISO/TR 10064-2). Crossings are read off
    polylines with ~0.03 mm chords (sagitta < 1e-5 mm), hence the 1e-4 mm tolerance.
    """
    from matplotlib.path import Path

    from gearcli.plotting.geometry import mesh_layout

    spec = PairSpec(10.0, DEG20, GearSpec(17, 100.0, thickness_allowance_mm=allowance),
                    GearSpec(25, 100.0), centre_distance_mm=centre_distance)
    g = compute_pair_geometry(spec)
    lay = mesh_layout(g)
    x1, y1 = profile.gear_outline(g.pinion, lay["rot1"], 800)
    x2, y2 = profile.gear_outline(g.gear, lay["rot2"], 800, (g.a_w_mm, 0.0))
    c = lay["T1"] + g.C_mm * lay["n"]
    # coarse polygons for point-in-gear tests (fast); their chords lie inside convex flanks by
    # < 2e-3 mm, far less than the gaps probed (>= j_n / 2) and on the safe side for contact
    p1 = Path(np.column_stack(profile.gear_outline(g.pinion, lay["rot1"], 60)))
    p2 = Path(np.column_stack(profile.gear_outline(g.gear, lay["rot2"], 60, (g.a_w_mm, 0.0))))
    # drive flanks: contact at C
    assert np.min(np.abs(_line_crossings(x1, y1, c, lay["n"]))) < 1e-4
    assert np.min(np.abs(_line_crossings(x2, y2, c, lay["n"]))) < 1e-4
    # coast flanks: pinion crossing and the nearest gear crossing, away from C, inside the path
    coast = lay["n"] * [-1.0, 1.0]
    t1, t2 = _line_crossings(x1, y1, c, coast), _line_crossings(x2, y2, c, coast)
    gaps = []
    for t in t1[(np.abs(t1) > 1e-3) & (np.abs(t1) < 0.45 * g.g_alpha_mm)]:
        nearest = t2[np.argmin(np.abs(t2 - t))]
        assert abs(nearest - t) < 0.2 * g.p_b_mm  # a coast-flank pair, not a tip or a root
        if abs(nearest - t) > 1e-4:  # a real gap: nothing but air between the two flanks
            mid = c + 0.5 * (t + nearest) * coast
            assert not (p1.contains_point(mid) or p2.contains_point(mid))
        gaps.append(abs(nearest - t))
    assert len(gaps) >= 2
    assert max(abs(gap - g.j_n_mm) for gap in gaps) < 1e-4
    # and the outlines never overlap (pinion points near the mesh tested against the gear)
    near = np.hypot(x1 - c[0], y1 - c[1]) < 0.6 * g.g_alpha_mm
    assert not p2.contains_points(np.column_stack([x1[near], y1[near]])).any()


def test_plot_pair_returns_a_figure():
    from matplotlib.figure import Figure

    from gearcli.plotting.geometry import plot_pair

    g = compute_pair_geometry(PairSpec(10.0, DEG20, GearSpec(17, 100.0), GearSpec(25, 100.0)))
    fig = plot_pair(g, title="seed")
    assert isinstance(fig, Figure) and len(fig.axes) == 2
    assert fig.axes[0].get_aspect() == 1.0 and fig.axes[1].get_aspect() == 1.0
