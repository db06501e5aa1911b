"""One body model (issue 31, docs/theory.md §2.6): a gear's given ``bore_diameter`` feeds both
the tooth law's gear-body compliance and the disc's mass and inertia; a given inertia wins."""

from __future__ import annotations

import math

import pytest

from gearcli.case.load import load_case
from gearcli.pipeline.geometry import run_geometry
from tests.conftest import ROOT, SEED

RHO = 7.85e-9  # t/mm^3, the seed's steel
B = 100.0  # mm, the seed's face width
D1 = 170.0  # mm, the seed pinion's reference diameter (the default disc)


def _pinion(*overrides):
    return run_geometry(load_case(SEED, list(overrides))).mass[0]


def test_a_bore_lowers_the_inertia_by_the_hollow_disc_closed_form():
    solid = _pinion()
    # J = π ρ b r⁴/2 of the solid disc (today's convention: the disc of the reference
    # diameter stands for the toothed ring)
    assert solid.inertia_t_mm2 == pytest.approx(math.pi * RHO * B * (D1 / 2) ** 4 / 2, rel=1e-12)
    for bore in (40.0, 80.0, 120.0):
        bored = _pinion(f"gears.pinion.bore_diameter={bore} mm")
        drop = solid.inertia_t_mm2 - bored.inertia_t_mm2
        assert drop == pytest.approx(math.pi * RHO * B * (bore / 2) ** 4 / 2, rel=1e-12)
        assert solid.mass_t - bored.mass_t == pytest.approx(
            math.pi * RHO * B * (bore / 2) ** 2, rel=1e-12)
    # a larger bore, a smaller inertia (monotonic)
    j = [_pinion(f"gears.pinion.bore_diameter={b} mm").inertia_t_mm2 for b in (40, 80, 120)]
    assert j[0] > j[1] > j[2]


def test_a_given_inertia_wins_over_the_bore():
    given = ["gears.pinion.inertia.model=given", "gears.pinion.inertia.value=0.05 kg*m^2"]
    plain = _pinion(*given)
    bored = _pinion(*given, "gears.pinion.bore_diameter=80 mm")
    assert plain.inertia_t_mm2 == bored.inertia_t_mm2 == pytest.approx(0.05e3)  # t*mm^2


def test_the_same_bore_sets_the_stiffness_and_the_inertia():
    from gearcli.pipeline.kernel_input import linearised_mesh

    def body(bore):  # cases/iso_pair.yaml: the tooth law
        loaded = load_case(ROOT / "cases" / "iso_pair.yaml",
                           [f"gears.pinion.bore_diameter={bore} mm"])
        geo = run_geometry(loaded)
        return linearised_mesh(loaded.case, geo).mesh_stiffness_N_mm, geo.mass[0].inertia_t_mm2

    # Sainsot et al.'s body is held rigidly at the bore: a bore nearer the root holds the tooth
    # nearer (stiffer, measured +12 % from 30 to 70 mm); the inertia falls by the closed form
    (k_small, j_small), (k_large, j_large) = body(30.0), body(70.0)
    assert k_large > 1.05 * k_small and j_large < j_small


def test_a_disc_inside_the_bore_is_refused():
    from gearcli.errors import GearcliError

    with pytest.raises(GearcliError, match="bore"):
        load_case(SEED, ["gears.pinion.bore_diameter=80 mm",
                         "gears.pinion.inertia.diameter=60 mm"])
