"""FE tooth compliance (docs/theory.md, "Finite-element check of the tooth compliance"):
mesh convergence, independence of the load-point refinement and of the reading depth, and
the potential-energy tooth law against FE on the four pairs of issue 31."""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("skfem", reason="optional extra 'fe'")
pytest.importorskip("triangle", reason="optional extra 'fe'")

from gearcli.model.fe import ComplianceCache, MeshControl, fe_mesh_stiffness  # noqa: E402
from gearcli.model.fe.tooth import fe_tooth_compliance  # noqa: E402
from gearcli.model.geometry import GearSpec, PairSpec, compute_pair_geometry  # noqa: E402
from gearcli.model.pair_stiffness import mesh_stiffness, pair_stiffness  # noqa: E402
from gearcli.model.tooth_stiffness import default_bore_diameter  # noqa: E402

A20 = math.radians(20.0)
E, NU = 2.07e5, 0.29  # MPa, - (the seed's steel)
SEED = compute_pair_geometry(PairSpec(10.0, A20, GearSpec(17, 100), GearSpec(25, 100)))
MAT = {"E1_MPa": E, "nu1": NU, "E2_MPa": E, "nu2": NU}


def _seed_pinion(control: MeshControl):
    g = SEED.pinion
    x = np.array([0.0, SEED.C_mm - SEED.A_mm, SEED.g_alpha_mm])  # A, C, E
    r = np.hypot(g.r_b_mm, SEED.A_mm + x)
    return fe_tooth_compliance(g, r, bore_diameter_mm=default_bore_diameter(g), youngs_MPa=E,
                               poisson=NU, plane_strain=True, control=control).compliance_mm2_N


def test_mesh_refinement_convergence_at_three_roll_positions():
    """Seed pinion at A, C and E (tip corner), every element size divided by 0.5 … 2.
    Measured (compliance ×1e5 mm²/N): refinement 0.5: 3.189 / 3.878 / 7.570; 1: 3.208 /
    3.889 / 7.581; 1.41: 3.209 / 3.889 / 7.582; 2: 3.203 / 3.892 / 7.588. The change from 0.5
    to 1 is 0.1–0.6 %, beyond 1 within ±0.2 % without a clean algebraic rate (re-meshing noise
    of the unstructured mesh dominates). Tolerances: the default (1) is within 0.5 % of 2 and
    the coarse mesh within 1.5 % (three times the observed), so a mesh that resolves nothing
    (a lost fillet refinement changes the root values by several %) fails."""
    coarse, default, fine = (_seed_pinion(MeshControl(refinement=f)) for f in (0.5, 1.0, 2.0))
    assert np.all(np.abs(default / fine - 1.0) < 0.005)
    assert np.all(np.abs(coarse / fine - 1.0) < 0.015)


def test_load_point_refinement_does_not_change_the_answer():
    """Only the boundary spacing at the loaded tooth (where the point load sits) is divided by
    4: the compliance read at depth moves by < 0.15 % (measured); bound 0.5 %. Reading the
    displacement AT the point load would diverge logarithmically instead."""
    base = _seed_pinion(MeshControl())
    fine = _seed_pinion(MeshControl(fine=0.01))
    assert np.all(np.abs(fine / base - 1.0) < 0.005)


@pytest.mark.parametrize("geo, b, w", [(SEED, 100.0, 38.3)])
def test_pair_stiffness_does_not_depend_on_the_reading_depth(geo, b, w):
    """FE global part at depth h plus Weber's term from the surface to h: h = 0.1 m … 0.4 m
    (×4) moved the pair stiffness by 1.1 % at the roll ends and 0.6 % at C on the seed (w
    38 N/mm) and by 2.9 % / 1.7 % on 62/62 m 2 at 200 N/mm (there h = 0.2 mm is 1.3 a); the
    local term itself changes by ~50 % over that range. Bound 2 % for the seed."""
    res = [fe_mesh_stiffness(geo, face_width_mm=b, load_N_mm=w, n_roll=5, **MAT,
                             control=MeshControl(depth=d), cache=ComplianceCache())
           for d in (0.1, 0.4)]
    assert np.all(np.abs(res[1].pair_N_mm / res[0].pair_N_mm - 1.0) < 0.02)
    assert np.all(res[1].local_mm_N > 1.3 * res[0].local_mm_N)  # the split did move


