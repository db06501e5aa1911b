"""Gear pair geometry against textbook values and independent computations.

Tolerances: values quoted by a source to n decimals are compared with half a unit of the last
quoted digit (the source rounded them); values recomputed independently here in double
precision are compared to ~1e-9 relative (round-off of a few dozen operations).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcli.model.frequencies import mesh_frequencies
from gearcli.model.geometry import GearSpec, PairSpec, RackSpec, compute_pair_geometry
from gearcli.model.involute import inv, inv_inverse

DEG20 = math.radians(20.0)


def _inv(a: float) -> float:
    """Involute function written out here, independent of the module under test."""
    return math.tan(a) - a


def _inv_inverse_bisect(value: float) -> float:
    """Independent inverse of the involute function (bisection to the last bit)."""
    lo, hi = 0.0, 1.5
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _inv(mid) < value else (lo, mid)
    return 0.5 * (lo + hi)


def seed_spec(**pair) -> PairSpec:
    """The seed article's pair: z 17/25, m 10 mm, α 20°, b 100 mm (docs/theory.md §9)."""
    return PairSpec(10.0, DEG20, GearSpec(17, 100.0), GearSpec(25, 100.0), **pair)


def codes(geom, severity: str) -> list[str]:
    return [f.code for f in geom.findings if f.severity == severity]


def assert_fractions(actual, expected) -> None:
    """(pairs in contact, time fraction) tuples; fractions to 1e-12 (one subtraction)."""
    assert [n for n, _ in actual] == [n for n, _ in expected]
    assert [f for _, f in actual] == pytest.approx([f for _, f in expected], abs=1e-12)


def h_star() -> float:
    """Straight tool flank height h_fP* − ρ_fP* (1 − sin α) = 0.99997 for ISO 53 A at 20°."""
    return 1.25 - 0.38 * (1.0 - math.sin(DEG20))


# --- involute helpers -------------------------------------------------------------------------

def test_inv_inverse_round_trip_to_1e14():
    alpha = np.concatenate([np.geomspace(1e-8, 1.5, 2000), [0.0999999, 0.1, 0.3490658503988659]])
    assert np.max(np.abs(inv_inverse(inv(alpha)) - alpha)) < 1e-14  # the accuracy promised
    assert inv_inverse(0.0) == 0.0
    assert inv_inverse(inv(DEG20)) == pytest.approx(DEG20, abs=1e-15)
    with pytest.raises(ValueError):
        inv_inverse(-1e-3)


def test_inv_small_angle_series_matches_extended_precision():
    # small angles use the series: compare with tan α − α in extended precision (80-bit long
    # double: reference error ~1e-19 · 3/α², i.e. < 3e-15 for α >= 0.01)
    if np.finfo(np.longdouble).eps > 1e-18:
        pytest.skip("no extended-precision long double on this platform")
    a = np.geomspace(0.01, 0.2, 50)
    exact = np.array([float(np.tan(np.longdouble(x)) - np.longdouble(x)) for x in a])
    assert np.max(np.abs(inv(a) - exact) / exact) < 2e-14


# --- seed pair (docs/theory.md §9) --------------------------------------------------------------

def test_seed_geometry_matches_theory():
    g = compute_pair_geometry(seed_spec())
    p, w = g.pinion, g.gear
    assert (p.d_mm, w.d_mm) == pytest.approx((170.0, 250.0), abs=1e-12)
    assert p.d_b_mm == pytest.approx(159.748, abs=5e-4)
    assert w.d_b_mm == pytest.approx(234.923, abs=5e-4)
    assert (p.d_a_mm, w.d_a_mm) == pytest.approx((190.0, 270.0), abs=1e-12)
    assert (p.d_f_mm, w.d_f_mm) == pytest.approx((145.0, 225.0), abs=1e-12)
    assert g.a_mm == pytest.approx(210.0, abs=1e-12)
    assert g.a_w_mm == pytest.approx(210.0, abs=1e-9)
    assert g.alpha_w_rad == pytest.approx(DEG20, abs=1e-12)
    assert g.p_b_mm == pytest.approx(29.5213, abs=5e-5)
    assert g.g_alpha_mm == pytest.approx(46.1485, abs=5e-5)
    assert g.eps_alpha == pytest.approx(1.56323, rel=1e-4)
    assert g.j_wt_mm == pytest.approx(0.0, abs=1e-9)
    assert g.ratio == pytest.approx(25 / 17)


