"""`gearcli schema` in the case file's units (issue 19): defaults and limits as a user writes
them (20 deg, not 0.349 rad), and the study file's schema."""

from __future__ import annotations

import json

from typer.testing import CliRunner

from gearcli.case.schema_text import generate
from gearcli.cli import app

runner = CliRunner()


def test_defaults_and_limits_are_in_the_default_units():
    defs = json.loads(generate())["$defs"]
    pa = defs["Gears"]["properties"]["pressure_angle"]
    assert pa["default"] == 20.0 and "[deg]" in pa["description"]
    assert (pa["exclusiveMinimum"], pa["exclusiveMaximum"]) == (0.0, 45.0)
    rho = defs["Material"]["properties"]["density"]
    assert rho["default"] == 7.85e-06 and "[kg/mm^3]" in rho["description"]
    assert rho["exclusiveMinimum"] == 0.0


def test_a_time_function_default_is_written_as_a_case_file_writes_it():
    """Issue 29: the default of load.torque was the internal TimeFunction object."""
    torque = json.loads(generate())["$defs"]["Load"]["properties"]["torque"]
    assert torque["default"] == 0.0 and "[N*mm]" in torque["description"]


def test_study_schema():
    res = runner.invoke(app, ["schema", "--study"])
    assert res.exit_code == 0
    schema = json.loads(res.output)
    assert "speed_curve" in schema["properties"]["design"]["enum"]
    assert "parameters" in schema["required"]
