"""The contact laws of the kernel (gearcli/core/laws.py), one pair at a time, against their closed
forms in docs/theory.md (§4.2-4.3 IMPACT, §4b.1-4b.2 and §4c the tooth law), called directly
(the compiled functions run from Python) and through the one dispatch point ``pair_force``.

Each law turns ``pair = (p, p', dp/ds1, dp/ds2, k, dk/dx1)`` and ``shared = (sigma, v,
sum k p)`` into ``(F, q1, q2, pot, pdamp)`` added to the running sums ``acc``. The reference
values below are written from the formulas, not from the code; they agree to round-off
(rel 1e-12: a few operations in another order).

Units: mm, N, s (docs/theory.md §1).
"""

from __future__ import annotations

import numpy as np
import pytest

from gearcli.core import layout
from gearcli.core.laws import KNOWN_LAWS, impact_law, law_constants, pair_force, tooth_law
from gearcli.core.layout import D, P
from tests.physics.test_kernel import adams_step  # docs/theory.md §4.1, written out

K_IMPACT = 1e5  # [N/mm^e]
C_MAX, D_MAX = 100.0, 0.1  # [N s/mm], [mm]
K_TOOTH = 1.4e6  # [N/mm]
C_M, F_REF = 3000.0, 3000.0  # mesh damping [N s/mm], reference force [N]
ACC = (10.0, -20.0, 3.0, 4.0)  # running sums the law adds to (q1, q2, pot, pdamp)
REL = 1e-12


def vectors(exponent: float = 1.5):
    """The run's parameter and derived vectors the laws' constants come from."""
    prm = np.zeros(layout.N_PARAMS)
    prm[P.exponent], prm[P.c_max], prm[P.d_max] = exponent, C_MAX, D_MAX
    prm[P.mesh_damping], prm[P.damping_force_ref] = C_M, F_REF
    derived = np.zeros(layout.N_DERIVED)
    derived[D.inv_exponent_plus_1] = 1.0 / (exponent + 1.0)
    return prm, derived


def constants(exponent: float = 1.5, factors: bool = False, **changes):
    """The laws' constants (laws.law_constants) of :func:`vectors` with ``prm`` entries
    changed by name; ``factors``: a run with stiffness factors (derived tooth_factors_used)."""
    prm, derived = vectors(exponent)
    for name, value in changes.items():
        prm[getattr(P, name)] = value
    derived[D.tooth_factors_used] = 1.0 if factors else 0.0
    return law_constants(prm, derived)


def impact_reference(pen, rate, dp1, dp2, k, dk, sigma, e):
    """docs/theory.md §4.2-4.3 with V = k(x1) p^(e+1)/(e+1): F, -dV/ds1 - damping, ..."""
    fel = k * pen**e
    force = max(0.0, fel + adams_step(pen, 0.0, 0.0, D_MAX, C_MAX) * rate)
    dq1 = -pen ** (e + 1.0) / (e + 1.0) * dk * sigma - (force * dp1 if force > 0 else 0.0)
    dq2 = -force * dp2 if force > 0 else 0.0
    return force, dq1, dq2, k * pen ** (e + 1.0) / (e + 1.0), (force - fel) * rate


def tooth_reference(pen, rate, dp1, dp2, k, dk, sigma, v, fel_sum):
    """docs/theory.md §4b.1, §4c: F = max(0, k p (1 + c_m v / max(sum k p, F_ref)))."""
    fel = k * pen
    force = max(0.0, fel * (1.0 + C_M * v / max(fel_sum, F_REF)))
    dq1 = -0.5 * pen**2 * dk * sigma
    if force <= 0.0:
        return 0.0, dq1, 0.0, 0.5 * k * pen**2, -fel * rate
    fd = force - fel
    return force, dq1 - fel * dp1 - fd * sigma, -fel * dp2 + fd * sigma, 0.5 * k * pen**2, fd * v