def test_seed_line_of_action_points_are_consistent():
    g = compute_pair_geometry(seed_spec())
    rb1, rb2, ra1, ra2 = 159.74774553 / 2, 234.92315520 / 2, 95.0, 135.0
    t1t2 = 210.0 * math.sin(DEG20)
    assert g.T1T2_mm == pytest.approx(t1t2, rel=1e-9)
    assert g.E_mm == pytest.approx(math.sqrt(ra1**2 - rb1**2), rel=1e-8)
    assert g.A_mm == pytest.approx(t1t2 - math.sqrt(ra2**2 - rb2**2), rel=1e-8)
    assert g.C_mm == pytest.approx(85.0 * math.sin(DEG20), rel=1e-12)  # r_b1 tan α = r1 sin α
    assert g.B_mm == pytest.approx(g.E_mm - g.p_b_mm, abs=1e-12)
    assert g.D_mm == pytest.approx(g.A_mm + g.p_b_mm, abs=1e-12)
    assert g.A_mm < g.B_mm < g.C_mm < g.D_mm < g.E_mm  # C in the single-contact zone
    assert g.single_contact_fraction == pytest.approx(2.0 - g.eps_alpha, abs=1e-12)
    assert g.double_contact_fraction == pytest.approx(g.eps_alpha - 1.0, abs=1e-12)
    assert_fractions(g.pair_fractions, ((1, 2 - g.eps_alpha), (2, g.eps_alpha - 1)))


def test_seed_mesh_frequency():
    f_z, n1, n2 = mesh_frequencies(17, math.radians(3000.0), 25 / 17)
    assert f_z == pytest.approx(141.667, abs=5e-4)
    assert n1 == pytest.approx(3000.0 / 360.0, rel=1e-12)
    assert n2 == pytest.approx(n1 * 17 / 25, rel=1e-12)


def test_seed_clearances_and_only_the_slight_undercut_warning():
    g = compute_pair_geometry(seed_spec())
    # c = a_w − r_a − r_f(mate) = 0.25 m for the standard rack
    for gear in (g.pinion, g.gear):
        assert gear.tip_clearance_mm == pytest.approx(2.5, abs=1e-9)
        assert gear.root_clearance_mm == pytest.approx(2.5, abs=1e-9)
    # z = 17 is just below z_min = 2 h*/sin²20° = 17.097: x_min = h* − 17 sin²20°/2
    assert g.pinion.x_min == pytest.approx(h_star() - 8.5 * math.sin(DEG20) ** 2, abs=1e-14)
    assert g.pinion.z_min == pytest.approx(2.0 * h_star() / math.sin(DEG20) ** 2, rel=1e-12)
    assert codes(g, "error") == []
    assert codes(g, "warning") == ["undercut"]


# --- profile-shifted pair: KHK Gear Technical Reference, "profile shifted spur gears" table
# (m 3, α 20°, z 12/24, x 0.6/0.36, a_w 56.4999 mm; reproduced at
# bolsover.com/utilitiesforalibre/profile-shifted-external-spur-gears.html)

def khk_spec(tip_shortening: float = 0.0) -> PairSpec:
    return PairSpec(3.0, DEG20, GearSpec(12, 30.0, 0.6, tip_shortening),
                    GearSpec(24, 30.0, 0.36, tip_shortening))