#: issue 31's pairs: (name, spec, face width [mm], line load [N/mm]); the seed at its
#: 450 N·m on the gear (w = T/(r_b2 b) = 38.3 N/mm), the others at 200 N/mm; 28/28 m 3.175
#: with the NASA Glenn test gears' 6.35 mm face (plane stress by the face-width rule).
PAIRS = [
    ("seed 17/25 m 10 b 100", SEED, 100.0, 450e3 / (SEED.gear.r_b_mm * 100.0)),
    ("62/62 m 2 b 20", compute_pair_geometry(PairSpec(2.0, A20, GearSpec(62, 20),
                                                      GearSpec(62, 20))), 20.0, 200.0),
    ("28/28 m 3.175 b 6.35", compute_pair_geometry(PairSpec(3.175, A20, GearSpec(28, 6.35),
                                                            GearSpec(28, 6.35))), 6.35, 200.0),
    ("21/43 m 5 b 50 x 0.35/-0.2", compute_pair_geometry(PairSpec(
        5.0, A20, GearSpec(21, 50, 0.35), GearSpec(43, 50, -0.2))), 50.0, 200.0),
]


def pe_vs_fe(geo, b, w):
    """(PE, FE) at the pitch point (pair) and the mean mesh stiffness, and the tooth-only
    parts at C [N/mm], at the default bores, both in the FE's plane state."""
    fe = fe_mesh_stiffness(geo, face_width_mm=b, load_N_mm=w, **MAT)
    x_c = geo.C_mm - geo.A_mm
    pe = pair_stiffness(geo, [x_c], face_width_mm=b, plane_strain=fe.plane_strain, **MAT)
    pe_mean = mesh_stiffness(geo, face_width_mm=b, plane_strain=fe.plane_strain, **MAT)
    pe_teeth = float(pe.pinion.total_mm_N[0] + pe.gear.total_mm_N[0])
    fe_teeth = float(np.interp(x_c, fe.x_mm, fe.tooth1_mm_N + fe.tooth2_mm_N))
    fe_local = float(np.interp(x_c, fe.x_mm, fe.local_mm_N))
    return {"pitch": (float(pe.k_N_mm[0]), fe.pitch_pair_N_mm),
            "mean": (pe_mean.mean_N_mm, fe.mean_N_mm), "teeth": (1 / pe_teeth, 1 / fe_teeth),
            "contact": (1 / pe.hertz_mm_N, 1 / fe_local), "plane_strain": fe.plane_strain}


@pytest.mark.slow
@pytest.mark.parametrize("name, geo, b, w", PAIRS, ids=[p[0] for p in PAIRS])
def test_pe_tooth_law_against_fe(name, geo, b, w):
    """The finding (docs/theory.md, FE section), measured FE/PE − 1:

    ====================  ========  ========  ===========  ===============
    pair                  k at C    mean      teeth at C   contact at C
    ====================  ========  ========  ===========  ===============
    seed 17/25            −20.6 %   −20.0 %   −5.2 %       Weber/YS ×3.9
    62/62 m 2             −9.0 %    −9.3 %    −4.7 %       ×1.7
    28/28 m 3.175         −13.2 %   −13.0 %   −4.0 %       ×2.6
    21/43 shifted         −13.3 %   −13.3 %   −4.3 %       ×2.5
    ====================  ========  ========  ===========  ===============

    The teeth + body agree within 5.3 %; the pair differs by 9–21 % because the law's
    linear Hertz term 2/(π b E*) (Yang & Sun 1985) is 1.7–3.9 times stiffer than Weber's
    flattening at the load. Asserted: teeth within 8 % (1.5× the worst observed), and the
    FE contact compliance larger than the law's (the cause); the pair totals are reported,
    not asserted (the FE is not tuned to the law)."""
    r = pe_vs_fe(geo, b, w)
    pe_t, fe_t = r["teeth"]
    assert fe_t == pytest.approx(pe_t, rel=0.08)
    pe_c, fe_c = r["contact"]
    assert fe_c < pe_c