def check(got, ref):
    force, dq1, dq2, pot, pdamp = ref
    expected = (force, ACC[0] + dq1, ACC[1] + dq2, ACC[2] + pot, ACC[3] + pdamp)
    for name, g, r in zip(("F", "q1", "q2", "pot", "pdamp"), got, expected, strict=True):
        assert g == pytest.approx(r, rel=REL, abs=1e-9), name


@pytest.mark.parametrize("e", [1.0, 1.5, 2.2])
@pytest.mark.parametrize("pen, rate", [(1e-4, 0.0), (0.03, 50.0), (0.03, -2000.0),
                                       (0.05, -1.0), (0.2, 30.0), (0.2, -1e6)])
@pytest.mark.parametrize("sigma, dk", [(1.0, 0.0), (-1.0, 0.0), (1.0, 3e3), (-1.0, -2e4)])
def test_impact_law_matches_its_closed_form(e, pen, rate, sigma, dk):
    consts = constants(e)
    pair = (pen, rate, 0.98 * sigma, -1.03 * sigma, K_IMPACT, dk)
    got = impact_law(consts, pair, (sigma, 0.0, 0.0), ACC)
    check(got, impact_reference(*pair, sigma, e))
    assert got == pair_force(layout.LAW_IMPACT, consts, pair, (sigma, 0.0, 0.0), ACC)


def test_impact_law_clipped_force_still_dissipates():
    """A fast separation (p' << 0) clips F to 0: no generalized force, dissipation -k p^e p'
    >= 0 (docs/theory.md §4.3)."""
    force, q1, q2, _, pdamp = impact_law(constants(1.5), (0.05, -1e6, 1.0, -1.0, K_IMPACT, 0.0),
                                         (1.0, 0.0, 0.0), ACC)
    assert force == 0.0 and (q1, q2) == ACC[:2]
    assert pdamp - ACC[3] == pytest.approx(K_IMPACT * 0.05**1.5 * 1e6, rel=REL)


@pytest.mark.parametrize("pen, rate, v", [(1e-5, 0.0, 0.0), (2e-3, 5.0, 20.0),
                                          (2e-3, -5.0, -20.0), (1e-3, 1.0, -1e4)])
@pytest.mark.parametrize("fel_sum", [100.0, 2e5])  # below and above F_ref
@pytest.mark.parametrize("sigma, dk", [(1.0, 0.0), (-1.0, 0.0), (1.0, 5e4), (-1.0, -3e5)])
def test_tooth_law_matches_its_closed_form(pen, rate, v, fel_sum, sigma, dk):
    consts = constants(1.0)
    pair = (pen, rate, 1.01 * sigma, -0.97 * sigma, K_TOOTH, dk)
    shared = (sigma, v, fel_sum)
    got = tooth_law(consts, pair, shared, ACC)
    check(got, tooth_reference(*pair, sigma, v, fel_sum))
    assert got == pair_force(layout.LAW_TOOTH, consts, pair, shared, ACC)


def test_tooth_law_shares_the_damping_in_proportion_to_the_elastic_forces():
    """Two pairs under one mesh rate: their damping forces are c_m v k_j p_j / sum k p, adding
    up to c_m v when loaded (docs/theory.md §4c)."""
    consts = constants(1.0)
    pairs = [(2e-3, 0.0, 1.0, -1.0, K_TOOTH, 0.0), (1e-3, 0.0, 1.0, -1.0, 0.5 * K_TOOTH, 0.0)]
    fel_sum = sum(p[0] * p[4] for p in pairs)
    v = 3.0
    damping = [tooth_law(consts, p, (1.0, v, fel_sum), ACC)[0] - p[0] * p[4]
               for p in pairs]
    assert sum(damping) == pytest.approx(C_M * v, rel=REL)
    assert damping[0] / damping[1] == pytest.approx(4.0, rel=REL)