def test_profile_shifted_pair_operating_centre_distance():
    g = compute_pair_geometry(khk_spec())
    # independent: inv α_w = inv α + 2 (x1 + x2) tan α / (z1 + z2), bisection, a_w cos α_w = a cos α
    inv_w = _inv(DEG20) + 2.0 * 0.96 * math.tan(DEG20) / 36.0
    alpha_w = _inv_inverse_bisect(inv_w)
    a_w = 54.0 * math.cos(DEG20) / math.cos(alpha_w)
    assert g.alpha_w_rad == pytest.approx(alpha_w, abs=1e-13)
    assert g.a_w_mm == pytest.approx(a_w, rel=1e-12)
    assert inv(g.alpha_w_rad) == pytest.approx(inv_w, rel=1e-12)
    # published (rounded) values
    assert inv_w == pytest.approx(0.034316, abs=5e-7)
    assert math.degrees(g.alpha_w_rad) == pytest.approx(26.0886, abs=5e-5)
    assert g.a_w_mm == pytest.approx(56.4999, abs=5e-5)
    assert g.pinion.d_w_mm == pytest.approx(37.667, abs=5e-4)
    assert g.gear.d_w_mm == pytest.approx(75.333, abs=5e-4)
    assert (g.pinion.d_b_mm, g.gear.d_b_mm) == pytest.approx((33.8289, 67.6579), abs=5e-5)
    assert (g.pinion.d_f_mm, g.gear.d_f_mm) == pytest.approx((32.100, 66.660), abs=5e-4)
    assert g.j_wt_mm == pytest.approx(0.0, abs=1e-12)


def test_profile_shifted_pair_contact_ratio_textbook():
    # KHK shortens both tips to keep the standard clearance: k = x1 + x2 − y,
    # y = (z1 + z2)/2 (cos α / cos α_w − 1) (centre distance modification coefficient)
    alpha_w = _inv_inverse_bisect(_inv(DEG20) + 2.0 * 0.96 * math.tan(DEG20) / 36.0)
    y = 18.0 * (math.cos(DEG20) / math.cos(alpha_w) - 1.0)
    assert y == pytest.approx(0.83329, abs=5e-6)  # published
    g = compute_pair_geometry(khk_spec(0.96 - y))
    assert (g.pinion.d_a_mm, g.gear.d_a_mm) == pytest.approx((44.840, 79.400), abs=5e-4)
    assert g.eps_alpha == pytest.approx(1.202, abs=5e-4)  # published 1.202
    assert g.pinion.tip_clearance_mm == pytest.approx(0.25 * 3.0, abs=1e-9)
    assert g.errors == ()


# --- findings ---------------------------------------------------------------------------------

def test_undercut_flagged_for_z12_standard_not_with_shift_03():
    spec = PairSpec(10.0, DEG20, GearSpec(12, 100.0), GearSpec(40, 100.0))
    g = compute_pair_geometry(spec)
    assert g.pinion.undercut and "undercut" in codes(g, "warning")
    x_min = h_star() - 6.0 * math.sin(DEG20) ** 2  # h* − z sin²α / 2
    assert g.pinion.x_min == pytest.approx(x_min, abs=1e-12)  # 0.2981
    assert g.pinion.undercut_coef == pytest.approx(x_min, abs=1e-12)
    assert g.pinion.undercut_mm == pytest.approx(10.0 * x_min, abs=1e-11)
    msg = next(f.message for f in g.findings if f.code == "undercut")
    assert "0.2981 m" in msg and "2.981 mm" in msg
    shifted = compute_pair_geometry(
        PairSpec(10.0, DEG20, GearSpec(12, 100.0, 0.3), GearSpec(40, 100.0, -0.3))
    )
    assert not shifted.pinion.undercut
    assert "undercut" not in codes(shifted, "warning")


