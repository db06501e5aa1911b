"""Flank-gap tables (extended engagement, reliefs) against independent constructions."""

import math

import numpy as np
import pytest

from gearcli.model import profile
from gearcli.model.gap import (
    TABLE_G1,
    TABLE_G2,
    Modifications,
    Relief,
    approach_gap,
    coast_phase_mm,
    gap_tables,
    recess_gap,
)
from gearcli.model.geometry import GearSpec, PairSpec, compute_pair_geometry

SEED = compute_pair_geometry(PairSpec(10.0, math.radians(20), GearSpec(17, 100), GearSpec(25, 100)))


def test_tip_gaps_vanish_at_A_and_E_and_grow_outside():
    assert abs(approach_gap(SEED, 0.0)) < 1e-9
    assert abs(recess_gap(SEED, SEED.g_alpha_mm)) < 1e-9
    xa = -np.linspace(0.05, 2.0, 20)
    ga = approach_gap(SEED, xa)
    ge = recess_gap(SEED, SEED.g_alpha_mm - xa)
    assert np.all(np.diff(ga) > 0) and np.all(np.diff(ge) > 0)
    # Two curves that touch: the gap grows quadratically at first (ratio ~4 for 2x distance).
    assert approach_gap(SEED, -0.2) / approach_gap(SEED, -0.1) == pytest.approx(4.0, rel=0.05)


def _outline_xy(gear, rotation, centre):
    x, y = profile.gear_outline(gear, rotation, 4000, centre)
    return np.column_stack([x, y])


@pytest.mark.parametrize("x", [-0.3, -1.0, -2.0])
def test_approach_gap_is_euclidean_distance_to_pinion_flank(x):
    # Independent: place the real pinion outline (dense polyline) and the gear tip corner at
    # the rigid-kinematic roll x and measure the shortest Euclidean distance. For an involute,
    # the normal through a point is the base tangent, so both measures agree exactly; the
    # tolerance covers the polyline chord error (spacing ~0.01 mm -> ~1e-6 mm).
    from gearcli.model.gap import tooth_angles

    beta1, beta2 = tooth_angles(SEED, x)
    tip = profile.tip_corner(SEED.gear)
    q = np.array([SEED.a_w_mm + tip.radius_mm * math.cos(beta2 + tip.angle_rad),
                  tip.radius_mm * math.sin(beta2 + tip.angle_rad)])
    # tooth outline is centred on +y: rotate so the centreline points at beta1
    pts = _outline_xy(SEED.pinion, beta1 - math.pi / 2, (0.0, 0.0))
    seg_a, seg_b = pts[:-1], pts[1:]
    d = seg_b - seg_a
    t = np.clip(np.einsum("ij,ij->i", q - seg_a, d) / np.einsum("ij,ij->i", d, d), 0, 1)
    dist = np.min(np.linalg.norm(seg_a + t[:, None] * d - q, axis=1))
    assert float(approach_gap(SEED, x)) == pytest.approx(dist, abs=2e-5)


def test_rigid_tables_are_zero_on_the_path_only():
    gt = gap_tables(SEED, engagement="rigid")
    assert gt.x_lo == 0.0 and gt.x_hi == pytest.approx(SEED.g_alpha_mm)
    assert np.all(gt.tables == 0.0)


def test_extended_tables_continuous_and_slopes_consistent():
    gt = gap_tables(SEED)
    assert gt.x_lo < 0.0 and gt.x_hi > SEED.g_alpha_mm
    for k in (TABLE_G1, TABLE_G2):
        g, s = gt.tables[k]
        assert np.all(np.isfinite(g)) and np.all(g >= 0.0)
    # slopes vs a 5-point difference of the tip-gap functions themselves at h = 1e-3 mm
    # (truncation ~ h^4 G^(5) < 1e-10; rounding ~ 1e-16/h ~ 1e-13)
    h = 1e-3
    for k, fn, xs in ((TABLE_G2, approach_gap, (-0.05, -0.5, -2.0)),
                      (TABLE_G1, recess_gap, [SEED.g_alpha_mm + d for d in (0.05, 0.5, 2.0)])):
        for x in xs:
            i = int(np.argmin(np.abs(gt.x_mm - x)))
            xi = gt.x_mm[i]
            five = (fn(SEED, xi - 2 * h) - 8 * fn(SEED, xi - h) + 8 * fn(SEED, xi + h)
                    - fn(SEED, xi + 2 * h)) / (12 * h)
            assert gt.tables[k, 1, i] == pytest.approx(float(five), abs=1e-8)
    # cap: the tip gap at the table ends reaches the cap (0.05 m = 0.5 mm) within a step
    assert gt.tables[TABLE_G2, 0, 0] == pytest.approx(0.5, abs=0.01)
    assert gt.tables[TABLE_G1, 0, -1] == pytest.approx(0.5, abs=0.01)


@pytest.mark.parametrize("shape, mid", [("linear", 0.5), ("parabolic", 0.25)])
def test_pinion_tip_relief(shape, mid):
    c, length = 0.02, 6.0
    mods = Modifications(pinion_tip=Relief(c, length_mm=length, shape=shape))
    gt = gap_tables(SEED, mods, engagement="rigid")
    g1 = lambda x: np.interp(x, gt.x_mm, gt.tables[TABLE_G1, 0])  # noqa: E731
    ga = SEED.g_alpha_mm
    assert g1(ga) == pytest.approx(c, rel=1e-3)
    assert g1(ga - length / 2) == pytest.approx(mid * c, rel=1e-2)
    assert g1(ga - length - 0.5) == 0.0
    assert np.all(gt.tables[TABLE_G2] == 0.0)


def test_relief_start_diameter_equals_length():
    # The gear tip relief starting at the diameter where the path is L from A.
    length = 5.0
    rho2 = SEED.T1T2_mm - (SEED.A_mm + length)  # distance from T2
    d_start = 2.0 * math.hypot(SEED.gear.r_b_mm, rho2)
    by_len = gap_tables(SEED, Modifications(gear_tip=Relief(0.03, length_mm=length)), "rigid")
    by_dia = gap_tables(SEED, Modifications(gear_tip=Relief(0.03, start_diameter_mm=d_start)),
                        "rigid")
    np.testing.assert_allclose(by_len.tables, by_dia.tables, atol=1e-12)
    assert by_len.tables[TABLE_G2, 0, 0] == pytest.approx(0.03)


def test_coast_phase_standard_pair_is_half_a_base_pitch():
    # Zero-backlash standard pair: psi1(r_w) = pi/(2 z1), so 2 r_b1 psi1 = p_b / 2.
    assert coast_phase_mm(SEED) == pytest.approx(SEED.p_b_mm / 2, rel=1e-12)
