"""ISO 6336-1 Method B mesh stiffness ('derived'), computed independently here."""

import math

import pytest

from gearcli.case.load import load_case
from gearcli.errors import CaseError
from gearcli.model.stiffness import iso6336_stiffness
from tests.conftest import SEED


def _iso_by_hand(z1, z2, x1, x2, alpha_deg, hfp, b, eps, ft, e_mpa=206000.0):
    # ISO 6336-1:2019 §9.3, Method B, written out term by term (C9 multiplies x2^2); c' of
    # the teeth scaled by E/E_st, and the low-load factor kept apart (rating only).
    q = (0.04723 + 0.15551 / z1 + 0.25791 / z2 - 0.00635 * x1 - 0.11654 * x1 / z1
         - 0.00193 * x2 - 0.24188 * x2 / z2 + 0.00529 * x1 * x1 + 0.00182 * x2 * x2)
    c_b = (1 + 0.5 * (1.2 - hfp)) * (1 - 0.02 * (20 - alpha_deg))
    load = min(ft / b / 100.0, 1.0) ** 0.25
    c = 0.8 * 1.0 * c_b / q * e_mpa / 206000.0
    return c, c * (0.75 * eps + 0.25), c * load


@pytest.mark.parametrize("z1, z2, x1, x2, alpha, hfp, ft", [
    (17, 25, 0.0, 0.0, 20.0, 1.25, 3600.0),   # the seed pair, 36 N/mm: low-load factor
    (21, 43, 0.35, -0.2, 20.0, 1.25, 20000.0),  # shifted pair, 200 N/mm: full stiffness
    (30, 30, 0.5, 0.5, 25.0, 1.4, 15000.0),   # 25 deg rack, deep dedendum
])
def test_iso6336_method_b(z1, z2, x1, x2, alpha, hfp, ft):
    eps = 1.6
    iso = iso6336_stiffness(z1, z2, x1, x2, alpha, hfp, 100.0, eps, ft)
    c, c_ga, c_rating = _iso_by_hand(z1, z2, x1, x2, alpha, hfp, 100.0, eps, ft)
    assert iso.c_prime == pytest.approx(c, rel=1e-12)
    assert iso.c_gamma_alpha == pytest.approx(c_ga, rel=1e-12)
    assert iso.c_prime_rating == pytest.approx(c_rating, rel=1e-12)
    assert iso.pair_stiffness_N_mm == pytest.approx(c * 100.0 * 1000.0, rel=1e-12)
    assert iso.mesh_stiffness_N_mm == pytest.approx(c_ga * 100.0 * 1000.0, rel=1e-12)


def test_iso_stiffness_scales_with_youngs_modulus():
    """ISO 6336-1 §9.3: c' of other materials is c'_steel E/E_st (E_st = 206 000 N/mm²):
    an aluminium pair (E = 70 000) is 0.34 times as stiff as a steel one."""
    steel = iso6336_stiffness(17, 25, 0, 0, 20.0, 1.25, 100.0, 1.56, 1e5)
    alu = iso6336_stiffness(17, 25, 0, 0, 20.0, 1.25, 100.0, 1.56, 1e5, 70000.0)
    assert alu.c_prime / steel.c_prime == pytest.approx(70000.0 / 206000.0, rel=1e-12)
    c, _, _ = _iso_by_hand(17, 25, 0, 0, 20.0, 1.25, 100.0, 1.56, 1e5, 70000.0)
    assert alu.c_prime == pytest.approx(c, rel=1e-12)


def test_seed_values_in_the_textbook_range():
    # A standard solid steel pair: c'_th ~ 15 N/(mm um); with C_M = 0.8 and C_B = 0.975
    # c' ~ 11.7 before the low-load factor (DIN 3990 / ISO 6336 quote c' ~ 14, c_gamma ~ 20 for
    # C_B = 1 and full load; the order of magnitude is the check here).
    iso = iso6336_stiffness(17, 25, 0, 0, 20.0, 1.25, 100.0, 1.5632, 1e5)
    assert iso.c_th == pytest.approx(1 / (0.04723 + 0.15551 / 17 + 0.25791 / 25))
    assert 11.0 < iso.c_prime < 12.5 and 16.0 < iso.c_gamma_alpha < 18.5


def test_derived_stiffness_is_linear(write_case, seed_text):
    text = seed_text.replace("  stiffness: 1.0e5 ", "  stiffness: derived ", 1)
    with pytest.raises(CaseError, match="contact.exponent.*linear"):
        load_case(write_case(text))
    ok = text.replace("  exponent: 1.5\n", "", 1)
    assert load_case(write_case(ok, "ok.yaml")).case.contact.exponent == 1.0


def test_derived_stiffness_raises_mesh_frequency_with_face_width():
    from gearcli.pipeline.simulate import run_simulation

    args = ["contact.stiffness=derived", "contact.exponent=1", "run.end_time=0.3",
            "drive.speed=STEP(time, 0, 0, 0.1, 3000)", "load.torque=STEP(time, 0, 0, 0.1, 4.5e5)"]
    narrow = run_simulation(SEED, args)
    wide = run_simulation(SEED, [*args, "gears.face_width=150"])
    # heavier gear (inertia ~ b) but stiffer mesh (~ b, at full load): f_n changes little; the
    # low-load factor (F_t/b)^0.25 makes the wider, less loaded mesh relatively softer
    assert wide.summary.mesh_stiffness_N_mm > narrow.summary.mesh_stiffness_N_mm
    assert math.isfinite(wide.summary.mesh_natural_frequency_Hz)


def test_derived_contact_stiffness_means_c_gamma_alpha_and_follows_e():
    """'derived': a constant pair stiffness k with ε_α k = c_γα b (the ISO mean mesh
    stiffness), from c' without the low-load factor, scaled with E (issue 14)."""
    from gearcli.pipeline.geometry import run_geometry
    from gearcli.pipeline.mesh_input import contact_stiffness, iso_stiffness

    ks = {}
    for e in ("2.07e5", "7e4"):
        loaded = load_case(SEED, ["contact.stiffness=derived", "contact.exponent=1",
                                  f"material.youngs_modulus={e}"])
        geo = run_geometry(loaded)
        iso = iso_stiffness(loaded.case, geo)
        ks[e] = contact_stiffness(loaded.case, geo)
        assert geo.geometry.eps_alpha * ks[e] == pytest.approx(iso.mesh_stiffness_N_mm, rel=1e-12)
        assert iso.load_factor < 1.0  # the seed's 38 N/mm line load: rating only
        assert iso.pair_stiffness_N_mm == pytest.approx(
            iso.c_prime * 1e3 * geo.geometry.pinion.face_width_mm, rel=1e-12)
    assert ks["7e4"] / ks["2.07e5"] == pytest.approx(7e4 / 2.07e5, rel=1e-12)
