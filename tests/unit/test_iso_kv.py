"""ISO 6336-1 Method B K_v (gearcli/model/iso_kv.py): coefficients, ranges, continuity, N_S,
the reduced mass by the standard's formula against the polar moments of the same discs, and
the resonance speed of the seed pair worked in docs/theory.md §10.4.

Published worked example: KISSsoft's ISO 6336 Method B printouts of the NREL 5 MW reference
gearbox (two spur meshes and one helical pair with ε_γ > 2), at the end of this file; they are all
in the sub-critical range, so the main-resonance and super-critical formulas are checked by the
coefficient table (cross-checked in three public implementations, module docstring), the range
limits and continuity only."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearcli.model.iso_kv import (
    coefficients,
    dynamic_factor,
    main_resonance_start,
    reduced_mass_kg_mm,
    resonance_speed_rpm,
)

KW = {"eps_gamma": 1.6, "c_prime_N_mm_um": 14.0, "line_load_N_mm": 300.0,
      "f_pb_eff_um": 8.0, "f_f_eff_um": 6.0, "tip_relief_um": 10.0}


def test_coefficients_for_spur_and_high_contact_ratios():
    assert coefficients(1.4) == (0.32, 0.34, 0.23, 0.90, 0.47, 0.47, 0.75)
    c = coefficients(1.8)
    assert c.cv7 == pytest.approx(0.125 * math.sin(math.pi * (1.8 - 2.0)) + 0.875)
    c = coefficients(2.2)
    assert (c.cv2, c.cv3, c.cv4, c.cv6) == pytest.approx(
        (0.57 / 1.9, 0.096 / 0.64, (0.57 - 0.11) / 0.76, 0.12 / 0.46))
    assert coefficients(3.0).cv7 == 1.0
    with pytest.raises(ValueError):
        coefficients(1.0)


def test_ranges_values_and_continuity():
    b_p, b_f, b_k = 14 * 8 / 300, 14 * 6 / 300, abs(1 - 14 * 10 / 300)
    n = np.array([0.0, 0.5, 1.0, 1.15, 1.3, 1.5, 2.0])
    kv = dynamic_factor(n, **KW)
    assert kv.n_s == 0.85  # line load >= 100 N/mm
    assert list(kv.range_name) == ["sub-critical", "sub-critical", "main resonance",
                                   "main resonance", "intermediate", "super-critical",
                                   "super-critical"]
    assert kv.k_v[0] == pytest.approx(1.0)  # K_v -> 1 as N -> 0
    assert kv.k_v[1] == pytest.approx(0.5 * (0.32 * b_p + 0.34 * b_f + 0.23 * b_k) + 1)
    main = 0.32 * b_p + 0.34 * b_f + 0.90 * b_k + 1
    sup = 0.47 * b_p + 0.47 * b_f + coefficients(1.6).cv7  # 0.756 for eps_gamma 1.6
    assert kv.k_v[2] == pytest.approx(main) and kv.k_v[5] == pytest.approx(sup)
    # the intermediate range joins the main resonance value at 1.15 and the super-critical
    # value at 1.5 (linear interpolation, eq. 22)
    edge = dynamic_factor(np.array([1.15 + 1e-9, 1.5 - 1e-9]), **KW).k_v
    assert edge == pytest.approx([main, sup], rel=1e-6)
    assert kv.k_v[4] == pytest.approx(sup + (main - sup) * (1.5 - 1.3) / 0.35)


def test_main_resonance_start_on_both_sides_of_100_N_per_mm():
    assert main_resonance_start(50.0) == pytest.approx(0.5 + 0.35 * math.sqrt(0.5))
    assert main_resonance_start(99.999) == pytest.approx(0.85, abs=1e-5)
    assert main_resonance_start(150.0) == 0.85
    assert dynamic_factor(0.8, **{**KW, "line_load_N_mm": 50.0}).range_name == "main resonance"


def test_reduced_mass_is_that_of_the_two_discs_on_the_line_of_action():
    """Eq. 30 is m1* m2*/(m1* + m2*) with m* = J*/r_b², J* = π ρ d_m⁴/32 a solid disc of
    diameter d_m per unit width and d_m2 = u d_m1, d_b2 = u d_b1: a second, independent form."""
    d_m1, d_b1, rho, u = 106.0, 98.67, 7.85e-6, 43 / 21
    m1 = math.pi * rho * d_m1**4 / 32 / (d_b1 / 2) ** 2
    m2 = math.pi * rho * (u * d_m1) ** 4 / 32 / (u * d_b1 / 2) ** 2
    assert reduced_mass_kg_mm(d_m1, d_b1, rho, rho, u) == pytest.approx(m1 * m2 / (m1 + m2))
    # a bore removes the inner disc: (1 - q^4) of the polar moment
    q = 0.4
    m1b = m1 * (1 - q**4)
    assert reduced_mass_kg_mm(d_m1, d_b1, rho, rho, u, q1=q) == pytest.approx(
        m1b * m2 / (m1b + m2))


def test_resonance_speed_of_the_seed_pair():
    """docs/theory.md §10.4: c_γα = 12.89 N/(mm·µm), m_red = 0.0690 kg/mm, z1 = 17:
    n_E1 = 30 000/(π 17) √(12.89/0.0690) = 7677 min⁻¹."""
    assert resonance_speed_rpm(17, 12.89, 0.0690) == pytest.approx(7677, rel=5e-4)


def test_gearcli_mesh_reports_the_resonance_speed_and_ratio():
    import json

    from typer.testing import CliRunner

    from gearcli.cli import app
    from tests.conftest import ROOT

    res = CliRunner().invoke(app, ["mesh", str(ROOT / "cases" / "iso_pair.yaml"), "--json"])
    assert res.exit_code == 0, res.output
    iso = json.loads(res.output)["iso6336_method_b"]
    assert iso["pinion_speed_rpm"] == pytest.approx(1340.0)  # the case's (1500 before issue 31)
    assert iso["resonance_ratio"] == pytest.approx(1340.0 / iso["resonance_speed_rpm"])
    assert iso["resonance_speed_rpm"] == pytest.approx(resonance_speed_rpm(
        21, iso["c_gamma_alpha_N_mm_um"], iso["reduced_mass_kg_mm"]))
    assert iso["speed_range"] == "sub-critical" and iso["k_v"] > 1.0


# --- a published worked example: KISSsoft (Release 03/2017) ISO 6336:2006 Method B printouts of
# the NREL 5 MW reference gearbox, public in github.com/gfsReboucas/Drivetrain, files
# @NREL_5MW/stage_02.rtf (spur planetary stage) and stage_03.rtf (helical parallel stage).
# Quoted inputs (N/mm, µm, 1/min, kg/mm) and printed results; the reduced masses are the
# printout's (its sun-planet value follows the standard's planetary rule, not eq. 30).
KISSSOFT = [
    # name, z1, c′, c_γα, m_red, ε_γ, K_A·F_t/b, f_pb (larger), y_p, f_fα (larger), y_f, C_a,
    # printed n_E1, printed N, printed K_V, decimals printed
    ("stage 2 sun-planet (spur)", 18, 12.240, 15.640, 0.1534, 1.370, 1.25 * 519.82,
     17.90, 1.342, 23.00, 1.725, 2.0, 5357, 0.046, 1.02, 2),
    ("stage 2 planet-ring (spur)", 36, 14.053, 20.563, 1.4684, 1.618, 1.25 * 519.82,
     20.70, 3.142, 27.00, 4.098, 2.0, 993, 0.124, 1.06, 2),
    ("stage 3 pair (helical, ε_γ > 2)", 24, 13.832, 18.632, 0.36503, 2.884, 1.25 * 666.85,
     15.90, 1.2, 22.00, 1.6, 2.0, 2843, 0.410, 1.092, 3),
]


@pytest.mark.parametrize("row", KISSSOFT, ids=[r[0] for r in KISSSOFT])
def test_kissoft_printouts_of_the_nrel_5mw_gearbox(row):
    (_, z1, c_p, c_ga, m_red, eps_g, w, f_pb, y_p, f_fa, y_f, c_a,
     n_e1_printed, n_printed, kv_printed, decimals) = row
    # n_E1 = 30000/(π z1) sqrt(c_γα/m_red) (ISO 6336-1 eq. 6): the printed integer; the inputs'
    # printed digits (m_red to 4-5 significant digits) allow ±1 1/min
    assert resonance_speed_rpm(z1, c_ga, m_red) == pytest.approx(n_e1_printed, abs=1.0)
    kv = dynamic_factor(n_printed, eps_gamma=eps_g, c_prime_N_mm_um=c_p, line_load_N_mm=w,
                        f_pb_eff_um=f_pb - y_p, f_f_eff_um=f_fa - y_f, tip_relief_um=c_a)
    assert str(kv.range_name) == "sub-critical"
    # K_V as printed, to its printed decimals (half a unit of the last digit) plus the effect of
    # N printed to 3 decimals (±0.0005 · K ≤ 0.0003 here)
    assert float(kv.k_v) == pytest.approx(kv_printed, abs=0.5 * 10.0 ** -decimals + 3e-4)


def test_the_case_deviations_enter_b_p_and_b_k():
    """B_p from the larger base pitch deviation f_pt cos α (an ISO 1328-1:2013 grade's f_pT,
    or the largest given |f_pt,i| after removing their mean), B_k from the C_a giving the
    larger B_k (designed relief, else the running-in C_ay from σ_Hlim, else 0), c′ with the
    low-load factor; no deviations: B_p = B_f = 0, B_k = 1 (pipeline/mesh_input)."""
    from gearcli.case.load import load_case
    from gearcli.model.errors import iso1328_single_pitch_tolerance_um
    from gearcli.pipeline.geometry import run_geometry
    from gearcli.pipeline.mesh_input import iso_dynamic

    def iso(*overrides):
        loaded = load_case("cases/seed.yaml", list(overrides))
        return iso_dynamic(loaded.case, run_geometry(loaded))

    plain = iso()
    assert (plain.B_p, plain.B_f, plain.B_k) == (0.0, 0.0, 1.0)
    assert plain.tip_relief_um == 0.0
    # seed: F_t/b = 3600 N / 100 mm = 36 N/mm < 100: c′ (rating) = c′ (36/100)^0.25
    assert plain.line_load_N_mm == pytest.approx(36.0, rel=1e-9)
    assert plain.low_load_factor == pytest.approx(0.36 ** 0.25, rel=1e-12)
    graded = iso("errors.pitch_deviation.gear={iso1328_grade: 7}",
                 "errors.pitch_deviation.pinion={values: [0.005, -0.008, 0.006"
                 + ", 0.0" * 14 + "]}",
                 "modifications.tip_relief.pinion={amount: 0.005, length: 5}",
                 "modifications.tip_relief.gear={amount: 0.02, length: 5}")
    # gear: f_pT = (0.001 d + 0.4 m + 5) √2^(7-5), d = 250 mm, m = 10 mm -> 19.5 µm; the
    # pinion's values have mean 0.003/17 mm: largest |f_pt - mean| = 8.18 µm < 19.5 µm
    f_pt = (0.001 * 250.0 + 0.4 * 10.0 + 5.0) * 2.0
    assert iso1328_single_pitch_tolerance_um(7, 250.0, 10.0) == pytest.approx(f_pt)
    assert graded.f_pb_eff_um == pytest.approx(f_pt * math.cos(math.radians(20.0)))
    c, w = graded.c_prime_N_mm_um, graded.line_load_N_mm
    assert graded.B_p == pytest.approx(c * graded.f_pb_eff_um / w)
    assert graded.B_k == pytest.approx(max(abs(1 - c * 5.0 / w), abs(1 - c * 20.0 / w)))
    assert plain.c_prime_N_mm_um == pytest.approx(c)  # the deviations leave c′ alone
    only_pinion = iso("errors.pitch_deviation.pinion={values: [0.005, -0.008, 0.006"
                      + ", 0.0" * 14 + "]}",
                      "modifications.tip_relief.pinion={amount: 0.003, length: 5}")
    mean = (0.005 - 0.008 + 0.006) / 17
    assert only_pinion.f_pb_eff_um == pytest.approx(
        1e3 * (0.008 + mean) * math.cos(math.radians(20.0)))
    # the unrelieved gear competes with B_k = 1 (C_a = 0): the larger B_k wins
    assert only_pinion.B_k == pytest.approx(max(1.0, abs(1 - c * 3.0 / w)))


def test_running_in_amount_of_the_kissoft_printout():
    """C_ay = (σ_Hlim/97 − 18.45)²/18 + 1.5 µm: at σ_Hlim = 1500 MPa (case-hardened steel)
    1.995 µm, the C_a = 2.00 µm the NREL stage 2 printout uses with no modification recorded
    ("running-in only"); a case with σ_Hlim and no tip relief takes it for B_k."""
    from gearcli.case.load import load_case
    from gearcli.pipeline.geometry import run_geometry
    from gearcli.pipeline.mesh_input import iso_dynamic, running_in_tip_relief_um

    assert running_in_tip_relief_um(1500.0) == pytest.approx(1.995, abs=5e-4)
    loaded = load_case("cases/seed.yaml", ["material.contact_fatigue_limit=1500 MPa"])
    d = iso_dynamic(loaded.case, run_geometry(loaded))
    assert d.tip_relief_um == pytest.approx(running_in_tip_relief_um(1500.0))
    assert d.tip_relief_source == "running-in amount C_ay"
