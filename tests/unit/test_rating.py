"""ISO 6336 / Hertz stresses (model.rating, model.contact_point) against independent references.

* Hertz line contact: Johnson's half-width route and a hand-computed number.
* Pitch-point nominal σ_H0 = Z_H Z_E √(F_t (u+1)/(d1 b u)) of the seed pair, every factor
  recomputed here from the ISO 6336-2 formulas and the seed's data (Table 1).
* Y_F, Y_S of a standard 20° rack (ISO 53 A: h_fP = 1.25 m, ρ_fP = 0.38 m) at z = 17, 25, 40,
  100 from ISO 6336-3 Method B's own closed form (E, G, H, θ iteration) written out here, against
  the library's construction on the generated fillet of model.profile.
"""

import math
from dataclasses import replace

import numpy as np
import pytest

from gearcli.model.contact_point import contact_points, pair_frame, tooth_angles
from gearcli.model.geometry import GearSpec, PairSpec, compute_pair_geometry
from gearcli.model.rating import (
    effective_modulus,
    form_factors,
    hertz_line_contact_stress,
    involute_load_line,
    load_line,
    root_section,
    root_stress,
    single_pair_contact_factors,
    static_rating,
)
from gearcli.pipeline.stress import tooth_maxima

ALPHA = math.radians(20.0)
E_STEEL, NU_STEEL = 2.07e5, 0.29  # seed Table 1 [N/mm², -]

# The fillet is a spline through 1601 exact points of model.profile's trochoid; both sides
# describe the same curve, so the only differences are spline interpolation (~(1/1600)² in the
# curvature ρ_F, < 1e-6 relative) and root finding (1e-14): 2e-6 relative covers them with room.
ISO_RTOL = 2e-6


def pair(z1, z2, m=10.0, b=100.0, **kw):
    return compute_pair_geometry(PairSpec(m, ALPHA, GearSpec(z1, b, **kw), GearSpec(z2, b)))


# --- Hertz -------------------------------------------------------------------------------------
def test_hertz_matches_johnson_half_width_route_and_a_hand_value():
    # Two steel cylinders R1 = R2 = 20 mm, E = 210 GPa, ν = 0.3, P = F/b = 1000 N/mm:
    # E* = E/(2(1 − ν²)) = 115384.6 N/mm², R = 10 mm, p0 = √(P E*/(π R)) = 1916.46 N/mm².
    e_star = effective_modulus(2.1e5, 0.3, 2.1e5, 0.3)
    assert e_star == pytest.approx(2.1e5 / (2 * (1 - 0.09)), rel=1e-14)
    sig = hertz_line_contact_stress(20_000.0, 20.0, 20.0, 20.0, e_star)
    assert sig == pytest.approx(1916.46, abs=0.01)
    # Johnson §4.3: a = √(4 P R/(π E*)), p0 = 2 P/(π a)
    p, r = 1000.0, 10.0
    a = math.sqrt(4 * p * r / (math.pi * e_star))
    assert sig == pytest.approx(2 * p / (math.pi * a), rel=1e-12)


def test_hertz_at_the_seed_pitch_point_for_a_known_force():
    geo = pair(17, 25)
    force, b = 10_000.0, 100.0
    rho1 = geo.pinion.r_b_mm * math.tan(geo.alpha_w_rad)  # |T1C|
    rho2 = geo.gear.r_b_mm * math.tan(geo.alpha_w_rad)  # |T2C|
    cp = contact_points(geo, [geo.C_mm - geo.A_mm])
    assert cp.rho1_mm[0] == pytest.approx(rho1, rel=1e-12)
    assert cp.rho2_mm[0] == pytest.approx(rho2, rel=1e-12)
    e_star = 1.0 / (2 * (1 - NU_STEEL**2) / E_STEEL)
    r_red = rho1 * rho2 / (rho1 + rho2)
    a = math.sqrt(4 * (force / b) * r_red / (math.pi * e_star))
    expected = 2 * (force / b) / (math.pi * a)
    got = hertz_line_contact_stress(force, b, cp.rho1_mm, cp.rho2_mm,
                                    effective_modulus(E_STEEL, NU_STEEL, E_STEEL, NU_STEEL))
    assert got[0] == pytest.approx(expected, rel=1e-12)


