"""Input slips of issue 32: a frequency given as a shaft speed (pint counts a revolution as
2π rad, so "60000 rpm" read as a frequency is 6283 Hz, not 1000 Hz), a speed given as a bare
rate ("3000 1/min" read as 50 rad/s instead of 314), and YAML booleans where numbers are
expected (pydantic's lax float reads ``true`` as 1.0)."""

import math
from pathlib import Path

import pytest

from gearcli import units
from gearcli.case.load import load_case
from gearcli.errors import CaseError
from gearcli.pipeline.sweep.study import load_study
from tests.unit.sweep_helpers import write_study

SEED = Path(__file__).resolve().parents[2] / "cases" / "seed.yaml"


def _error(overrides: list[str]) -> str:
    with pytest.raises(CaseError) as info:
        load_case(SEED, overrides)
    return str(info.value)


# --- frequencies ------------------------------------------------------------------------------


def test_output_rate_in_rpm_is_refused_with_the_conversion_shown():
    msg = _error(["run.output_rate=60000 rpm"])
    assert "run.output_rate: got '60000 rpm'; a frequency, not a speed: write '1000 Hz' " \
        "(60000/min)" in msg
    assert "\n" not in msg.split("run.output_rate", 1)[1].split("\n", 1)[0]


@pytest.mark.parametrize(("text", "hz"), [("100 rev/s", 100.0), ("6000 rev/min", 100.0),
                                          ("36000 deg/s", 100.0), ("100 turn/s", 100.0)])
def test_every_angle_per_time_is_refused_for_a_frequency(text, hz):
    with pytest.raises(units.UnitError, match=f"write '{hz:g} Hz'"):
        units.parse_quantity(text, units.FREQUENCY)


def test_hz_per_second_and_per_minute_are_the_same_frequency():
    # exact: 1/s and Hz are one unit in pint, and 60000/60 is exact in binary floating point
    values = [units.parse_quantity(t, units.FREQUENCY)
              for t in ("1000 Hz", "1 kHz", "1000 1/s", "60000 1/min", "60000/min", 1000)]
    assert values == [1000.0] * len(values)
    run = [load_case(SEED, [f"run.output_rate={t}"]).case.run.output_rate
           for t in ("1000 Hz", "1000 1/s", "60000 1/min")]
    assert run == [1000.0, 1000.0, 1000.0]


def test_rpm_is_accepted_for_a_shaft_speed():
    rad_s = units.parse_quantity("3000 rpm", units.ANGULAR_VELOCITY)
    assert rad_s == pytest.approx(3000 * 2 * math.pi / 60, rel=1e-15)
    assert units.parse_quantity("50 rev/s", units.ANGULAR_VELOCITY) == pytest.approx(rad_s,
                                                                                     rel=1e-15)
    case = load_case(SEED, ["drive.speed=3000 rpm"]).case
    assert case.drive.speed.pp(0.0) == pytest.approx(rad_s, rel=1e-15)


@pytest.mark.parametrize("text", ["3000 1/min", "50 1/s"])
def test_a_speed_without_an_angle_is_refused(text):
    msg = _error([f"drive.speed={text}"])
    assert f"drive.speed: got '{text}'" in msg
    assert "'3000 rpm' or '50 rev/s'" in msg


def test_study_mesh_frequency_in_rpm_is_refused(tmp_path):
    with pytest.raises(CaseError) as info:
        load_study(write_study(tmp_path, "parameters:\n  mesh_frequency: [\"3000 rpm\"]\n"))
    msg = str(info.value)
    assert "a frequency, not a speed: write '50 Hz' (3000/min)" in msg


def test_study_mesh_frequency_per_minute_equals_hz(tmp_path):
    a = load_study(write_study(tmp_path, "parameters:\n  mesh_frequency: [\"170 Hz\"]\n",
                               "a.yaml"))
    b = load_study(write_study(tmp_path, "parameters:\n  mesh_frequency: [\"10200 1/min\"]\n",
                               "b.yaml"))
    assert a.points[0].overrides == b.points[0].overrides


# --- YAML booleans ----------------------------------------------------------------------------


@pytest.mark.parametrize(("override", "key"), [
    ("contact.exponent=true", "contact.exponent"),
    ("contact.exponent=yes", "contact.exponent"),
    ("friction.static_coefficient=false", "friction.static_coefficient"),
    ("gears.pinion.profile_shift=true", "gears.pinion.profile_shift"),
    ("gears.pinion.teeth=true", "gears.pinion.teeth"),
    ("gears.module=false", "gears.module"),
    ("run.output_rate=true", "run.output_rate"),
    ("run.rtol=true", "run.rtol"),
])
def test_a_boolean_where_a_number_is_expected_is_refused(override, key):
    msg = _error([override])
    value = "True" if override.endswith(("true", "yes")) else "False"
    assert f"{key}: got {value}; " in msg
    assert "expected" in msg


def test_exponent_true_with_derived_stiffness_is_refused_not_made_linear():
    msg = _error(["contact.stiffness=derived", "contact.exponent=true"])
    assert "contact.exponent: got True; a YAML boolean, not a number" in msg


def test_numbers_still_load():
    case = load_case(SEED, ["contact.exponent=1", "friction.static_coefficient=0"]).case
    assert case.contact.exponent == 1.0
    assert case.friction.static_coefficient == 0.0


def test_speed_curve_study_in_rpm_is_refused(tmp_path):
    with pytest.raises(CaseError) as info:
        load_study(write_study(tmp_path, "design: speed_curve\nparameters:\n  mesh_frequency: "
                               "{linspace: [\"30000 rpm\", \"240000 rpm\"], num: 3}\n"))
    assert "a frequency, not a speed: write '500 Hz' (30000/min)" in str(info.value)


@pytest.mark.parametrize(("text", "dim"), [
    ("0;", units.FREQUENCY), ("5 mm", units.FREQUENCY), ("5 rad", units.FREQUENCY),
    ("0;", units.ANGULAR_VELOCITY), ("5 mm", units.ANGULAR_VELOCITY)])
def test_other_dimensions_keep_their_wrong_dimension_error(text, dim):
    """The angle check looks only at per-time units; anything else is pint's conversion's
    (the fuzz test found "0;" once raising a raw DimensionalityError here)."""
    with pytest.raises(units.UnitError, match="wrong dimension"):
        units.parse_quantity(text, dim)