def test_pointed_tip_warning_and_error():
    def pinion(z, x):
        return PairSpec(10.0, DEG20, GearSpec(z, 100.0, x), GearSpec(40, 100.0))

    warn = compute_pair_geometry(pinion(12, 0.8))
    assert 0.0 < warn.pinion.s_a_mm < 2.0
    assert "pointed_tip" in codes(warn, "warning")
    err = compute_pair_geometry(pinion(10, 0.9))
    assert err.pinion.s_a_mm < 0.0
    assert "pointed_tip" in codes(err, "error")
    # independent tip thickness s_a = d_a (s/d + inv α − inv α_a) for the warning case
    d, d_a = 120.0, 120.0 + 2 * 10.0 * 1.8
    s = 10.0 * (math.pi / 2 + 2 * 0.8 * math.tan(DEG20))
    alpha_a = math.acos(d * math.cos(DEG20) / d_a)
    s_a = d_a * (s / d + _inv(DEG20) - _inv(alpha_a))
    assert warn.pinion.s_a_mm == pytest.approx(s_a, rel=1e-12)


def test_interference_small_pinion_with_large_gear():
    g = compute_pair_geometry(PairSpec(10.0, DEG20, GearSpec(8, 100.0), GearSpec(60, 100.0)))
    assert g.A_mm < 0.0  # the gear tip reaches beyond T1
    assert "interference" in codes(g, "error")


def test_mate_tip_in_undercut_zone_is_a_warning():
    # z 14/20 standard: A lies between T1 and T2 but the gear tip reaches the pinion's undercut.
    # The undercut fillet lies inside the involute: no collision, a shorter active profile.
    g = compute_pair_geometry(PairSpec(10.0, DEG20, GearSpec(14, 100.0), GearSpec(20, 100.0)))
    assert 0.0 < g.A_mm and g.E_mm < g.T1T2_mm
    assert g.pinion.undercut and g.pinion.d_Nf_mm < g.pinion.d_Ff_mm
    assert "undercut_contact" in codes(g, "warning")
    assert "interference" not in codes(g, "error")


def test_fillet_interference_is_an_error():
    # Long addendum h_aP* = 1.2 on a rack whose straight flank ends at h_fP* - rho(1 - sin a)
    # = 1.05 m: a large mate's tip reaches the pinion's (non-undercut) fillet.
    spec = PairSpec(10.0, DEG20, GearSpec(40, 100.0), GearSpec(300, 100.0),
                    RackSpec(1.2, 1.3, 0.38))
    g = compute_pair_geometry(spec)
    assert not g.pinion.undercut and g.pinion.d_Nf_mm < g.pinion.d_Ff_mm
    assert "interference" in codes(g, "error")


@pytest.mark.parametrize("b_mm, warned", [(340.0, False), (341.0, True), (500.0, True)])
def test_face_width_beyond_two_pinion_diameters_is_warned(b_mm, warned):
    # z1 = 17, m = 10: d1 = 170 mm, so VDI 2736-2's b/d1 <= 2.0 ends at b = 340 mm
    g = compute_pair_geometry(PairSpec(10.0, DEG20, GearSpec(17, b_mm), GearSpec(25, b_mm)))
    assert ("face_width" in codes(g, "warning")) == warned
    if warned:
        text = next(f.message for f in g.findings if f.code == "face_width")
        assert f"{b_mm / 170.0:.2f} x the pinion's reference diameter" in text


def test_contact_ratio_below_one_is_an_error():
    spec = PairSpec(10.0, DEG20, GearSpec(17, 100.0, 0.0, 0.6), GearSpec(25, 100.0, 0.0, 0.6))
    g = compute_pair_geometry(spec)
    assert g.eps_alpha < 1.0
    assert "contact_ratio" in codes(g, "error")
    # 0 pairs during 1 − ε, 1 pair during ε
    assert_fractions(g.pair_fractions, ((0, 1.0 - g.eps_alpha), (1, g.eps_alpha)))
    assert g.single_contact_fraction == pytest.approx(g.eps_alpha)
    assert g.double_contact_fraction == 0.0


