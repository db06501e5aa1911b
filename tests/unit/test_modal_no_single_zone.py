"""`gearcli modal` on a loaded mesh without a single-pair zone (issue 31 item 4).

A pair whose loaded contact has two or more pairs at every roll position has no single-pair
stiffness (NaN, JSON null); the modal model must not need it: it is linearised with the mean
stiffness of the loaded contact over the mesh cycle (gearcli.pipeline.kernel_input.
linearised_mesh, docs/theory.md §4b), and the zone stiffness it cannot give is reported as not
applicable. Two pairs: 62/62, m 2 mm, b 20 mm, 233 N·m (F/b ≈ 200 N/mm), at α 20° (ε_α 1.79,
the issue's pair: 2-3 pairs under load) and at α 15° (ε_α 2.15: never a single pair, by
geometry alone, whatever the tooth-compliance model does at the tip corner).
"""

import json
import math

import numpy as np
import pytest

from gearcli.pipeline.mesh import run_mesh
from gearcli.pipeline.modal import modal_document, run_modal
from tests.conftest import ROOT

ISO_PAIR = ROOT / "cases" / "iso_pair.yaml"
PAIR_62 = ["gears.module=2 mm", "gears.face_width=20 mm", "gears.pinion.teeth=62",
           "gears.gear.teeth=62", "gears.pinion.profile_shift=0", "gears.gear.profile_shift=0",
           "gears.pinion.bore_diameter=40 mm", "gears.gear.bore_diameter=40 mm",
           'load.torque={function: "STEP(time, 0, 0, 0.2, 233)", unit: N*m}']
ALPHA_15 = [*PAIR_62, "gears.pressure_angle=15 deg"]

#: The modal linearisation (kernel_input.LINEARISATION_POINTS = 100 positions, one cycle) and
#: run_mesh(cycles=1, points_per_cycle=100) solve the same equations on the same roll grid:
#: they agree to round-off, so a relative 1e-12 would catch any other stiffness (the
#: geometric/ISO fallback differs by > 10 %).
SAME_SOLVE = 1e-12


@pytest.fixture(scope="module", params=[PAIR_62, ALPHA_15], ids=["alpha20", "alpha15"])
def analyses(request):
    return (run_modal(ISO_PAIR, request.param),
            run_mesh(ISO_PAIR, request.param, cycles=1, points_per_cycle=100))


def test_alpha15_pair_never_has_a_single_pair_in_contact():
    # the premise, by geometry: ε_α > 2, and the loaded contact keeps >= 2 pairs everywhere
    res = run_mesh(ISO_PAIR, ALPHA_15, cycles=1, points_per_cycle=100)
    assert res.geometry.geometry.eps_alpha > 2.0
    assert res.loaded.pairs_in_contact.min() >= 2
    assert math.isnan(res.loaded.zone_stiffness_N_mm(1))


def test_modal_linearised_with_the_loaded_mean_stiffness(analyses):
    modal, mesh = analyses
    k_mean = float(mesh.loaded.mesh_stiffness_N_mm.mean())
    assert modal.mesh.mesh_stiffness_N_mm == pytest.approx(k_mean, rel=SAME_SOLVE)
    # the zone stiffnesses are those of the loaded contact, NaN where the zone is absent
    for pairs, value in ((1, modal.mesh.single_pair_stiffness_N_mm),
                         (2, modal.mesh.double_pair_stiffness_N_mm)):
        expected = mesh.loaded.zone_stiffness_N_mm(pairs)
        assert (math.isnan(value) and math.isnan(expected)) or \
            value == pytest.approx(expected, rel=SAME_SOLVE)


def test_mesh_mode_is_the_closed_form_of_the_mean_stiffness(analyses):
    # drive 'speed': the pinion is prescribed, one coordinate θ2, so the one mode is
    # f = sqrt(k r_b2² / J2) / 2π (single-DOF oscillator, Rao §2.2); with viscous mesh damping
    # |λ| of the complex pair is that same ω_n (Rao §2.6)
    modal, _ = analyses
    st = modal.system.structure
    (mode,) = modal.result.elastic
    f = math.sqrt(modal.mesh.mesh_stiffness_N_mm * st.r_b2_mm**2 / st.J2_t_mm2) / (2 * math.pi)
    assert mode.undamped_frequency_Hz == pytest.approx(f, rel=1e-12)  # eigh round-off
    assert mode.natural_frequency_Hz == pytest.approx(f, rel=1e-9)  # eig round-off
    assert mode.description.startswith("mesh mode")


def test_document_is_strict_json_with_null_single_pair_zone(analyses):
    modal, _ = analyses
    doc = modal_document(modal).to_dict()
    text = json.dumps(doc, allow_nan=False)  # raises on a NaN anywhere
    lin = json.loads(text)["linearisation"]
    if math.isnan(modal.mesh.single_pair_stiffness_N_mm):
        assert lin["single_pair_stiffness_N_mm"] is None
    assert lin["double_pair_stiffness_N_mm"] > 0.0
    assert np.isfinite(lin["mesh_stiffness_N_mm"]) and lin["mesh_stiffness_N_mm"] > 0.0
    assert doc["checks"][0]["name"] == "resonance_margin_percent"


def test_alpha15_document_says_no_single_pair_zone():
    doc = modal_document(run_modal(ISO_PAIR, ALPHA_15)).to_dict()
    assert doc["linearisation"]["single_pair_stiffness_N_mm"] is None