def test_the_potential_gradient_is_the_generalized_force():
    """Both laws: the elastic generalized force on s1 is -dV/ds1 of V(k(x1), p) with
    x1 = sigma s1 + const, p = p0 + dp/ds1 s1 (no rate, no damping): a central difference of
    V along s1 (k linear in x1; O(h^2) and round-off ~1e-8 relative). Without the dk/dx1 term
    q1 would be off by 8e-3 (IMPACT) and 7.5e-4 (tooth) relative, far beyond 1e-6."""
    for law, e in ((layout.LAW_IMPACT, 1.5), (layout.LAW_TOOTH, 1.0)):
        consts = constants(e, c_max=0.0)
        k0, dk, p0, dp1, sigma = (K_IMPACT if law == layout.LAW_IMPACT else K_TOOTH), 2e5, \
            0.01, 0.95, -1.0

        def potential(s1, law=law, consts=consts, k0=k0, dk=dk, p0=p0, dp1=dp1, sigma=sigma):
            pair = (p0 + dp1 * s1, 0.0, dp1, -1.0, k0 + dk * sigma * s1, dk)
            return pair_force(law, consts, pair, (sigma, 0.0, 0.0), (0.0,) * 4)[3]

        h = 1e-6
        q1 = pair_force(law, consts, (p0, 0.0, dp1, -1.0, k0, dk), (sigma, 0.0, 0.0),
                        (0.0,) * 4)[1]
        assert q1 == pytest.approx(-(potential(h) - potential(-h)) / (2 * h), rel=1e-6), law


def test_every_known_law_dispatches_to_its_own_function():
    """pair_force picks the law by its id; every id in KNOWN_LAWS has a branch (a law without
    one would silently fall back to IMPACT)."""
    consts = constants(1.0)
    pair, shared = (2e-3, 4.0, 1.0, -1.0, K_TOOTH, 0.0), (1.0, 4.0, 2e5)
    own = {layout.LAW_IMPACT: impact_law, layout.LAW_TOOTH: tooth_law}
    assert sorted(own) == sorted(KNOWN_LAWS)
    results = {law: pair_force(law, consts, pair, shared, ACC) for law in KNOWN_LAWS}
    for law in KNOWN_LAWS:
        assert results[law] == own[law](consts, pair, shared, ACC)
    assert len({r[0] for r in results.values()}) == len(KNOWN_LAWS)  # the laws differ here


def test_impact_damping_scales_with_the_stiffness_factor():
    """With stiffness factors the IMPACT law scales c_max by f = k/k_contact as it scales k
    (docs/theory.md §4b.2): at full damping depth (p >= d_max) the damping force is f c_max p';
    f = 0 (a missing tooth) carries no force at all; f = 1 is the plain law."""
    consts = constants(1.5, factors=True, k_contact=K_IMPACT, c_max=30.0, d_max=1e-4)
    pen, rate = 2e-3, 50.0  # p > d_max: STEP at its full value c_max
    elastic = K_IMPACT * pen ** 1.5
    for f in (1.0, 0.5, 0.0):
        pair = (pen, rate, 1.0, -1.0, f * K_IMPACT, 0.0)
        got = impact_law(consts, pair, (1.0, rate, 0.0), ACC)
        assert got[0] == pytest.approx(f * (elastic + 30.0 * rate), rel=1e-12, abs=0.0), f
        # the kernel's dispatch in a run with stiffness factors scales the same way
        assert pair_force(layout.LAW_IMPACT, consts, pair, (1.0, rate, 0.0), ACC) == got


def test_without_stiffness_factors_the_dispatch_skips_the_damping_scaling():
    """A run without stiffness factors has the run's k for every pair, so pair_force takes the
    IMPACT law without the scaling test (laws._impact): the same numbers as impact_law for
    that k, and c_max unscaled."""
    consts = constants(1.5, k_contact=K_IMPACT, c_max=30.0, d_max=1e-4)
    pair, shared = (2e-3, 50.0, 1.0, -1.0, K_IMPACT, 0.0), (1.0, 50.0, 0.0)
    assert pair_force(layout.LAW_IMPACT, consts, pair, shared, ACC) == \
        impact_law(consts, pair, shared, ACC)
    assert consts.stiffness_factors == 0.0
    assert constants(1.5, factors=True).stiffness_factors == 1.0
