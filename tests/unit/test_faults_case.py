"""The case file's ``faults:`` list (gearcli/case/schema_faults.py, docs/theory.md "Tooth
faults"): units, the records it gives the model, located errors."""

import math

import pytest

from gearcli.case.load import load_case
from gearcli.case.schema_faults import fault_records
from gearcli.errors import CaseError
from gearcli.model.faults import ChippedTip, MissingTooth, RootCrack, Spall
from tests.conftest import ROOT

ISO = ROOT / "cases" / "iso_pair.yaml"


def test_faults_in_a_case_become_model_records_in_internal_units():
    case = load_case(ISO, [
        "faults=[{kind: root_crack, gear: pinion, tooth: 3, depth: 0.2 cm, angle: 30 deg, "
        "width: 0.5}, {kind: spall, gear: gear, tooth: 5, roll_angle: 25 deg, length: 3 mm, "
        "width: 0.5, depth: 10 um}, {kind: chipped_tip, gear: pinion, tooth: 0, height: 1 mm},"
        " {kind: missing_tooth, gear: gear, tooth: 42}]"]).case
    rec = fault_records(case.faults)
    assert isinstance(rec[0], RootCrack) and (rec[0].gear, rec[0].tooth) == ("pinion", 3)
    assert (rec[0].depth_mm, rec[0].angle_deg, rec[0].width) == pytest.approx((2.0, 30.0, 0.5))
    assert isinstance(rec[1], Spall) and rec[1].roll_angle_deg == pytest.approx(25.0)
    assert rec[1].depth_mm == pytest.approx(0.01) and rec[1].diameter_mm is None
    assert rec[2] == ChippedTip("pinion", 0, 1.0, 1.0)
    assert rec[3] == MissingTooth("gear", 42)
    assert load_case(ISO).case.faults == []
    crack = load_case(ISO, ["faults=[{kind: root_crack, gear: gear, tooth: 1, depth: 1}]"])
    assert crack.case.faults[0].angle == pytest.approx(math.radians(45.0))  # the default


@pytest.mark.parametrize("entry, match", [
    ("{kind: missing_tooth, gear: pinion, tooth: 21}", r"faults\.0\.tooth.*0 \.\.\. 20"),
    ("{kind: crack, gear: pinion, tooth: 2}", "root_crack"),
    ("{kind: spall, gear: gear, tooth: 1, length: 2, width: 0.5, depth: 0.01}", "exactly one"),
    ("{kind: chipped_tip, gear: gear, tooth: 1, height: 1, width: 1.5}", "width"),
    ("{kind: root_crack, gear: wheel, tooth: 1, depth: 1}", "gear"),
    ("{kind: root_crack, gear: gear, tooth: 1, depth: 1, angle: 100 deg}", "angle"),
])
def test_refused_fault_entries(entry, match):
    with pytest.raises(CaseError, match=match):
        load_case(ISO, [f"faults=[{entry}]"])
