"""ISO 6336 rating (gearcli/model/iso6336) against hand calculations written here from the
standard's formulas (not by calling the function under test), and its responses: load factors
(K_Hβ Method C in both branches, K_Hα/K_Fα Method B and its limits), life factors at and between
the knees (ISO 6336-6's inverted S-N lines), influence factors between the knees, ISO 6336-5
material lines, inspection dimensions by an independent construction, S_H ∝ 1/√T, harder
material → higher S_H, one-bin duty cycle = the single rating, Miner sums."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from gearcli.model.iso6336 import bending as b3
from gearcli.model.iso6336.common import Edition, involute
from gearcli.model.iso6336.factors import (
    face_load_factor_method_c,
    running_in_helix,
    transverse_load_factors,
)
from gearcli.model.iso6336.inspection import (
    BALL_SERIES_MM,
    dimension_over_balls,
    inspection_input_error,
    span,
    span_teeth,
    standard_ball_diameter,
    theoretical_ball_diameter,
)
from gearcli.model.iso6336.life import (
    LONG_LIFE_CYCLES,
    bending_life_curve,
    cycles_at_strength,
    influence_at,
    load_cycles,
    miner_damage,
    pitting_life_curve,
)
from gearcli.model.iso6336.material import MaterialKind, Quality, allowable_stress, sigma_limits
from gearcli.model.iso6336.rate import rate
from gearcli.model.iso6336.spectrum import LoadBin, duty_cycle_damage
from tests.unit.test_iso6336_anchor import make_input

EH = MaterialKind.CASE_HARDENED


# --- ISO 6336-1 load factors ------------------------------------------------------------------
def test_face_load_factor_method_c_linear_branch():
    """F_m/b = 500 N/mm, c_γβ = 17, f_sh = 10, f_ma = 8 µm, Eh: F_βx = 1.33·10 + 8 = 21.3,
    y_β = 0.15·21.3 = 3.195 (< 6), F_βy = 18.105, K_Hβ = 1 + 17·18.105/(2·500) = 1.307785."""
    k, fbx, fby = face_load_factor_method_c(500.0, 17.0, 10.0, 8.0, kinds=(EH, EH),
                                            sigma_h_lim_MPa=(1500.0, 1500.0), v_m_s=4.0)
    assert (fbx, fby) == pytest.approx((21.3, 18.105), rel=1e-12)
    assert k == pytest.approx(1.307785, rel=1e-12)


def test_face_load_factor_method_c_root_branch_and_minimum():
    """F_m/b = 100: 1 + 17·18.105/200 = 2.539 > 2, so K_Hβ = √(2·17·18.105/100) = 2.48111;
    no misalignment: F_βx = F_βx,min = 0.005 F_m/b."""
    k, _, _ = face_load_factor_method_c(100.0, 17.0, 10.0, 8.0, y_beta_um=3.195)
    assert k == pytest.approx(math.sqrt(2.0 * 17.0 * 18.105 / 100.0), rel=1e-12)
    _, fbx, _ = face_load_factor_method_c(1000.0, 17.0, 0.0, 0.0, y_beta_um=0.0)
    assert fbx == pytest.approx(5.0)


def test_running_in_helix_by_material_and_speed():
    """St/V: 320/σ_Hlim F_βx, capped at 25600/σ_Hlim (5 < v ≤ 10 m/s) and 12800/σ_Hlim (v > 10);
    Eh: 0.15 F_βx ≤ 6 µm; GG: 0.55 F_βx ≤ 45 / 22 µm."""
    v_kind = MaterialKind.THROUGH_HARDENED_ALLOY
    assert running_in_helix(v_kind, 800.0, 100.0, 4.0) == pytest.approx(40.0)
    assert running_in_helix(v_kind, 800.0, 100.0, 8.0) == pytest.approx(32.0)
    assert running_in_helix(v_kind, 800.0, 100.0, 12.0) == pytest.approx(16.0)
    assert running_in_helix(EH, 1500.0, 100.0, 4.0) == 6.0
    assert running_in_helix(MaterialKind.GREY_IRON, 400.0, 100.0, 8.0) == 45.0
    assert running_in_helix(MaterialKind.GREY_IRON, 400.0, 100.0, 12.0) == 22.0


def test_transverse_load_factors_and_their_limits():
    """ε = 1.6, c_γα = 20, f_pb − y_α = 28 µm, F_tH/b = 200: K = 0.8 (0.9 + 0.4·20·28/200) = 1.616;
    K_Hα ≤ 1/Z_ε² = 1.25 (Z_ε² = 0.8), K_Fα ≤ 1/(0.25 + 0.75/1.6) = 1.391304; at a high load
    both are 1."""
    z_eps = math.sqrt((4.0 - 1.6) / 3.0)
    k_h, k_f = transverse_load_factors(1.6, 20.0, 30.0, 2.0, 200.0, z_eps)
    assert k_h == pytest.approx(1.25, rel=1e-12)
    assert k_f == pytest.approx(1.0 / 0.71875, rel=1e-12)
    k_h, k_f = transverse_load_factors(1.6, 20.0, 12.0, 2.0, 1000.0, z_eps)
    unclamped = 0.8 * (0.9 + 0.4 * 20.0 * 10.0 / 1000.0)  # 0.784 < 1
    assert unclamped < 1.0 and (k_h, k_f) == (1.0, 1.0)


# --- life factors -----------------------------------------------------------------------------
def test_pitting_life_factor_at_and_between_the_knees():
    """Eh, no pitting permitted (ISO 6336-2 Table 2): 1.6 up to 10⁵, 1.0 at 5·10⁷, 0.85 at 10¹⁰,
    flat outside. Between, ISO 6336-6 (Cor.1:2007, Annex C) writes the lines inverted:
    N = (Z_NT/1.6)^(−13.222469)·10⁵ for Z_NT > 1 and N = Z_NT^(−32.60122926)·5·10⁷ below."""
    z = pitting_life_curve(EH)
    assert (z(1e3), z(1e5), z(5e7), z(1e10), z(1e12)) == pytest.approx((1.6, 1.6, 1.0, 0.85, 0.85))
    for znt in (1.5, 1.3, 1.1):
        assert z((znt / 1.6) ** -13.222469 * 1e5) == pytest.approx(znt, rel=1e-7)
    for znt in (0.98, 0.9, 0.86):
        assert z(znt ** -32.60122926 * 5e7) == pytest.approx(znt, rel=1e-7)
    opt = pitting_life_curve(EH, optimum=True)
    assert opt(1e9) == 1.0 and opt(1e3) == 1.6
    permitted = pitting_life_curve(EH, pitting_permitted=True)
    assert (permitted(6e5), permitted(1e7), permitted(1e9)) == pytest.approx((1.6, 1.3, 1.0))
    assert permitted(math.sqrt(6e5 * 1e7)) == pytest.approx(math.sqrt(1.6 * 1.3))
    nitrided = pitting_life_curve(MaterialKind.NITRIDED)
    assert (nitrided(1e5), nitrided(2e6)) == (1.3, 1.0)


def test_bending_life_factor_at_and_between_the_knees():
    """Eh (ISO 6336-3 Table 3): 2.5 up to 10³, 1.0 at 3·10⁶, 0.85 at 10¹⁰; ISO 6336-6 inverted:
    N = (Y_NT/2.5)^(−8.73724908)·10³ (Y_NT ≥ 1), N = Y_NT^(−49.91250338)·3·10⁶ (Y_NT < 1).
    The first exponent is 6.6e-5 below the knees' ln(3000)/ln 2.5 = 8.73781 (the other three
    ISO 6336-6 exponents agree with their knees to 1e-9), which moves ln Y_NT by that fraction
    of ln(Y_NT/2.5): the tolerance. Through-hardened: the static knee at 10⁴."""
    y = bending_life_curve(EH)
    assert (y(1e3), y(3e6), y(1e10)) == pytest.approx((2.5, 1.0, 0.85))
    for ynt in (2.0, 1.5, 1.1):
        slip = abs(8.73724908 / (math.log(3000.0) / math.log(2.5)) - 1.0)  # 6.6e-5
        tol = 1.01 * slip * abs(math.log(ynt / 2.5))
        assert y((ynt / 2.5) ** -8.73724908 * 1e3) == pytest.approx(ynt, rel=tol)
    for ynt in (0.95, 0.9):
        assert y(ynt ** -49.91250338 * 3e6) == pytest.approx(ynt, rel=1e-7)
    v = bending_life_curve(MaterialKind.THROUGH_HARDENED_CARBON)
    assert (v(1e4), v(5e3)) == (2.5, 2.5) and v(1e5) == pytest.approx(
        2.5 * (1.0 / 2.5) ** (math.log(10.0) / math.log(300.0)))


def test_influence_factors_between_the_knees_and_load_cycles():
    """Z_L = 1.02 from the endurance knee on, 1 at the static knee, and √1.02 at the geometric
    mean of the knees (log-log line); N_L = 60 n L_h q."""
    z = pitting_life_curve(EH)
    assert influence_at(1e4, z, 1.0, 1.02) == 1.0
    assert influence_at(1e9, z, 1.0, 1.02) == 1.02
    assert influence_at(math.sqrt(1e5 * 5e7), z, 1.0, 1.02) == pytest.approx(math.sqrt(1.02))
    assert load_cycles(246.775, 175200.0, 3.0) == pytest.approx(60 * 246.775 * 175200 * 3)


def test_cycles_at_strength_inverts_the_curve_and_miner_sums():
    z = pitting_life_curve(EH)

    def strength(n):
        return 1500.0 * z(n)

    n = cycles_at_strength(strength, 1500.0 * 0.9, 1e5)
    exponent = math.log(1e10 / 5e7) / math.log(1.0 / 0.85)  # the line through the two knees
    assert n == pytest.approx(0.9 ** -exponent * 5e7, rel=1e-9)
    assert cycles_at_strength(strength, 1500.0 * 0.8, 1e5) == math.inf  # below 0.85: none
    assert cycles_at_strength(strength, 1500.0 * 1.7, 1e5) == 0.0  # above static
    assert miner_damage([1e6, 2e6, 5.0], [4e6, 8e6, math.inf]) == pytest.approx(0.5)
    assert miner_damage([1.0], [0.0]) == math.inf
    assert LONG_LIFE_CYCLES == 1e10


# --- ISO 6336-5 material lines ------------------------------------------------------------------
def test_material_lines():
    """σ_lim = A x + B: Eh MQ 1500/425 (A = 0); through-hardened alloy MQ at HV 300:
    1.313·300 + 373 = 766.9 and 0.425·300 + 187 = 314.5; outside the range the hardness is
    clamped and flagged."""
    assert sigma_limits(EH, Quality.MQ, 700.0) == (1500.0, 425.0)
    assert sigma_limits(EH, Quality.ME, 700.0) == (1650.0, 525.0)
    v = MaterialKind.THROUGH_HARDENED_ALLOY
    assert sigma_limits(v, Quality.MQ, 300.0) == pytest.approx((766.9, 314.5))
    out = allowable_stress(v, Quality.MQ, 450.0, "H")
    assert not out.in_range and out.hardness == 360.0
    assert out.value_MPa == pytest.approx(1.313 * 360.0 + 373.0)


# --- inspection: an independent construction ------------------------------------------------
def _flank_distance(z, x, m, alpha, r_centre):
    """Smallest distance from a point on the space centreline at radius r_centre to the flank,
    sampling the involute densely (polar form: half tooth angle ψ(ρ) = s/d + inv α − inv α_ρ)."""
    d = m * z
    rb = 0.5 * d * math.cos(alpha)
    s = m * (0.5 * math.pi + 2.0 * x * math.tan(alpha))
    rho = np.linspace(rb * 1.0000001, 0.5 * d + 2.0 * m, 400001)
    a_rho = np.arccos(rb / rho)
    psi = s / d + involute(alpha) - (np.tan(a_rho) - a_rho)
    phi = math.pi / z - psi  # angle of the flank point from the space centreline
    return float(np.min(np.hypot(rho * np.sin(phi), rho * np.cos(phi) - r_centre)))


@pytest.mark.parametrize(("z", "x", "ball"), [(17, 0.2, 7.0), (24, -0.1, 6.5)])
def test_dimension_over_balls_by_construction(z, x, ball):
    """The ball centre sits on the space centreline where its distance to the flank is D/2
    (sampled involute, Brent root); M = 2 r_K + D (even z), 2 r_K cos(90°/z) + D (odd). The
    involute is sampled every ~0.03 µm: the distance error (quadratic in the spacing) is far
    below the 2e-6 mm tolerance on M."""
    m, alpha = 4.0, math.radians(20.0)
    r_k = brentq(lambda r: _flank_distance(z, x, m, alpha, r) - 0.5 * ball,
                 0.5 * m * z * 0.95, 0.5 * m * z + 2.0 * m, xtol=1e-10)
    expect = 2.0 * r_k * (math.cos(0.5 * math.pi / z) if z % 2 else 1.0) + ball
    assert dimension_over_balls(z, x, m, alpha, ball) == pytest.approx(expect, abs=2e-6)


def test_span_by_the_base_tooth_thickness():
    """W_k = (k − 1) p_b + s_b with the base tooth thickness s_b = d_b (s/d + inv α) (the two
    flanks' tangent planes are base-circle tangents); z = 31, x = 0.25, m = 3, α = 20°:
    the span over k = 4 (the rule's k: 31/π (tan α_M − 2 x tan α/31 − inv α) + 0.5 → 4)."""
    z, x, m, alpha = 31, 0.25, 3.0, math.radians(20.0)
    d = m * z
    d_b = d * math.cos(alpha)
    s = m * (0.5 * math.pi + 2.0 * x * math.tan(alpha))
    alpha_m = math.acos(d_b / (d + 2.0 * x * m))
    k_rule = z / math.pi * (math.tan(alpha_m) - 2 * x * math.tan(alpha) / z - involute(alpha)) + 0.5
    assert span_teeth(z, x, alpha) == round(k_rule) == 4
    expect = 3 * math.pi * m * math.cos(alpha) + d_b * (s / d + involute(alpha))
    assert span(z, x, m, alpha, 4) == pytest.approx(expect, rel=1e-13)
    assert span(z, x, m, alpha, 4, -0.1) == pytest.approx(expect - 0.1 * math.cos(alpha))


def test_theoretical_ball_touches_on_the_shifted_circle():
    """The theoretical ball's contact point lies on d + 2 x m: the ball centre radius r_K from
    M_dK, and the contact on the normal at r_b tan α_K − D/2 from the base tangent point."""
    z, x, m, alpha = 24, 0.3, 5.0, math.radians(20.0)
    d_m = theoretical_ball_diameter(z, x, m, alpha)
    r_b = 0.5 * m * z * math.cos(alpha)
    r_k = 0.5 * (dimension_over_balls(z, x, m, alpha, d_m) - d_m)
    t_contact = math.sqrt(r_k ** 2 - r_b ** 2) - 0.5 * d_m
    assert math.hypot(r_b, t_contact) == pytest.approx(0.5 * m * z + x * m, rel=1e-12)
    assert standard_ball_diameter(d_m) >= d_m
    assert standard_ball_diameter(8.6) == 8.75 and standard_ball_diameter(26.0) == 30.0


def test_the_largest_ball_touches_at_the_tip_by_an_independent_construction():
    """inspection_input_error's tip bound against the contact point built from M_dK (as the
    test above: the ball centre radius from the dimension over balls, the contact on the
    normal from the base tangent point): the ball whose contact is on the tip circle
    (brentq) is the largest allowed, 0.1 % more is refused, and tiny balls fall through."""
    z, x, m, alpha = 24, 0.3, 5.0, math.radians(20.0)
    r_b, d_a = 0.5 * m * z * math.cos(alpha), m * z + 2.0 * m * (1.0 + x)

    def contact_radius(d_m):
        r_k = 0.5 * (dimension_over_balls(z, x, m, alpha, d_m) - d_m)
        return math.hypot(r_b, math.sqrt(r_k ** 2 - r_b ** 2) - 0.5 * d_m)

    d_tip = brentq(lambda d_m: contact_radius(d_m) - 0.5 * d_a, 8.6, 30.0, xtol=1e-12)
    assert inspection_input_error(z, x, m, alpha, d_a, (0.0, 0.0), 0.999 * d_tip) is None
    key, reason = inspection_input_error(z, x, m, alpha, d_a, (0.0, 0.0), 1.001 * d_tip)
    assert key == "ball_diameter" and "above the tip" in reason
    key, reason = inspection_input_error(z, x, m, alpha, d_a, (0.0, 0.0), 1.0)
    assert key == "ball_diameter" and "falls between the flanks" in reason
    key, _ = inspection_input_error(z, x, m, alpha, d_a, (-0.05, -9.0), None)
    assert key == "thickness_allowances"


def test_the_standard_ball_of_fine_pitch_gears_touches_between_base_and_tip():
    """No ball given: the series' size must be one inspection_input_error accepts. With the
    series starting at 1 mm, modules below ~0.4 mm (theoretical D_M ≈ 1.7 m) got a ball whose
    contact lay above the tip (m 0.3, z 24: 1 mm against 0.50 mm)."""
    alpha = math.radians(20.0)
    for m in (0.1, 0.2, 0.3, 0.35, 0.5, 1.0):
        for z in (17, 24, 50, 100, 200):
            for x in (0.0, 0.3):
                d_a = m * z + 2.0 * m * (1.0 + x)
                assert inspection_input_error(z, x, m, alpha, d_a, (0.0, -0.02 * m),
                                              None) is None, (m, z, x)


def test_ball_beyond_the_series_continues_in_its_last_step():
    """A module large enough to need a ball beyond the series (here m 200, D_M ≈ 360 mm)
    still gets a size: the series' last step (5 mm) continued, never an error that would stop
    the whole rating."""
    assert standard_ball_diameter(301.0) == 305.0
    assert standard_ball_diameter(300.0) == 300.0
    assert standard_ball_diameter(412.3) == 415.0
    assert standard_ball_diameter(11.2, series=(10.0, 12.0)) == 12.0
    assert standard_ball_diameter(13.0, series=(10.0, 12.0)) == 14.0
    d_m = theoretical_ball_diameter(23, 0.2, 200.0, math.radians(20.0))
    assert d_m > max(BALL_SERIES_MM)
    ball = standard_ball_diameter(d_m)
    assert d_m <= ball < d_m + 5.0 and ball % 5.0 == 0.0


# --- responses of the rating ------------------------------------------------------------------
def test_safety_against_pitting_scales_with_one_over_root_torque():
    """K factors given (K_Hα at its lower limit 1 in both): σ_H ∝ √F_t, σ_HG unchanged, so
    S_H(2T)/S_H(T) = 1/√2; bending: S_F ∝ 1/T."""
    base = make_input()
    r1 = rate(base)
    r2 = rate(dataclasses.replace(base, pinion_torque_Nm=2.0 * base.pinion_torque_Nm))
    for g1, g2 in ((r1.pinion, r2.pinion), (r1.gear, r2.gear)):
        assert g2.S_H / g1.S_H == pytest.approx(1.0 / math.sqrt(2.0), rel=1e-12)
        assert g2.S_F / g1.S_F == pytest.approx(0.5, rel=1e-12)


def test_harder_material_raises_the_safety_against_pitting():
    """Two through-hardened alloy MQ gears at HV 250 and 300: σ_Hlim = 1.313 HV + 373 (ISO 6336-5),
    below 850 both, so Z_L, Z_v, Z_R keep their coefficients: S_H grows by σ_Hlim(300)/σ_Hlim(250)
    = 766.9/701.25."""
    def make(hv):
        kind = MaterialKind.THROUGH_HARDENED_ALLOY
        g = dict(material=kind, surface_hardness=hv, sigma_h_lim_MPa=None, sigma_f_lim_MPa=None,
                 proof_stress_MPa=700.0)
        base = make_input(face_load_factor=1.2)
        return rate(dataclasses.replace(base, pinion=dataclasses.replace(base.pinion, **g),
                                        gear=dataclasses.replace(base.gear, **g)))
    soft, hard = make(250.0), make(300.0)
    assert hard.pinion.S_H / soft.pinion.S_H == pytest.approx(766.9 / 701.25, rel=1e-12)
    assert hard.pinion.S_H > soft.pinion.S_H and hard.gear.S_H > soft.gear.S_H


def test_one_bin_duty_cycle_equals_the_single_rating():
    inp = make_input()
    r = rate(inp)
    d = duty_cycle_damage(inp, [LoadBin(inp.pinion_torque_Nm, inp.pinion_speed_rpm, 1.0)])
    assert d.pinion.pitting == pytest.approx(r.pinion.damage_pitting, rel=1e-12)
    assert d.pinion.pitting == pytest.approx(175200.0 / r.pinion.life_pitting_h, rel=1e-12)
    assert d.gear.pitting == r.gear.damage_pitting == 0.0
    assert d.pinion.bending == d.gear.bending == 0.0


def test_two_bin_duty_cycle_follows_the_sn_line():
    """Half the life at T, half at 0.97 T, same speed: beyond 5·10⁷ cycles the sun's allowed
    cycles go as Z_NT^(−32.60) ∝ σ_H^(−32.60) ∝ T^(−16.30) (K factors given), so
    D = ½ D(T) (1 + 0.97^16.30). (At 0.9 T the required Z_NT, 0.84, is below the curve's end
    0.85: no damage — the second case.)"""
    inp = make_input()
    d1 = duty_cycle_damage(inp, [LoadBin(inp.pinion_torque_Nm, inp.pinion_speed_rpm, 1.0)])
    d2 = duty_cycle_damage(inp, [LoadBin(inp.pinion_torque_Nm, inp.pinion_speed_rpm, 0.5),
                                 LoadBin(0.97 * inp.pinion_torque_Nm, inp.pinion_speed_rpm, 0.5)])
    slope = 0.5 * math.log(1e10 / 5e7) / math.log(1.0 / 0.85)
    assert d2.pinion.pitting == pytest.approx(0.5 * d1.pinion.pitting * (1.0 + 0.97 ** slope),
                                              rel=1e-9)
    d3 = duty_cycle_damage(inp, [LoadBin(inp.pinion_torque_Nm, inp.pinion_speed_rpm, 0.5),
                                 LoadBin(0.9 * inp.pinion_torque_Nm, inp.pinion_speed_rpm, 0.5)])
    assert d3.pinion.pitting == pytest.approx(0.5 * d1.pinion.pitting, rel=1e-12)
    assert d3.pinion.pitting_per_bin[1] == 0.0
    with pytest.raises(ValueError, match="sum to"):
        duty_cycle_damage(inp, [LoadBin(1.0, 1.0, 0.5)])


def test_document_to_dict_is_plain():
    import json
    doc = rate(make_input()).to_dict()
    text = json.dumps(doc, allow_nan=False)
    assert doc["pinion"]["life_bending_h"] is None  # infinite life
    assert [r["value"] for r in doc["pinion"]["factors"] if r["symbol"] == "L_F"] == [None]
    assert any(row["symbol"] == "Y_F" for row in doc["gear"]["factors"])
    assert "ISO 6336-3:2006" in text and doc["method"] == "ISO 6336 Method B"


def test_rim_deep_tooth_and_helix_factors():
    """Y_B = 1.6 ln(2.242 h/s_R) for 0.5 < s_R/h < 1.2, 1 above; Y_DT = −0.666 ε + 2.366 for
    2.05 < ε ≤ 2.5 at grade ≤ 4; Y_β: 2006 1 − β/120° (ε_β = 1), 2019 divided by cos³β."""
    assert b3.rim_factor(60.0, 45.0) == 1.0 and b3.rim_factor(None, 45.0) == 1.0
    assert b3.rim_factor(36.0, 45.0) == pytest.approx(1.6 * math.log(2.242 * 45.0 / 36.0))
    with pytest.raises(ValueError):
        b3.rim_factor(20.0, 45.0)
    assert b3.deep_tooth_factor(2.2, 4) == pytest.approx(-0.666 * 2.2 + 2.366)
    assert b3.deep_tooth_factor(2.2, 5) == 1.0 and b3.deep_tooth_factor(2.6, 3) == 0.7
    beta = math.radians(15.0)
    assert b3.helix_factor(beta, 1.2, "2006") == pytest.approx(1.0 - 15.0 / 120.0)
    assert b3.helix_factor(beta, 1.2, "2019") == pytest.approx((1.0 - 15.0 / 120.0)
                                                               / math.cos(beta) ** 3)


def test_inputs_are_checked():
    with pytest.raises(ValueError, match="pinion_torque_Nm"):
        make_input(pinion_torque_Nm=0.0)
    with pytest.raises(ValueError, match="'2010'"):
        make_input(edition="2010")
    assert make_input(edition="2019").edition is Edition.ISO2019


def test_mean_stress_factor_for_reversed_bending():
    """Y_M = (1 + M)/((1 − R) + M (1 + R)) (Haigh line through the pulsating test point): fully
    reversed R = −1 with M = 0.4 gives 0.7; R = 0 gives 1; 2006 gives 0.7 for any R < 0."""
    assert b3.mean_stress_factor(False, "2019", sensitivity=0.4, stress_ratio=-1.0) == \
        pytest.approx(0.7)
    r, m = -0.5, 0.3
    assert b3.mean_stress_factor(False, "2019", sensitivity=m, stress_ratio=r) == \
        pytest.approx((1 + m) / ((1 - r) + m * (1 + r)))
    assert b3.mean_stress_factor(True, "2019", stress_ratio=0.0) == 1.0
    assert b3.mean_stress_factor(False, "2006", stress_ratio=-0.3) == 0.7
    assert b3.mean_stress_factor(True, "2019", MaterialKind.NITRIDED) == 0.7
    with pytest.raises(ValueError, match="mean stress sensitivity"):
        b3.mean_stress_factor(False, "2019", MaterialKind.NITRIDED, stress_ratio=-0.5)


def test_method_b_closed_form_equals_the_generated_fillet_section():
    """ISO's closed-form 30° section (bending.form_geometry) and gearcli.model.rating's section
    found on the actual generated fillet (spline of the trochoid, Brent root) describe the same
    curve: for the anchor's sun and planet (same tip diameters, tip shortening included) Y_F,
    Y_S, s_Fn, ρ_F, h_Fe agree to 2e-6 relative (rating's spline and root tolerances,
    tests/unit/test_rating.py ISO_RTOL)."""
    from gearcli.model.geometry import GearSpec, PairSpec, compute_pair_geometry
    from gearcli.model.rating import static_rating
    from tests.unit.test_iso6336_anchor import X1, X2

    k1 = 1.0 + X1 - (432.838 - 378.0) / 42.0  # d_a = d + 2 m (h_aP* + x − k)
    k2 = 1.0 + X2 - (815.663 - 756.0) / 42.0
    geo = compute_pair_geometry(PairSpec(21.0, math.radians(20.0),
                                         GearSpec(18, 550.0, X1, tip_shortening_coef=k1),
                                         GearSpec(36, 550.0, X2, tip_shortening_coef=k2),
                                         centre_distance_mm=584.0))
    st = static_rating(geo, 1000.0, (206000.0, 206000.0), (0.3, 0.3))
    r = rate(make_input())
    for gs, gr in ((st.pinion, r.pinion), (st.gear, r.gear)):
        got = [gr.factor(s).value for s in ("Y_F", "Y_S", "s_Fn", "ρ_F", "h_Fe")]
        ref = [gs.Y_F, gs.Y_S, gs.section.s_Fn_mm, gs.section.rho_F_mm, gs.h_Fe_mm]
        assert got == pytest.approx(ref, rel=2e-6)
