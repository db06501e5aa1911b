"""Issue 29, "every axis ... in display units": a sweep's trend table and figures follow the
display units (``gearcli --units``, ``gearcli.sweep(units=...)``), and a study over a case
that declares ``units:`` labels its parameters in that case's units, not in Adams units."""

from __future__ import annotations

import math

import pytest
import yaml
from typer.testing import CliRunner

import gearcli
from gearcli.cli import app
from gearcli.data import __file__ as _data_init
from gearcli.errors import CaseError
from gearcli.pipeline.sweep.study import load_study_text
from tests.unit.sweep_helpers import write_study

PAIR = yaml.safe_load((__import__("pathlib").Path(_data_init).parent / "pair.yaml").read_text())


def _over_pair(parameters: str, design: str = "grid"):
    """A study whose inline base is the pair template (``units: engineering``)."""
    text = yaml.safe_dump({"base": PAIR, "design": design}, sort_keys=False)
    return load_study_text(text + f"parameters:\n{parameters}", "t.yaml")


def test_bare_numbers_of_an_engineering_case_are_labelled_in_its_units():
    """The pair template says ``units: engineering``: a bare drive speed is rpm (the Adams
    default would label it deg/s, a factor 6 off), in a list and in a range alike."""
    s = _over_pair("  drive.speed: [1000, 1500]\n  load.torque: {linspace: [400, 600], num: 3}\n")
    assert s.parameter_columns == ["drive.speed [rpm]", "load.torque [N*m]"]
    assert [p.values["drive.speed [rpm]"] for p in s.points[::3]] == [1000.0, 1500.0]
    assert [p.values["load.torque [N*m]"] for p in s.points[:3]] == [400.0, 500.0, 600.0]
    # the seed (no units:, Adams defaults) keeps deg/s and N*mm
    seed = load_study_text(f"base: {gearcli.__path__[0]}/../cases/seed.yaml\n"
                           "parameters:\n  drive.speed: [3000]\n", "s.yaml")
    assert seed.parameter_columns == ["drive.speed [deg/s]"]


def test_the_base_value_of_a_bare_number_is_read_in_the_case_units():
    """one_at_a_time: an unvaried parameter's column holds the base case's value converted to
    the parameter's unit; the pair's bare ``load.torque`` final 500 is N·m, not N·mm."""
    base = dict(PAIR, load={"applied_to": "gear", "torque": 500})
    text = yaml.safe_dump({"base": base, "design": "one_at_a_time"}, sort_keys=False)
    s = load_study_text(text + 'parameters:\n  load.torque: ["400000 N*mm"]\n'
                        "  gears.module: [4]\n", "t.yaml")
    assert s.points[0].values["load.torque [N*mm]"] == pytest.approx(500_000.0)


@pytest.mark.parametrize("units, dte", [("si", "DTE, peak to peak [m]"),
                                        ("engineering", "DTE, peak to peak [µm]")])
def test_sweep_trends_follow_the_display_units(tmp_path, units, dte):
    """`gearcli --units si sweep` writes trends.md (and the figures, from the same labels:
    trends.metric_axis) in SI; the default engineering units give µm. One short point."""
    path = write_study(tmp_path, 'parameters:\n  gears.face_width: ["100 mm"]\n')
    out = tmp_path / "out"
    res = CliRunner().invoke(app, ["--units", units, "sweep", str(path), "-o", str(out),
                                   "-j", "1", "-q"])
    assert res.exit_code == 0, res.output
    text = (out / "trends.md").read_text()
    assert dte in text
    other = "DTE, peak to peak [µm]" if units == "si" else "DTE, peak to peak [m]"
    assert other not in text


def test_api_sweep_refuses_unknown_units(tmp_path):
    path = write_study(tmp_path, 'parameters:\n  gears.face_width: ["100 mm"]\n')
    with pytest.raises(CaseError, match="expected one of engineering, si"):
        gearcli.sweep(path, units="imperial")
    assert math.isfinite(1.0)


def test_time_functions_written_as_mappings_keep_an_unlabelled_column():
    """Values that are not numbers (a time function as a mapping with its own unit) give no
    unit to the column: it would name a unit the values are not in."""
    s = _over_pair('  load.torque:\n    - {function: "STEP(time, 0, 0, 0.1, 400)", unit: N*m}\n')
    assert s.parameter_columns == ["load.torque"]
