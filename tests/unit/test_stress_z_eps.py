"""The ISO static σ_H of `gearcli stress` (model.rating.static_rating) has the contact ratio
factor Z_ε (issue 28): σ_H0 = Z_H Z_E Z_ε √(F_t (u+1)/(d1 b u)) (ISO 6336-2:2019 eq. 4, spur:
Z_β = 1), σ_H = Z_B σ_H0 (pinion), Z_D σ_H0 (gear) with every K factor 1 (eq. 2, 3).

Hand value for cases/iso_pair.yaml: z 21/43, m 5 mm, α 20°, b 50 mm, x 0.35/−0.2 (zero
backlash: inv α_w = inv α + 2 tan α (x1 + x2)/(z1 + z2)), steel E 206 GPa, ν 0.3, 300 N·m on
the gear (F_t = T/r2 on the reference circle). Only ε_α and M1/M2 come from the code (the
geometry, tested in tests/unit/test_geometry*.py and test_rating.py)."""

import math

import pytest

from gearcli.case.load import load_case
from gearcli.model.rating import single_pair_contact_factors, static_rating
from gearcli.pipeline.geometry import run_geometry
from tests.conftest import ROOT

ALPHA = math.radians(20.0)
Z1, Z2, M, B, X1, X2 = 21, 43, 5.0, 50.0, 0.35, -0.2
E, NU, T_NMM = 206000.0, 0.3, 300e3


def _inv(a: float) -> float:
    return math.tan(a) - a


def _alpha_w() -> float:
    target = _inv(ALPHA) + 2 * math.tan(ALPHA) * (X1 + X2) / (Z1 + Z2)
    lo, hi = 0.0, 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _inv(mid) < target else (lo, mid)
    return 0.5 * (lo + hi)


@pytest.fixture(scope="module")
def iso_pair():
    geo = run_geometry(load_case(ROOT / "cases" / "iso_pair.yaml")).geometry
    r_b2 = 0.5 * Z2 * M * math.cos(ALPHA)
    return geo, static_rating(geo, T_NMM / r_b2, (E, E), (NU, NU))


def test_iso_static_contact_stress_has_z_eps(iso_pair):
    geo, st = iso_pair
    a_w = _alpha_w()
    assert geo.alpha_w_rad == pytest.approx(a_w, rel=1e-9)
    d1, u = Z1 * M, Z2 / Z1
    f_t = T_NMM / (0.5 * Z2 * M)  # 2790.7 N
    z_h = math.sqrt(2 * math.cos(a_w) / (math.cos(ALPHA) ** 2 * math.sin(a_w)))
    z_e = math.sqrt(E / (2 * math.pi * (1 - NU**2)))  # √(1/(π 2(1−ν²)/E)) [√(N/mm²)]
    z_eps = math.sqrt((4 - geo.eps_alpha) / 3)
    hand = z_h * z_e * z_eps * math.sqrt(f_t * (u + 1) / (d1 * B * u))
    assert 0.85 < z_eps < 0.95  # ε_α ≈ 1.5: the factor is not 1, the test can fail
    assert st.force_tangential_N == pytest.approx(f_t, rel=1e-12)
    assert st.sigma_H0_iso_MPa == pytest.approx(hand, rel=1e-12)
    assert st.sigma_H0_MPa == pytest.approx(hand / z_eps, rel=1e-12)  # Hertz at C, kept
    m1, m2, z_b, z_d = single_pair_contact_factors(geo)
    assert st.pinion.sigma_H_iso_MPa == pytest.approx(z_b * hand, rel=1e-12)
    assert st.gear.sigma_H_iso_MPa == pytest.approx(z_d * hand, rel=1e-12)
    # the Hertz values at B and D stay without Z_ε (the exact single-pair stresses)
    assert st.pinion.sigma_H_single_MPa == pytest.approx(m1 * hand / z_eps, rel=1e-12)
    assert st.gear.sigma_H_single_MPa == pytest.approx(m2 * hand / z_eps, rel=1e-12)