def test_contact_ratio_above_two_fractions():
    spec = PairSpec(1.0, math.radians(15.0), GearSpec(60, 10.0), GearSpec(90, 10.0),
                    RackSpec(1.25, 1.5, 0.2))
    g = compute_pair_geometry(spec)
    assert 2.0 < g.eps_alpha < 3.0
    f = g.eps_alpha - 2.0
    assert_fractions(g.pair_fractions, ((2, 1.0 - f), (3, f)))
    assert g.single_contact_fraction == 0.0
    assert g.double_contact_fraction == pytest.approx(1.0 - f)


def test_backlash_from_increased_centre_distance():
    g = compute_pair_geometry(seed_spec(centre_distance_mm=211.0))
    # independent (ISO/TR 10064-2 / DIN 3967): j_bn = (d_b1 + d_b2)(inv α_w − inv α_w0),
    # α_w0 = α for x1 + x2 = 0, α_w from a_w cos α_w = a cos α
    alpha_w = math.acos(210.0 * math.cos(DEG20) / 211.0)
    j_n = 10.0 * 42 * math.cos(DEG20) * (_inv(alpha_w) - _inv(DEG20))
    assert g.alpha_w_rad == pytest.approx(alpha_w, abs=1e-14)
    assert g.j_n_mm == pytest.approx(j_n, rel=1e-9)
    assert g.j_wt_mm == pytest.approx(j_n / math.cos(alpha_w), rel=1e-9)
    assert g.j_n_mm == pytest.approx(2.0 * 1.0 * math.sin(DEG20), rel=0.03)  # ≈ 2 Δa sin α
    assert g.errors == ()


def test_backlash_from_thickness_allowances_at_reference_centre_distance():
    spec = PairSpec(10.0, DEG20, GearSpec(17, 100.0, thickness_allowance_mm=0.1),
                    GearSpec(25, 100.0, thickness_allowance_mm=0.15))
    g = compute_pair_geometry(spec)
    assert g.a_w_mm == pytest.approx(210.0, abs=1e-9)  # allowances do not move a_w
    assert g.j_wt_mm == pytest.approx(0.25, abs=1e-12)  # α_w = α: j_wt = A_s1 + A_s2
    assert g.j_n_mm == pytest.approx(0.25 * math.cos(DEG20), abs=1e-12)
    assert g.pinion.s_mm == pytest.approx(5 * math.pi - 0.1, abs=1e-12)
    assert g.a_w_zero_backlash_mm < 210.0


def test_negative_backlash_and_undefined_operating_angle_are_errors():
    tight = compute_pair_geometry(seed_spec(centre_distance_mm=209.5))
    assert tight.j_wt_mm < 0.0
    assert "centre_distance" in codes(tight, "error")
    far = compute_pair_geometry(seed_spec(centre_distance_mm=190.0))  # below a cos α = 197.3
    assert math.isnan(far.alpha_w_rad) and math.isnan(far.eps_alpha)
    assert "centre_distance" in codes(far, "error")
    assert "clearance" in codes(far, "error")


def test_clearance_error_and_warning():
    neg = compute_pair_geometry(PairSpec(10.0, DEG20, GearSpec(17, 100.0, 0.0, -0.5),
                                         GearSpec(25, 100.0)))
    assert neg.pinion.tip_clearance_mm == pytest.approx(-2.5, abs=1e-9)
    assert "clearance" in codes(neg, "error")
    low = compute_pair_geometry(PairSpec(10.0, DEG20, GearSpec(17, 100.0, 0.0, -0.2),
                                         GearSpec(25, 100.0)))
    assert low.pinion.tip_clearance_mm == pytest.approx(0.5, abs=1e-9)
    assert low.gear.root_clearance_mm == pytest.approx(0.5, abs=1e-9)
    assert "clearance" in codes(low, "warning") and "clearance" not in codes(low, "error")