def test_seed_pitch_point_nominal_contact_stress():
    # Seed: z 17/25, m 10, α 20°, b 100, x = 0, T_load = 450 N·m on the gear.
    z1, z2, m, b = 17, 25, 10.0, 100.0
    d1, d2 = m * z1, m * z2
    f_t = 450e3 / (d2 / 2)  # 3600 N on the reference circle
    u = z2 / z1
    z_h = math.sqrt(2 * math.cos(ALPHA) / (math.cos(ALPHA) ** 2 * math.sin(ALPHA)))  # α_w = α
    z_e = math.sqrt(1 / (math.pi * 2 * (1 - NU_STEEL**2) / E_STEEL))
    expected = z_h * z_e * math.sqrt(f_t * (u + 1) / (d1 * b * u))
    assert z_h == pytest.approx(2.4946, abs=1e-4) and z_e == pytest.approx(189.66, abs=0.01)
    assert expected == pytest.approx(282.19, abs=0.01)
    geo = pair(z1, z2)
    st = static_rating(geo, 450e3 / geo.gear.r_b_mm, (E_STEEL, E_STEEL), (NU_STEEL, NU_STEEL))
    assert st.force_tangential_N == pytest.approx(f_t, rel=1e-12)
    assert st.sigma_H0_MPa == pytest.approx(expected, rel=1e-12)
    # the same number is the Hertz stress of the full normal force at C
    cp = contact_points(geo, [geo.C_mm - geo.A_mm])
    at_c = hertz_line_contact_stress(st.force_normal_N, b, cp.rho1_mm, cp.rho2_mm, st.e_star_MPa)
    assert at_c[0] == pytest.approx(expected, rel=1e-12)
    # Z_ε for ε_α = 1.5630 (docs/theory.md §9)
    assert st.Z_eps == pytest.approx(math.sqrt((4 - geo.eps_alpha) / 3), rel=1e-14)


def test_single_pair_factors_are_the_hertz_ratios_at_B_and_D():
    geo = pair(17, 25)
    m1, m2, z_b, z_d = single_pair_contact_factors(geo)
    st = static_rating(geo, 5000.0, (E_STEEL, E_STEEL), (NU_STEEL, NU_STEEL))
    for point, factor in ((geo.B_mm, m1), (geo.D_mm, m2)):
        rho1 = point
        sig = hertz_line_contact_stress(5000.0, 100.0, rho1, geo.T1T2_mm - rho1, st.e_star_MPa)
        assert sig == pytest.approx(factor * st.sigma_H0_MPa, rel=1e-12)
    assert z_b == max(m1, 1.0) and z_d == max(m2, 1.0)
    assert m1 > 1.0 > m2  # seed: B is worse than C, D is better (C lies in the single zone)


# --- ISO 6336-3 Method B, independent closed form ------------------------------------------------
def iso_method_b(z, m, x, d_en, h_fp=1.25, rho_fp=0.38, alpha=ALPHA):
    """ISO 6336-3:2019 Method B, spur (β = 0, z_n = z), generating rack without protuberance.

    Returns (Y_F, Y_S, s_Fn, ρ_F, h_Fe) [-, -, mm, mm, mm] for a load at diameter d_en.
    """
    h_fp, rho_fp = h_fp * m, rho_fp * m
    e = math.pi / 4 * m - h_fp * math.tan(alpha) - (1 - math.sin(alpha)) * rho_fp / math.cos(alpha)
    g = rho_fp / m - h_fp / m + x
    h = 2 / z * (math.pi / 2 - e / m) - math.pi / 3
    theta = math.pi / 6
    for _ in range(200):  # θ = 2G/z tan θ − H (fixed point, converges in a few steps)
        theta = 2 * g / z * math.tan(theta) - h
    s_fn = m * (z * math.sin(math.pi / 3 - theta) + math.sqrt(3) * (g / math.cos(theta)
                                                                   - rho_fp / m))
    rho_f = m * (rho_fp / m + 2 * g * g / (math.cos(theta) * (z * math.cos(theta) ** 2 - 2 * g)))
    d_b = m * z * math.cos(alpha)
    a_en = math.acos(d_b / d_en)
    inv = lambda a: math.tan(a) - a  # noqa: E731
    gamma_e = (0.5 * math.pi + 2 * math.tan(alpha) * x) / z + inv(alpha) - inv(a_en)
    a_fen = a_en - gamma_e
    h_fe = 0.5 * m * ((math.cos(gamma_e) - math.sin(gamma_e) * math.tan(a_fen)) * d_en / m
                      - z * math.cos(math.pi / 3 - theta) - g / math.cos(theta) + rho_fp / m)
    y_f = 6 * (h_fe / m) * math.cos(a_fen) / ((s_fn / m) ** 2 * math.cos(alpha))
    big_l = s_fn / h_fe
    q_s = s_fn / (2 * rho_f)
    y_s = (1.2 + 0.13 * big_l) * q_s ** (1 / (1.21 + 2.3 / big_l))
    return y_f, y_s, s_fn, rho_f, h_fe


