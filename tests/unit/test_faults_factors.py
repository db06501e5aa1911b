"""Tooth faults as stiffness factors (docs/theory.md "Tooth faults"; gearcli/model/faults).

* zero-size faults give exact ones; a missing tooth gives zero mesh stiffness over
  (2 − ε_α) p_b of a pinion revolution and changes nothing outside its own ε_α p_b;
* the factors fall monotonically with crack depth and crack width, spall width and depth,
  chip width; spalls and chips act only over their span;
* the cracked tooth's compliance (the model's healthy tables plus the crack's added integrals)
  against an independent quadrature of M²/(EI), V²/(GA), N²/(EA) over the cracked section
  written here (no published number for this geometry was within reach: the brief's fallback);
* the tooth indices: tooth 0 of both gears at C at θ1 = 0, by brute force over the kernel's
  slot formula (core/flank.py) for several table ranges.

Units: mm, N, MPa, rad.
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from gearcli.model import profile
from gearcli.model.faults import ChippedTip, MissingTooth, RootCrack, Spall, tooth_index_offsets
from gearcli.model.faults.factors import (
    crack_compliance,
    crack_section,
    fault_factors,
    revolution_stiffness,
)
from gearcli.model.geometry import GearSpec, PairSpec, compute_pair_geometry
from gearcli.model.pair_stiffness import pair_contact, pair_stiffness
from gearcli.model.rating import root_section
from gearcli.model.tooth_stiffness import tooth_compliance_at, tooth_section

E, NU = 2.07e5, 0.29
E_PS, G = E / (1.0 - NU**2), E / (2.0 * (1.0 + NU))
A20 = math.radians(20.0)
SEED = compute_pair_geometry(PairSpec(10.0, A20, GearSpec(17, 100), GearSpec(25, 100)))
SHIFTED = compute_pair_geometry(PairSpec(5.0, A20, GearSpec(21, 50, 0.35), GearSpec(43, 50, -0.2)))
KW = {"face_width_mm": 100.0, "E1_MPa": E, "nu1": NU, "E2_MPa": E, "nu2": NU}


def _stiffness(pair, x):
    return pair_stiffness(pair, x, **{**KW, "face_width_mm": pair.pinion.face_width_mm})


def _path(pair, n=201):
    return np.linspace(0.0, pair.g_alpha_mm, n)


@pytest.mark.parametrize("fault", [
    RootCrack("pinion", 3, 0.0), RootCrack("gear", 3, 4.0, width=0.0),
    Spall("pinion", 1, 0.0, 0.5, 0.1, diameter_mm=170.0),
    Spall("gear", 1, 5.0, 0.0, 0.1, diameter_mm=250.0),
    Spall("gear", 1, 5.0, 0.5, 0.0, roll_angle_deg=20.0),
    ChippedTip("pinion", 0, 0.0), ChippedTip("gear", 24, 3.0, width=0.0)])
def test_zero_size_faults_are_exact_ones(fault):
    ps = _stiffness(SEED, _path(SEED))
    table = fault_factors(SEED, ps, [fault])
    assert table.shape == (4, 25, ps.x_mm.size)
    assert np.all(table == 1.0)


def test_refused_faults():
    for make, match in ((lambda: RootCrack("ring", 0, 1.0), "gear"),
                        (lambda: RootCrack("pinion", -1, 1.0), "tooth"),
                        (lambda: RootCrack("pinion", 0, 1.0, width=1.5), "share"),
                        (lambda: RootCrack("pinion", 0, -1.0), "depth"),
                        (lambda: Spall("pinion", 0, 1.0, 0.5, 0.1), "exactly one"),
                        (lambda: ChippedTip("gear", 0, -2.0), "height")):
        with pytest.raises(ValueError, match=match):
            make()
    ps = _stiffness(SEED, _path(SEED, 5))
    with pytest.raises(ValueError, match="17 teeth"):
        fault_factors(SEED, ps, [MissingTooth("pinion", 17)])
    with pytest.raises(ValueError, match="runs through"):
        fault_factors(SEED, ps, [RootCrack("pinion", 0, 30.0, 90.0)])


def test_factors_fall_with_crack_depth_and_width():
    """Per position on the path: non-increasing in depth (strictly where the contact is above
    the crack start, i.e. everywhere on the seed pinion's path) and linear, decreasing, in the
    width share."""
    ps = _stiffness(SEED, _path(SEED))
    depths = [0.0, 0.5, 1.0, 2.0, 4.0, 6.0, 8.0, 10.0]
    f = np.array([fault_factors(SEED, ps, [RootCrack("pinion", 2, q)])[0, 2] for q in depths])
    assert np.all(np.diff(f, axis=0) < 0.0)
    assert np.all(f[1:] > 0.0) and np.all(f <= 1.0)
    # the deeper the crack, the more the load at the tip suffers (longer lever)
    assert np.all(f[1:, -1] < f[1:, 0])
    widths = [0.0, 0.25, 0.5, 0.75, 1.0]
    fw = np.array([fault_factors(SEED, ps, [RootCrack("pinion", 2, 6.0, width=w)])[0, 2]
                   for w in widths])
    assert np.all(np.diff(fw, axis=0) < 0.0)
    np.testing.assert_allclose(fw[2], 0.5 * (fw[0] + fw[4]), rtol=1e-14)
    # the other teeth and the other gear are untouched
    table = fault_factors(SEED, ps, [RootCrack("pinion", 2, 6.0)])
    assert np.all(np.delete(table[0], 2, axis=0) == 1.0) and np.all(table[1:] == 1.0)


def _h_of_y(gear):
    """Half thickness h(y) of the tooth, built here: the fillet as a dense polyline of
    profile.fillet_points (20001 points), the involute's radius solved from y (Brent)."""
    rad, psi = profile.fillet_points(gear, 20001)
    yf, hf = rad * np.cos(psi), rad * np.sin(psi)

    def h(y):
        if y <= yf[-1]:
            return float(np.interp(y, yf, hf))
        r = brentq(lambda r: r * math.cos(float(profile.flank_half_angle(gear, r))) - y,
                   gear.r_b_mm, gear.r_a_mm * 1.001, xtol=1e-14)
        return r * math.sin(float(profile.flank_half_angle(gear, r)))

    return h, yf[0], yf[-1]


@pytest.mark.parametrize("gear, depth, angle, where", [
    (SEED.pinion, 4.0, 45.0, 0.5), (SEED.pinion, 8.0, 60.0, 0.95), (SEED.gear, 3.0, 30.0, 0.2),
    (SHIFTED.pinion, 2.5, 45.0, 0.7), (SHIFTED.gear, 3.5, 75.0, 0.9)])
def test_cracked_tooth_against_independent_quadrature(gear, depth, angle, where):
    """Cracked tooth, load on the involute at a share ``where`` of the active flank, along its
    normal: bending, shear and axial compliance by direct quadrature over the section written
    here (Tian 2004; Chaari et al. 2009: above the crack start at ISO's 30° point, every
    section whose half thickness h exceeds h_q = h_c − q sin ν keeps the thickness h + h_q).
    Reference to quad 1e-9 on a polyline fillet (chord error ~1e-9 mm); the model's crack
    integrals use a cubic spline of h through the section's ~700 nodes (its error in h is
    ~Δy⁴ h'''' ≲ 1e-8 relative on the involute, larger near the fillet's curvature change):
    tolerance 1e-5 on the cracked total, whose crack share is 3-57 % here (measured 1e-9 …
    6e-7)."""
    h_of_y, y0, y_ff = _h_of_y(gear)
    rs = root_section(gear)
    y_c, h_c = rs.y_F_mm, 0.5 * rs.s_Fn_mm
    h_q = h_c - depth * math.sin(math.radians(angle))
    r_lo = max(profile.root_form_radius(gear), gear.r_b_mm)
    r = r_lo + where * (profile.tip_form_radius(gear) - r_lo)
    psi = float(profile.flank_half_angle(gear, r))
    h_p, y_p = r * math.sin(psi), r * math.cos(psi)
    a1 = math.acos(gear.r_b_mm / r) - psi
    y_l = y_p - h_p * math.tan(a1)
    b = gear.face_width_mm

    def h_e(y):
        h = h_of_y(y)
        return 0.5 * (h + h_q) if (y >= y_c and h > h_q) else h

    kw = {"epsabs": 0, "epsrel": 1e-10, "limit": 500}
    breaks = sorted({y0, y_ff, y_c, y_p} | {y for y in (y_ff,) if y < y_p})
    breaks = [v for v in breaks if v <= y_p]
    ref = 0.0
    for lo, hi in zip(breaks[:-1], breaks[1:], strict=True):
        ref += quad(lambda y: (math.cos(a1) * (y_l - y)) ** 2 / (E_PS * (2 * h_e(y)) ** 3 * b / 12)
                    + 1.2 * math.cos(a1) ** 2 / (G * 2 * h_e(y) * b)
                    + math.sin(a1) ** 2 / (E_PS * 2 * h_e(y) * b), lo, hi, **kw)[0]
    healthy = tooth_compliance_at(tooth_section(gear), y_p, y_l, a1, face_width_mm=b,
                                  youngs_MPa=E, poisson=NU, bore_diameter_mm=gear.r_f_mm)
    beam = float(healthy.bending_mm_N + healthy.shear_mm_N + healthy.axial_mm_N)
    added = float(crack_compliance(gear, healthy, y_p, y_l, depth, angle)[0])
    assert 0.02 < added / (beam + added) < 0.65  # the crack matters here
    assert beam + added == pytest.approx(ref, rel=1e-5)


def test_crack_section_is_zero_below_the_crack_and_continuous():
    crack = crack_section(SEED.pinion, 5.0, 45.0)
    below = crack.integrals(np.linspace(crack.y0_mm, crack.y_start_mm, 7))
    assert np.all(below == 0.0)
    y = np.linspace(crack.y_start_mm, crack.y_mm[-1], 3001)
    v = crack.integrals(y)
    assert np.all(np.diff(v[0]) >= 0.0) and np.all(np.diff(v[3]) >= 0.0)
    # the cumulative table and the in-between Gauss rule agree at the nodes
    np.testing.assert_allclose(crack.integrals(crack.y_mm[5:-1:37]), crack.cum[:, 5:-1:37],
                               rtol=1e-12, atol=0.0)


def test_a_missing_tooth_is_zero_over_two_minus_eps_of_a_mesh_period():
    """Rigid-kinematics mesh stiffness over a pinion revolution with pinion tooth 5 missing:
    zero over (2 − ε_α) p_b (where tooth 5 would carry alone), the sound mesh's elsewhere
    except over the ε_α p_b where tooth 5 would be on the path; grid p_b/400: tolerance two
    grid steps on the lengths."""
    pair = SEED
    n = 400
    step = pair.p_b_mm / n
    sound = revolution_stiffness(pair, lambda x: _stiffness(pair, x), [], points_per_pitch=n)
    rev = revolution_stiffness(pair, lambda x: _stiffness(pair, x),
                               [MissingTooth("pinion", 5)], points_per_pitch=n)
    assert np.all(sound.k_mesh_N_mm > 0.0)
    np.testing.assert_array_equal(sound.k_mesh_N_mm, sound.healthy_N_mm)
    zero = rev.k_mesh_N_mm == 0.0
    assert zero.sum() * step == pytest.approx((2.0 - pair.eps_alpha) * pair.p_b_mm,
                                              abs=2 * step)
    changed = rev.k_mesh_N_mm != sound.k_mesh_N_mm
    assert changed.sum() * step == pytest.approx(pair.eps_alpha * pair.p_b_mm, abs=2 * step)
    # where: tooth 5 is at C at s1 = 5 p_b; it is on the path from s1 = 5 p_b − x_C to
    # 5 p_b + g_α − x_C
    x_c = pair.C_mm - pair.A_mm
    s = rev.s1_mm[changed]
    assert s.min() == pytest.approx(5 * pair.p_b_mm - x_c, abs=2 * step)
    assert s.max() == pytest.approx(5 * pair.p_b_mm + pair.g_alpha_mm - x_c, abs=2 * step)
    # a gear tooth: the same over a gear revolution
    gear_rev = revolution_stiffness(pair, lambda x: _stiffness(pair, x),
                                    [MissingTooth("gear", 20)], pitches=25, points_per_pitch=n)
    assert (gear_rev.k_mesh_N_mm == 0.0).sum() * step == pytest.approx(
        (2.0 - pair.eps_alpha) * pair.p_b_mm, abs=2 * step)


def test_spall_and_chip_act_over_their_span_only():
    """A spall on the pinion centred on its pitch diameter, 6 mm along the profile: factor < 1
    exactly where the pinion's own roll distance ρ1 = |T1A| + x lies within the span
    √(ρ_c² ± r_b L) (involute arc length ρ²/(2 r_b)), 1 elsewhere; the factor falls with the
    width share, and with depth up to the deflection, then stays; a full-width pit deeper
    than the deflection is 0 over its span. A chipped gear tip (3 mm, full width) is 0 where
    the gear's contact radius exceeds r_a2 − 3 mm and 1 below."""
    pair = SEED
    ps = _stiffness(pair, _path(pair, 801))
    x = ps.x_mm
    r_b = pair.pinion.r_b_mm
    rho_c = math.sqrt(pair.pinion.r_mm**2 - r_b**2)
    lo, hi = math.sqrt(rho_c**2 - 6.0 * r_b), math.sqrt(rho_c**2 + 6.0 * r_b)
    inside = (pair.A_mm + x >= lo) & (pair.A_mm + x <= hi)
    assert 20 < inside.sum() < 400

    def spall(width, depth, defl=0.01):
        s = Spall("pinion", 4, 6.0, width, depth, diameter_mm=2 * pair.pinion.r_mm)
        return fault_factors(pair, ps, [s], deflection_mm=defl)[0, 4]

    f = spall(0.5, 0.05)
    assert np.all(f[~inside] == 1.0) and np.all(f[inside] < 1.0)
    widths = np.array([spall(w, 0.05) for w in (0.2, 0.4, 0.6, 0.8, 0.99)])
    assert np.all(np.diff(widths[:, inside], axis=0) < 0.0)
    depths = np.array([spall(0.5, d) for d in (0.002, 0.005, 0.008, 0.01, 0.02)])
    assert np.all(np.diff(depths[:4, inside], axis=0) < 0.0)
    np.testing.assert_array_equal(depths[3], depths[4])  # deeper than the deflection
    assert np.all(spall(1.0, 0.05)[inside] == 0.0)
    # roll angle form: the same centre
    same = Spall("pinion", 4, 6.0, 0.5, 0.05, roll_angle_deg=math.degrees(rho_c / r_b))
    np.testing.assert_allclose(fault_factors(pair, ps, [same], deflection_mm=0.01)[0, 4], f,
                               rtol=0, atol=1e-15)
    chip = fault_factors(pair, ps, [ChippedTip("gear", 7, 3.0)])[1, 7]
    rho2 = pair.T1T2_mm - pair.A_mm - x
    r2 = np.hypot(pair.gear.r_b_mm, rho2)
    above = r2 > pair.gear.r_a_mm - 3.0
    assert 10 < above.sum() < 400
    assert np.all(chip[above] == 0.0) and np.all(chip[~above] == 1.0)
    half = fault_factors(pair, ps, [ChippedTip("gear", 7, 3.0, width=0.5)])[1, 7]
    assert np.all((half[above] > 0.0) & (half[above] < 1.0)) and np.all(half[~above] == 1.0)


def test_flank_rows():
    """Rows drive pinion, drive gear, coast pinion, coast gear (core.layout TABLE_*): a crack
    (closed under coast load) and a spall (on the drive flank) only on the drive row; a
    missing tooth and a chipped tip on both, the coast row the drive row's function of the
    coast roll position (symmetric teeth)."""
    ps = _stiffness(SEED, _path(SEED))
    table = fault_factors(SEED, ps, [
        RootCrack("pinion", 1, 5.0), Spall("gear", 2, 5.0, 0.5, 0.1, diameter_mm=250.0),
        MissingTooth("pinion", 3), ChippedTip("gear", 4, 2.0, width=0.6)])
    assert table[0, 1].min() < 0.99 and np.all(table[2, 1] == 1.0)
    assert table[1, 2].min() < 0.99 and np.all(table[3, 2] == 1.0)
    assert np.all(table[[0, 2], 3] == 0.0)
    assert table[1, 4].min() < 0.99
    np.testing.assert_array_equal(table[3, 4], table[1, 4])
    ones = np.delete(table, [1, 2, 3, 4], axis=1)
    assert np.all(ones == 1.0)


def test_faults_on_one_tooth_multiply():
    ps = _stiffness(SEED, _path(SEED))
    crack, chip = RootCrack("pinion", 1, 5.0), ChippedTip("pinion", 1, 2.0, width=0.4)
    both = fault_factors(SEED, ps, [crack, chip])[0, 1]
    np.testing.assert_array_equal(both, fault_factors(SEED, ps, [crack])[0, 1]
                                  * fault_factors(SEED, ps, [chip])[0, 1])


@pytest.mark.parametrize("pair", [SEED, SHIFTED])
@pytest.mark.parametrize("x_lo", [0.0, -0.3, -4.0, -17.0, -25.0])
def test_tooth_zero_is_at_the_pitch_point_at_t_zero(pair, x_lo):
    """The kernel's slot formula (core/flank.py: r = σ s1 − phase, n = floor(r/p_b),
    x1_j = x_lo + (r − n p_b) + j p_b, drive tooth (k + n − j) mod z, coast (k − n + j) mod z)
    with tooth_index_offsets: at s1 = 0 the drive slot at x_C holds pinion and gear tooth 0;
    one base pitch later, tooth 1; at s1 = 2 r_b1 ψ1(r_w1) the coast slot at x_C holds pinion
    tooth 0 and gear tooth 1. The tables' start x_lo varies (it depends on the load)."""
    from gearcli.model.gap import coast_phase_mm

    p_b, z1, z2 = pair.p_b_mm, pair.pinion.teeth, pair.gear.teeth
    x_c = pair.C_mm - pair.A_mm
    slots = {"s1_0": (-(x_c - x_lo)) % p_b, "s1c_0": (-coast_phase_mm(pair) - (x_c - x_lo)) % p_b}
    k = tooth_index_offsets(pair, x_lo, slots)

    def teeth_at_c(s1, sign, phase, k1, k2):
        r = sign * s1 - phase
        n = math.floor(r / p_b)
        j = round((x_c - x_lo - (r - n * p_b)) / p_b)
        assert abs(x_lo + (r - n * p_b) + j * p_b - x_c) < 1e-9 and j >= 0
        step = n - j if sign > 0 else j - n
        return (int(k1) + step) % z1, (int(k2) + step) % z2

    drive = (1.0, slots["s1_0"], k["tooth_k1"], k["tooth_k2"])
    assert teeth_at_c(0.0, *drive) == (0, 0)
    assert teeth_at_c(p_b, *drive) == (1, 1)
    assert teeth_at_c(-3 * p_b, *drive) == (z1 - 3, z2 - 3)
    s_coast = 2 * pair.pinion.r_b_mm * float(profile.flank_half_angle(pair.pinion,
                                                                      pair.pinion.r_w_mm))
    coast = (-1.0, slots["s1c_0"], k["tooth_k1_coast"], k["tooth_k2_coast"])
    assert teeth_at_c(s_coast, *coast) == (0, 1)
    assert teeth_at_c(s_coast + p_b, *coast) == (1, 2)


def test_contact_heights_on_the_path_are_above_the_crack_start():
    """The crack model's premise on the seed pair: every contact on the path loads both teeth
    above their 30° critical section (else a crack would not weaken them there)."""
    c = pair_contact(SEED, _path(SEED))
    assert c.y_point1_mm.min() > root_section(SEED.pinion).y_F_mm
    assert c.y_point2_mm.min() > root_section(SEED.gear).y_F_mm
