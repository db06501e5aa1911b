"""`gearcli mesh` with faults: the faulted stiffness and STE over one pinion revolution
(pipeline/mesh_faults.py; docs/theory.md "Tooth faults", "The faulted revolution in `gearcli
mesh`"), and `modal`'s note that it uses the healthy mean stiffness.

Case: cases/iso_pair.yaml (tooth law, no relief, 21/43 teeth, ε_α 1.57), F = 2970 N.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from gearcli.case.load import load_case
from gearcli.cli import app
from gearcli.pipeline.capabilities import not_included
from gearcli.pipeline.mesh import run_mesh
from tests.conftest import ROOT

ISO = ROOT / "cases" / "iso_pair.yaml"
CRACK = "faults=[{kind: root_crack, gear: pinion, tooth: 2, depth: 4 mm, angle: 45 deg}]"
MISSING = "faults=[{kind: missing_tooth, gear: pinion, tooth: 3}]"


@pytest.fixture(scope="module")
def crack():
    return run_mesh(load_case(ISO, [CRACK]))


def test_the_revolution_covers_one_pinion_revolution_from_t0(crack):
    r, g = crack.revolution, crack.geometry.geometry
    step = r.s1_mm[1] - r.s1_mm[0]
    assert r.s1_mm[0] == 0.0
    assert r.s1_mm[-1] + step == pytest.approx(g.pinion.teeth * g.p_b_mm, rel=1e-12)


def test_healthy_ste_is_the_loaded_mesh_at_the_same_phase(crack):
    """Without relief, with linear pairs touching at zero gap, δ = F / Σ k: the loaded STE of
    `mesh` mapped onto the revolution's phase matches F / k_healthy(s1) to 1e-5 on 85 % of
    the revolution (measured 3e-6 median; the rest is near the contact changes, where the
    loaded contact's extended engagement carries and the rigid-kinematics sum does not)."""
    r = crack.revolution
    approx = crack.loaded.force_N / r.k_healthy_N_mm
    close = np.abs(r.ste_healthy_mm - approx) / approx < 1e-5
    assert close.mean() > 0.85
    # the phase is right: shifted by a tenth of a pitch the match is lost
    shifted = np.roll(r.ste_healthy_mm, r.s1_mm.size // (10 * 21))
    assert (np.abs(shifted - approx) / approx < 1e-5).mean() < 0.5


def test_crack_lowers_stiffness_only_around_its_tooth(crack):
    r, g = crack.revolution, crack.geometry.geometry
    s = crack.summary.faulted_revolution
    assert s.faults == ("root_crack pinion tooth 2",)
    # docs/theory.md "Tooth faults": iso_pair q = 4 mm, 45°: 6.5 % largest reduction (7.1 %
    # with the linear Hertz term: Weber's softer contact term, §4b, dilutes the crack's bending
    # compliance in the pair's total)
    assert s.stiffness_largest_drop == pytest.approx(0.065, abs=0.001)
    drop = r.k_faulted_N_mm < r.k_healthy_N_mm * (1 - 1e-12)
    pitches = r.s1_mm[drop] / g.p_b_mm
    # tooth 2 is on the path from its entry at A to its exit at E: within ε_α pitches around
    # its pitch-point passage at 2 p_b
    assert pitches.min() > 2 - g.eps_alpha and pitches.max() < 2 + g.eps_alpha
    assert np.all(r.ste_faulted_mm[drop] > r.ste_healthy_mm[drop])
    np.testing.assert_array_equal(r.ste_faulted_mm[~drop], r.ste_healthy_mm[~drop])


def test_missing_tooth_has_no_carrying_pair_over_2_minus_eps():
    res = run_mesh(load_case(ISO, [MISSING]))
    s, g = res.summary.faulted_revolution, res.geometry.geometry
    # (2 − ε_α) p_b of the z1 p_b revolution; the grid is p_b/200
    assert s.no_contact_share == pytest.approx((2 - g.eps_alpha) / g.pinion.teeth,
                                               abs=1.0 / (200 * g.pinion.teeth))
    assert s.stiffness_largest_drop == 1.0 and s.stiffness_min_N_mm == 0.0
    assert np.isnan(res.revolution.ste_faulted_mm).any()


def test_healthy_case_has_no_revolution_and_the_cli_writes_it_with_faults(tmp_path):
    plain = run_mesh(load_case(ISO))
    assert plain.revolution is None and "faulted_revolution" not in plain.document()
    out = tmp_path / "m"
    res = CliRunner().invoke(app, ["mesh", str(ISO), "--set", CRACK, "-o", str(out), "-q"])
    assert res.exit_code == 0, res.output
    doc = json.loads((out / "mesh.json").read_text())
    assert doc["faulted_revolution"]["points"] == 21 * 200
    assert (out / "mesh_faults.png").is_file()
    header = (out / "mesh_faults.csv").read_text().splitlines()[0]
    assert header.startswith("roll_s1_mm,mesh_stiffness_faulted_N_mm")


def test_modal_and_mesh_say_what_they_use():
    case = load_case(ISO, [CRACK]).case
    modal = [n for n in not_included("modal", case) if n.startswith("tooth faults")]
    assert modal and "healthy pair's mean mesh stiffness" in modal[0]
    mesh = [n for n in not_included("mesh", case) if n.startswith("tooth faults")]
    assert "faulted mesh stiffness and STE over one pinion revolution" in mesh[0]