def iso_outer_single_contact_diameter(z, z_mate, m, alpha=ALPHA):
    """ISO 6336-3 d_en (spur, x = 0, a_w = a): outer point of single contact of gear z."""
    rb, rbm = m * z * math.cos(alpha) / 2, m * z_mate * math.cos(alpha) / 2
    ra, ram = m * z / 2 + m, m * z_mate / 2 + m
    p_b = math.pi * m * math.cos(alpha)
    a = m * (z + z_mate) / 2
    g_a = math.sqrt(ra**2 - rb**2) + math.sqrt(ram**2 - rbm**2) - a * math.sin(alpha)
    eps = g_a / p_b
    return 2 * math.sqrt((math.sqrt(ra**2 - rb**2) - p_b * (eps - 1)) ** 2 + rb**2)


@pytest.mark.parametrize(("z1", "z2"), [(17, 25), (40, 100)])
def test_form_and_stress_correction_factors_match_iso_closed_form(z1, z2):
    m = 10.0
    geo = pair(z1, z2, m)
    st = static_rating(geo, 1000.0, (E_STEEL, E_STEEL), (NU_STEEL, NU_STEEL))
    for which, z, mate in (("pinion", z1, z2), ("gear", z2, z1)):
        g, gs = getattr(geo, which), getattr(st, which)
        y_f, y_s, s_fn, rho_f, h_fe = iso_method_b(z, m, 0.0, iso_outer_single_contact_diameter(
            z, mate, m))
        assert gs.section.s_Fn_mm == pytest.approx(s_fn, rel=ISO_RTOL)
        assert gs.section.rho_F_mm == pytest.approx(rho_f, rel=ISO_RTOL)
        assert gs.h_Fe_mm == pytest.approx(h_fe, rel=ISO_RTOL)
        assert gs.Y_F == pytest.approx(y_f, rel=ISO_RTOL), (which, z)
        assert gs.Y_S == pytest.approx(y_s, rel=ISO_RTOL), (which, z)
        # tip loading (d_en = d_a): Y_Fa, Y_Sa
        y_fa, y_sa, *_ = iso_method_b(z, m, 0.0, g.d_a_mm)
        assert gs.Y_Fa == pytest.approx(y_fa, rel=ISO_RTOL)
        assert gs.Y_Sa == pytest.approx(y_sa, rel=ISO_RTOL)


@pytest.mark.parametrize(("z", "x"), [(25, -0.2), (25, 0.3), (25, 0.6), (12, 0.0), (30, -0.5)])
def test_profile_shift_and_undercut_move_the_section_like_iso(z, x):
    # (12, 0.0) is undercut: the 30° point still lies on the tool-rounding trochoid
    geo = pair(z, 40, 4.0, profile_shift=x)
    g = geo.pinion
    _, _, s_fn, rho_f, _ = iso_method_b(z, 4.0, x, g.d_a_mm)
    sec = root_section(g)
    assert sec.s_Fn_mm == pytest.approx(s_fn, rel=ISO_RTOL)
    assert sec.rho_F_mm == pytest.approx(rho_f, rel=ISO_RTOL)


def test_root_stress_is_the_section_bending_stress_times_Y_S():
    geo = pair(17, 25)
    g = geo.pinion
    sec = root_section(g)
    y_l, a_fen = involute_load_line(g, 0.5 * (g.d_a_mm + g.d_mm))
    y_f, y_s, h = form_factors(g, sec, y_l, a_fen)
    sig = root_stress(2000.0, 80.0, g, sec, y_l, a_fen)
    bending = 2000.0 * math.cos(a_fen) * h / (80.0 * sec.s_Fn_mm**2 / 6.0)  # M / W
    assert sig == pytest.approx(bending * y_s, rel=1e-12)


