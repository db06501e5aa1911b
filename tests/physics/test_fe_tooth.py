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
    parts at C [N/mm], at the default bores, both in the FE's plane state, the law's contact
    term (Weber to the centrelines) at the line load w."""
    fe = fe_mesh_stiffness(geo, face_width_mm=b, load_N_mm=w, **MAT)
    x_c = geo.C_mm - geo.A_mm
    law = {"face_width_mm": b, "plane_strain": fe.plane_strain, "load_N_mm": w, **MAT}
    pe = pair_stiffness(geo, [x_c], **law)
    pe_mean = mesh_stiffness(geo, **law)
    pe_teeth = float(pe.pinion.total_mm_N[0] + pe.gear.total_mm_N[0])
    fe_teeth = float(np.interp(x_c, fe.x_mm, fe.tooth1_mm_N + fe.tooth2_mm_N))
    return {"pitch": (float(pe.k_N_mm[0]), fe.pitch_pair_N_mm),
            "mean": (pe_mean.mean_N_mm, fe.mean_N_mm), "teeth": (1 / pe_teeth, 1 / fe_teeth)}


@pytest.mark.slow
@pytest.mark.parametrize("name, geo, b, w", PAIRS, ids=[p[0] for p in PAIRS])
def test_pe_tooth_law_against_fe(name, geo, b, w):
    """Issue 31's target: the law's single-pair stiffness at C and mean mesh stiffness within
    5 % of FE on the four pairs at their default bores. Measured FE/PE − 1:

    ====================  =======================  =======================  ===========
    pair                  k at C  before / now     mean  before / now       teeth at C
    ====================  =======================  =======================  ===========
    seed 17/25            −20.6 % / +2.6 %         −20.0 % / +1.3 %         −5.2 %
    62/62 m 2             −9.0 % / +3.8 %          −9.3 % / +2.0 %          −4.7 %
    28/28 m 3.175         −13.2 % / +4.3 %         −13.0 % / +2.7 %         −4.0 %
    21/43 shifted         −13.3 % / +3.8 %         −13.3 % / +2.4 %         −4.3 %
    ====================  =======================  =======================  ===========

    "Before": the linear Hertz term 2/(π b E*) (Yang & Sun 1985), 1.7–3.9 times stiffer than
    Weber's flattening; "now": Weber's flattening to the tooth centrelines at the line load
    (docs/theory.md §4b), the FE's own local term taken deeper. The mean is a secant at the
    full load on both sides except that the FE shares the load between the pairs (each pair's
    local term at its share): the law is slightly softer in the double-pair zone. The 5 %
    is the issue's bound, not a fit: the FE was not tuned to the law nor the law to the FE
    (the depth to the centreline is Weber's). The teeth + body alone (the law's beam to the
    centreline vs the FE read 0.25 m below the surface) within 8 %."""
    r = pe_vs_fe(geo, b, w)
    for key in ("pitch", "mean"):
        pe, fe = r[key]
        assert fe == pytest.approx(pe, rel=0.05), (key, fe / pe - 1.0)
    pe_t, fe_t = r["teeth"]
    assert fe_t == pytest.approx(pe_t, rel=0.08)


PAIR_62 = PAIRS[1][1]


@pytest.mark.slow
def test_corner_contact_rises_towards_the_tip_edge_in_fe_too():
    """Contact outside the path (the tip corner on the mate's involute, the force along the
    mate's involute normal): FE and law at 0.1 … 1.2 mm before A and after E on 62/62 m 2 at
    200 N/mm. Measured FE/PE − 1 +3.4 … +3.5 % (as on the path), and both rise towards the
    edge (+3.0 % FE, +2.9 % law from A to 1.2 mm before it): the corner is no softer in FE,
    so the law's rising corner stiffness is the mechanics of the turned force, not a missing
    compliance. Bounds: 5 % (the path's bound) and a rise in both."""
    from gearcli.model.fe.extended import fe_pair_stiffness

    ga = PAIR_62.g_alpha_mm
    x = np.array([-1.2, -0.4, -0.1, 0.0, ga, ga + 0.1, ga + 0.4, ga + 1.2])
    law = {"face_width_mm": 20.0, "load_N_mm": 200.0, "plane_strain": True, **MAT}
    k_fe = fe_pair_stiffness(PAIR_62, x, **law)
    k_pe = pair_stiffness(PAIR_62, x, **law).k_N_mm
    assert np.all(np.abs(k_fe / k_pe - 1.0) < 0.05), k_fe / k_pe - 1.0
    for k in (k_fe, k_pe):
        assert k[0] > k[1] > k[2] > k[3] and k[-1] > k[-2] > k[-3] > k[-4]


def test_fe_loads_at_involute_points_match_the_flank_normal_route():
    """fe_tooth_compliance with explicit loads (the corner route: points (−h_P, y_P), forces
    (cos α_1, −sin α_1) from the law's contact geometry) gives the involute route's
    compliance on the path: the same points and directions (to round-off) in one mesh."""
    from gearcli.model.fe.extended import tooth_loads
    from gearcli.model.pair_stiffness import pair_contact

    g = SEED.pinion
    x = np.array([0.0, SEED.C_mm - SEED.A_mm, SEED.g_alpha_mm])
    c = pair_contact(SEED, x)
    pts, dirs = tooth_loads(c.y_point1_mm, c.h_point1_mm, c.angle1_rad)
    r = np.hypot(g.r_b_mm, SEED.A_mm + x)
    common = {"bore_diameter_mm": default_bore_diameter(g), "youngs_MPa": E, "poisson": NU,
              "plane_strain": True, "control": MeshControl(refinement=0.5)}
    by_radius = fe_tooth_compliance(g, r, **common).compliance_mm2_N
    by_point = fe_tooth_compliance(g, None, loads=(pts, dirs), **common).compliance_mm2_N
    assert by_point == pytest.approx(by_radius, rel=1e-6)


@pytest.mark.slow
def test_loaded_contact_with_the_tip_corners_law_against_fe():
    """Issue 31's 62/62 m 2 b 20 pair (bores 40 mm) at 0.1, 0.3, 1 and 2 times its 200 N/mm,
    loaded contact with the case's gaps (extended contact at the tip corners) by the same LTCA,
    only k(x) from the law or from FE (pipeline/mesh_fe.py; 29 roll nodes from 2.1 mm before
    A to 2.1 mm after E, those of the 2× load, for all loads). Measured STE peak-to-peak law /
    FE [µm]: 0.82 / 0.80, 1.76 / 1.79, 0.81 / 0.89, 3.06 / 2.89 (FE/PE − 1 −3.0, +1.8,
    +9.9, −5.4 %); one pair alone in contact at 0.1 × only (7.5 % of the cycle, both), never
    at 0.3 × and above. Asserted: within 15 % (the issue's bound) at every load, and the FE
    has no single-pair zone at the nominal load either: the tip gap at the middle of the
    single-pair zone, 0.62 mm outside the path, is 4.1 µm against a mesh deflection of
    8–14 µm, so the corner touches whatever its stiffness (docs/theory.md §4b, "Corner
    contact"); the Harris map of the unmodified pair is not monotonic in FE either."""
    from gearcli.case.load import load_case
    from gearcli.pipeline.geometry import run_geometry
    from gearcli.pipeline.mesh_fe import loaded_pe_fe
    from gearcli.pipeline.mesh_input import static_force_N
    from tests.unit.test_modal_no_single_zone import ISO_PAIR
    from tests.unit.test_modal_no_single_zone import PAIR_62 as OVERRIDES_62

    loaded = load_case(ISO_PAIR, OVERRIDES_62)
    geo = run_geometry(loaded)
    force = static_force_N(loaded.case, geo)
    m = loaded.case.material
    cache = ComplianceCache()  # one FE model per gear: the nodes of the largest load for all
    ste, nodes = {}, None
    for frac in (2.0, 1.0, 0.3, 0.1):
        law = {"face_width_mm": 20.0, "E1_MPa": m.youngs_modulus, "nu1": m.poisson_ratio,
               "E2_MPa": m.youngs_modulus, "nu2": m.poisson_ratio, "bore_diameter1_mm": 40.0,
               "bore_diameter2_mm": 40.0, "plane_strain": True,
               "load_N_mm": frac * force / 20.0}
        ste[frac], single, nodes = loaded_pe_fe(loaded.case, geo, frac * force, law, cache,
                                                nodes)
        assert ste[frac].fe == pytest.approx(ste[frac].pe, rel=0.15), (frac, ste[frac])
        if frac == 1.0:
            assert single.fe == 0.0 and single.pe == 0.0
    assert ste[0.3].fe > ste[1.0].fe < ste[2.0].fe  # the dip of the extended contact