def test_impossible_gears_are_reported_not_raised():
    g = compute_pair_geometry(PairSpec(10.0, DEG20, GearSpec(2, 100.0), GearSpec(25, 100.0)))
    assert "root_diameter" in codes(g, "error")
    g = compute_pair_geometry(PairSpec(10.0, DEG20, GearSpec(17, 100.0, -5.0),
                                       GearSpec(25, 100.0, -5.0)))
    assert "tip_diameter" in codes(g, "error") and "centre_distance" in codes(g, "error")
    g = compute_pair_geometry(PairSpec(10.0, DEG20, GearSpec(17, 100.0, tip_rounding_mm=6.0),
                                       GearSpec(25, 100.0)))
    assert "tip_rounding" in codes(g, "error")


def test_tip_rounding_shortens_the_path_of_contact():
    plain = compute_pair_geometry(seed_spec())
    rounded = compute_pair_geometry(
        PairSpec(10.0, DEG20, GearSpec(17, 100.0, tip_rounding_mm=2.0), GearSpec(25, 100.0))
    )
    assert rounded.pinion.d_Fa_mm < rounded.pinion.d_a_mm
    assert rounded.E_mm < plain.E_mm and rounded.A_mm == pytest.approx(plain.A_mm)
    assert rounded.E_mm == pytest.approx(
        math.sqrt((rounded.pinion.d_Fa_mm / 2) ** 2 - (rounded.pinion.d_b_mm / 2) ** 2)
    )


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"module_mm": 0.0}, "module_mm"),
        ({"pressure_angle_rad": 0.0}, "pressure_angle_rad"),
        ({"pressure_angle_rad": math.pi / 4}, "pressure_angle_rad"),
        ({"pinion": GearSpec(0, 100.0)}, "pinion.teeth"),
        ({"gear": GearSpec(25, 100.0, thickness_allowance_mm=-0.1)}, "thickness_allowance"),
        ({"rack": RackSpec(1.0, 1.25, 0.6)}, "root_radius_coef"),
        ({"centre_distance_mm": -1.0}, "centre_distance_mm"),
    ],
)
def test_invalid_numbers_raise_value_error(kwargs, match):
    base = {"module_mm": 10.0, "pressure_angle_rad": DEG20, "pinion": GearSpec(17, 100.0),
            "gear": GearSpec(25, 100.0)}
    with pytest.raises(ValueError, match=match):
        compute_pair_geometry(PairSpec(**{**base, **kwargs}))


def test_disc_mass_inertia_seed_pinion():
    from gearcli.model.params import disc_mass_inertia

    mass, inertia = disc_mass_inertia(7.85e-9, 170.0, 100.0)  # steel, t/mm³
    assert mass == pytest.approx(7.85e-9 * math.pi * 85.0**2 * 100.0, rel=1e-14)  # 17.8 kg
    # second method: J = ∫ r² dm over thin rings (midpoint rule, error ~ (Δr/r)² ~ 1e-8)
    r = (np.arange(20000) + 0.5) * (85.0 / 20000)
    ring_mass = 7.85e-9 * 2 * np.pi * r * (85.0 / 20000) * 100.0
    assert inertia == pytest.approx(np.sum(ring_mass * r**2), rel=1e-7)
    with pytest.raises(ValueError, match="diameter_mm"):
        disc_mass_inertia(7.85e-9, 0.0, 100.0)


def test_findings_name_their_gear():
    g = compute_pair_geometry(PairSpec(10.0, DEG20, GearSpec(8, 100.0), GearSpec(60, 100.0)))
    assert {(f.code, f.subject) for f in g.findings} == {
        ("undercut", "pinion"), ("interference", "pinion")}
    g = compute_pair_geometry(seed_spec(centre_distance_mm=209.5))
    assert ("centre_distance", None) in {(f.code, f.subject) for f in g.findings}
    for f in g.findings:  # one line each, naming the quantity, a value with unit and a limit
        assert "\n" not in f.message and ("allowed" in f.message or "recommended" in f.message)