# --- contact points ---------------------------------------------------------------------------
def test_general_load_line_reproduces_the_involute_one_on_the_path():
    geo = pair(17, 25)
    x = np.linspace(0.0, geo.g_alpha_mm, 9)
    _, o2, t1, n = pair_frame(geo)
    b1, b2 = tooth_angles(geo, x)
    p = t1 + (geo.A_mm + x)[:, None] * n
    y, a = load_line(p, np.broadcast_to(-n, p.shape), b1)  # the gear pushes the pinion back
    yi, ai = involute_load_line(geo.pinion, np.hypot(p[:, 0], p[:, 1]))
    np.testing.assert_allclose(y, yi, rtol=0, atol=1e-10)
    np.testing.assert_allclose(a, ai, rtol=0, atol=1e-12)
    y, a = load_line(p - o2, np.broadcast_to(n, p.shape), b2)
    yi, ai = involute_load_line(geo.gear, np.hypot(p[:, 0] - o2[0], p[:, 1]))
    np.testing.assert_allclose(y, yi, rtol=0, atol=1e-10)
    np.testing.assert_allclose(a, ai, rtol=0, atol=1e-12)


def test_tip_rounding_contact_is_continuous_at_A_and_E():
    base = PairSpec(10.0, ALPHA, GearSpec(17, 100.0, tip_rounding_mm=1.0),
                    GearSpec(25, 100.0, tip_rounding_mm=1.5))
    geo = compute_pair_geometry(base)
    h = 1e-9
    for x_end in (0.0, geo.g_alpha_mm):
        inside = contact_points(geo, [x_end - h if x_end else h])
        outside = contact_points(geo, [x_end + h if x_end else -h])
        assert not outside.clamped[0] and outside.region[0] != 0
        for name in ("y_load1_mm", "alpha_fen1_rad", "y_load2_mm", "alpha_fen2_rad"):
            assert getattr(outside, name)[0] == pytest.approx(getattr(inside, name)[0], abs=1e-6)
    # the rounded tip's own curvature takes over outside the path
    cp = contact_points(geo, [-0.5, geo.g_alpha_mm + 0.5])
    assert cp.rho2_mm[0] == 1.5 and cp.rho1_mm[1] == 1.0
    # before A the gear tip touches the pinion higher up its flank (ρ1 grows), off the LoA
    rho1 = contact_points(geo, [-2.0, -1.0, -1e-6]).rho1_mm
    assert rho1[0] > rho1[1] > rho1[2] > geo.A_mm


def test_sharp_corner_contact_is_clamped_and_flagged():
    geo = pair(17, 25)
    cp = contact_points(geo, [-0.3, 0.0, geo.g_alpha_mm, geo.g_alpha_mm + 0.3])
    assert cp.clamped.tolist() == [True, False, False, True]
    assert cp.region.tolist() == [-1, 0, 0, 1]
    assert cp.rho1_mm[0] == cp.rho1_mm[1] == pytest.approx(geo.A_mm)
    assert cp.rho1_mm[3] == cp.rho1_mm[2] == pytest.approx(geo.E_mm)


def test_face_widths_for_contact_and_bending():
    spec = PairSpec(10.0, ALPHA, GearSpec(17, 120.0), GearSpec(25, 90.0))
    geo = compute_pair_geometry(spec)
    st = static_rating(geo, 1000.0, (E_STEEL, E_STEEL), (NU_STEEL, NU_STEEL))
    assert st.contact_face_width_mm == 90.0
    assert st.pinion.face_width_mm == 110.0  # narrower + 2 m
    assert st.gear.face_width_mm == 90.0
    wide = compute_pair_geometry(replace(spec, pinion=GearSpec(17, 100.0)))
    assert static_rating(wide, 1.0, (E_STEEL,) * 2, (NU_STEEL,) * 2).pinion.face_width_mm == 100


def test_tooth_maxima_follow_the_slot_to_tooth_mapping():
    # two slots, z = 3; slot j at cycle n holds tooth (n − j) mod 3
    cycle = np.array([0, 0, 1, 1, 2, 2, 3])
    values = np.array([[1, 10], [2, 20], [3, 30], [4, 40], [5, 50], [6, 60], [7, 70]], float)
    loaded = np.ones_like(values, bool)
    sel = np.ones(cycle.size, bool)
    # tooth 0: (n=0,j=0)->2, (n=1,j=1)->40, (n=3,j=0)->7; tooth 1: (1,0)->4, (2,1)->60;
    # tooth 2: (0,1)->20, (2,0)->6, (3,1)->70
    np.testing.assert_array_equal(tooth_maxima(values, cycle, sel, loaded, 3), [40, 60, 70])
    loaded[:, 1] = False  # slot 1 unloaded: only slot 0, tooth n mod 3
    sel[4:] = False  # and only cycles 0, 1: tooth 2 never loaded -> NaN
    out = tooth_maxima(values, cycle, sel, loaded, 3)
    np.testing.assert_array_equal(out[:2], [2, 4])
    assert math.isnan(out[2])
