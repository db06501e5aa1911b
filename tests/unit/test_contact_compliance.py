"""Weber's contact flattening as the tooth law's contact term (gearcli/model/contact_compliance.py,
docs/theory.md §4b): the asymptotic Weber formula, the secant/tangent relation to Yang & Sun's
linear Hertz term, and the pair's depths to the tooth centrelines."""

import math

import numpy as np
import pytest

from gearcli.model.contact_compliance import (
    contact_modulus,
    hertz_half_width,
    weber_approach,
    weber_pair_compliance,
)
from gearcli.model.geometry import GearSpec, PairSpec, compute_pair_geometry
from gearcli.model.pair_stiffness import pair_contact, pair_stiffness
from gearcli.model.tooth_stiffness import hertz_compliance, tooth_point

E, NU = 2.07e5, 0.29
A20 = math.radians(20.0)


def test_weber_asymptote_for_deep_points():
    """h ≫ a: δ → 2w(1 − ν²)/(πE) [ln(2h/a) − ν/(2(1 − ν))] (Weber 1949, plane strain); the
    exact half-plane value differs by O((a/h)²): 1e-4 relative at h = 100 a."""
    w, a = 200.0, 0.05
    h = 100 * a
    weber = 2 * w * (1 - NU**2) / (math.pi * E) * (math.log(2 * h / a) - NU / (2 * (1 - NU)))
    assert weber_approach(w, h, a, E, NU) == pytest.approx(weber, rel=1e-4)


def test_tangent_is_the_secant_minus_half_yang_and_sun():
    """d(w C)/dw = C − 1/(π b E*) for h ≫ a: a ∝ √w makes dδ/dw = δ/w − 1/(π E′) per body,
    and 1/E′_1 + 1/E′_2 = 1/E* (plane strain), so Weber's secant compliance exceeds its
    tangent by half the linear Hertz term 2/(π b E*) of Yang & Sun (1985) that the law used
    before. Central difference, step 1e-4 w; bound 1e-4 relative (the O((a/h)²) remainder
    at h = 400 mm, a ≈ 0.1 mm is far below)."""
    b, r_red, h1, h2 = 20.0, 10.0, 400.0, 400.0  # deep points: the asymptotic regime
    kw = {"face_width_mm": b, "E1_MPa": E, "nu1": NU, "E2_MPa": E, "nu2": NU}
    w, dw = 200.0, 0.02
    secant = weber_pair_compliance(w, r_red, h1, h2, **kw)
    tangent = ((w + dw) * weber_pair_compliance(w + dw, r_red, h1, h2, **kw)
               - (w - dw) * weber_pair_compliance(w - dw, r_red, h1, h2, **kw)) / (2 * dw)
    assert secant - tangent == pytest.approx(0.5 * hertz_compliance(b, E, NU, E, NU), rel=1e-4)


def test_law_contact_term_is_weber_to_the_centrelines():
    """On the path the law's contact compliance is Weber's at the Hertz half width of the
    involutes' reduced radius, each body's flattening to its tooth centreline (h_P of the
    contact point); it softens with less load and does not depend on it linearly."""
    geo = compute_pair_geometry(PairSpec(2.0, A20, GearSpec(62, 20), GearSpec(62, 20)))
    x_c = geo.C_mm - geo.A_mm
    kw = {"face_width_mm": 20.0, "E1_MPa": E, "nu1": NU, "E2_MPa": E, "nu2": NU}
    ps = pair_stiffness(geo, [x_c], load_N_mm=200.0, **kw)
    rho1 = geo.C_mm
    rho2 = geo.T1T2_mm - rho1
    r1, r2 = np.hypot(geo.pinion.r_b_mm, rho1), np.hypot(geo.gear.r_b_mm, rho2)
    h1, h2 = tooth_point(geo.pinion, r1)[0], tooth_point(geo.gear, r2)[0]
    a = hertz_half_width(200.0, rho1 * rho2 / (rho1 + rho2), contact_modulus(E, NU, E, NU))
    expect = (weber_approach(200.0, h1, a, E, NU) + weber_approach(200.0, h2, a, E, NU)) / (
        200.0 * 20.0)
    assert ps.hertz_mm_N[0] == pytest.approx(float(expect), rel=1e-12)
    c = pair_contact(geo, [x_c])
    assert c.h_point1_mm[0] == pytest.approx(float(h1), rel=1e-12)
    light = pair_stiffness(geo, [x_c], load_N_mm=50.0, **kw)
    assert light.hertz_mm_N[0] > ps.hertz_mm_N[0] > hertz_compliance(20.0, E, NU, E, NU)
    legacy = pair_stiffness(geo, [x_c], **kw)  # no load: Yang & Sun, the law before issue 31
    assert legacy.hertz_mm_N[0] == pytest.approx(hertz_compliance(20.0, E, NU, E, NU))
    with pytest.raises(ValueError, match="load > 0"):
        weber_pair_compliance(0.0, 10.0, 1.0, 1.0, **kw)
