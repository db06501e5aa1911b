"""Which command models which feature: one table (gearcli/pipeline/capabilities.py), and every
command's "not included" note made from it."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from gearcli.case.load import load_case
from gearcli.pipeline.capabilities import FEATURES, MODELLED, not_included, used_features
from tests.conftest import ROOT

PKG = Path(__file__).resolve().parents[2] / "gearcli"
ISO = ROOT / "cases" / "iso_pair.yaml"
FAULT = "faults=[{kind: missing_tooth, gear: pinion, tooth: 3}]"
PITCH = "errors.pitch_deviation.gear={iso1328_grade: 6, seed: 1}"
RELIEF = "modifications.tip_relief.pinion={amount: 0.02 mm, length: 5 mm}"


def _case(*overrides):
    """iso_pair without friction (it has friction on), plus ``overrides``."""
    return load_case(ISO, ["friction.enabled=false", *overrides]).case


def test_every_command_names_only_known_features():
    names = {f.name for f in FEATURES}
    assert len(names) == len(FEATURES)
    for command, have in MODELLED.items():
        assert have <= names, command
    assert MODELLED["simulate"] == names  # the time-domain model includes everything


@pytest.mark.parametrize("overrides, used", [
    ((), set()),
    (("friction.enabled=true",), {"friction"}),
    ((PITCH,), {"runout_pitch"}),
    ((FAULT,), {"faults"}),
    ((FAULT, PITCH, "friction.enabled=true"), {"faults", "runout_pitch", "friction"}),
])
def test_used_features_follow_the_case(overrides, used):
    assert {f.name for f in used_features(_case(*overrides))} == used


def test_notes_are_the_features_a_command_leaves_out():
    case = _case(FAULT, PITCH, "friction.enabled=true")
    assert not_included("simulate", case) == []
    mesh = not_included("mesh", case)
    assert any(n.startswith("tooth faults are not included") for n in mesh)
    assert any(n.startswith("runout, pitch and profile slope deviations are not included")
               for n in mesh)
    assert any(n.startswith("friction is not included") for n in mesh)
    assert len(not_included("modal", case)) == 3


def test_relief_is_modelled_by_mesh_but_named_for_no_command_that_leaves_it_out():
    case = _case(RELIEF)
    assert "relief" in {f.name for f in used_features(case)}
    for command in ("simulate", "mesh", "modal", "rate"):
        assert not any("relief" in n for n in not_included(command, case)), command


def test_the_mesh_analysis_carries_the_generated_notes():
    from gearcli.pipeline.mesh import run_mesh

    loaded = load_case(ISO, [FAULT])
    res = run_mesh(loaded, cycles=1, points_per_cycle=40)
    assert list(res.notes[:len(not_included("mesh", loaded.case))]) == \
        not_included("mesh", loaded.case)
    assert any("tooth faults" in n for n in res.notes)


def test_no_command_writes_its_own_not_included_note():
    """The phrase lives in the table's module only (a hand-written note elsewhere would drift
    from the table)."""
    pattern = re.compile(r"not included")
    offenders = [str(p.relative_to(PKG)) for p in PKG.rglob("*.py")
                 if p.name != "capabilities.py" and pattern.search(p.read_text())]
    assert offenders == []
