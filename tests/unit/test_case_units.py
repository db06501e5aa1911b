"""Declared units (issue 29): `units: adams | engineering | si` sets what bare numbers mean;
strings with units mean what they say; without the key a case keeps its meaning."""

import json
import math
import subprocess
import sys

import pytest
from typer.testing import CliRunner

from gearcli import units
from gearcli.case.load import load_case_text
from gearcli.cli import app
from gearcli.errors import CaseError

runner = CliRunner()
STEP = "STEP(time, 0, 0, 1, 3000)"


def _declared(seed_text: str, system: str | None, **edits: str) -> str:
    text = seed_text
    for old, new in edits.values():
        assert old in text
        text = text.replace(old, new, 1)
    return (f"units: {system}\n" if system else "") + text


@pytest.mark.parametrize("system", ["engineering", "si"])
def test_each_system_factor_is_pints(system):
    """Bit for bit: a bare number in a declared system equals the string with its unit as pint
    converts it in an undeclared case."""
    dims = {d.name: d for d in vars(units).values() if isinstance(d, units.Dim)}
    for name, (unit, factor) in units.UNIT_SYSTEMS[system].items():
        pint_factor = units.registry().Quantity(1.0, unit).to(dims[name].internal).magnitude
        assert factor == pint_factor, (name, unit)
        for x in (1500.0, 0.349, 7850.0, 2.07e11, 1e-5):
            assert units.parse_quantity(x, units.in_system(dims[name], system)) == \
                units.parse_quantity(f"{x!r} {unit}", dims[name]), (name, x)


def test_engineering_speed_is_rpm_and_torque_n_m(seed_text):
    text = _declared(seed_text, "engineering", speed=(STEP, "1500"),
                     torque=("STEP(time, 0, 0, 1, 4.5e+05)", "450"),
                     density=("7.85e-6 ", "7850 "))
    case = load_case_text(text, "c.yaml").case
    assert case.units == "engineering"
    assert case.drive.speed.pp(2.0) == units.parse_quantity("1500 rpm", units.ANGULAR_VELOCITY)
    assert case.drive.speed.pp(2.0) * 30.0 / math.pi == pytest.approx(1500.0, rel=1e-15)
    assert case.load.torque.pp(2.0) == 4.5e5  # N*mm
    assert case.material.density == pytest.approx(7.85e-9, rel=1e-15)  # t/mm^3
    assert case.gears.module == 10.0 and case.gears.pressure_angle == math.radians(20)


def test_without_units_a_bare_speed_stays_deg_per_s(seed_text):
    case = load_case_text(seed_text.replace(STEP, "1500"), "c.yaml").case
    assert case.units is None
    assert case.drive.speed.pp(2.0) == pytest.approx(math.radians(1500), rel=1e-15)  # 250 rpm


def test_adams_is_the_default_spelled_out(seed_text):
    plain = load_case_text(seed_text, "c.yaml").case
    adams = load_case_text(_declared(seed_text, "adams"), "c.yaml").case
    dump = json.loads(plain.model_dump_json())
    assert "units" not in dump  # an undeclared case's resolved dump is as before
    assert {**json.loads(adams.model_dump_json()), "units": None} == {**dump, "units": None}


def test_si_lengths_are_metres_and_strings_mean_what_they_say(seed_text):
    text = _declared(seed_text, "si", module=("  module: 10 ", "  module: 0.01 "),
                     face=("  face_width: 100 ", '  face_width: "100 mm" '),
                     angle=("  pressure_angle: 20 ", "  pressure_angle: 0.3490658503988659 "),
                     speed=(STEP, "STEP(time, 0, 0, 1, 52.35987755982988)"),
                     density=("7.85e-6 ", "7850 "),
                     stiction=("stiction_velocity: 0.01 ", "stiction_velocity: 1e-5 "),
                     transition=("transition_velocity: 0.10 ", "transition_velocity: 1e-4 "),
                     torque=("STEP(time, 0, 0, 1, 4.5e+05)", "STEP(time, 0, 0, 1, 450)"),
                     max_damping=("  max_damping: 100 ", "  max_damping: 1e5 "),
                     depth=("  penetration_depth: 0.1 ", "  penetration_depth: 1e-4 "))
    si = load_case_text(text, "c.yaml").case
    seed = load_case_text(seed_text, "c.yaml").case
    assert si.gears.module == 10.0 and si.gears.face_width == 100.0
    assert si.gears.pressure_angle == pytest.approx(seed.gears.pressure_angle, rel=1e-15)
    assert si.material.youngs_modulus == 2.07e5  # MPa in every system
    assert si.drive.speed.pp(2.0) == pytest.approx(seed.drive.speed.pp(2.0), rel=1e-15)
    assert si.load.torque.pp(2.0) == pytest.approx(4.5e5, rel=1e-15)
    assert si.contact.max_damping == pytest.approx(100.0, rel=1e-15)
    assert si.contact.stiffness == seed.contact.stiffness  # N/mm^e in every system


def test_resolved_case_of_a_declared_system_loads_to_the_same_values(seed_text):
    import yaml

    text = _declared(seed_text, "engineering", speed=(STEP, "STEP(time, 0, 0, 1, 1500)"),
                     density=("7.85e-6 ", "7850 "))
    case = load_case_text(text, "c.yaml").case
    dump = json.loads(case.model_dump_json())
    assert dump["units"] == "engineering"
    assert dump["drive"]["speed"] == {"function": "STEP(time, 0, 0, 1, 1500)", "unit": "rpm"}
    again = load_case_text(yaml.safe_dump(dump), "r.yaml").case
    assert again == case
    dump.pop("units")  # the values carry their units: read as adams, they are the same
    assert json.loads(load_case_text(yaml.safe_dump(dump), "r.yaml").case.model_dump_json()) \
        == {k: v for k, v in json.loads(case.model_dump_json()).items() if k != "units"}


def test_unknown_units_is_one_line_naming_the_allowed_ones(seed_text, write_case):
    path = write_case(_declared(seed_text, "imperial"))
    res = runner.invoke(app, ["geometry", str(path)])
    assert res.exit_code == 1
    first = res.stderr.splitlines()[0]
    assert first == (f"error: {path}:1: units: got 'imperial'; expected 'adams', "
                     "'engineering' or 'si'"), first


def test_limits_are_shown_in_the_declared_units(seed_text):
    text = _declared(seed_text, "si", module=("  module: 10 ", "  module: -0.01 "))
    with pytest.raises(CaseError, match=r"(?m)gears.module: got -0.01; expected > 0 m$"):
        load_case_text(text.replace("  pressure_angle: 20 ", "  pressure_angle: 0.35 "),
                       "c.yaml")


def test_override_can_declare_units(seed_text, write_case):
    from gearcli.case.load import load_case

    path = write_case(seed_text.replace(STEP, "1500").replace("7.85e-6 ", "7850 "))
    case = load_case(path, ["units=engineering"]).case
    assert case.drive.speed.pp(2.0) == pytest.approx(1500 * math.pi / 30, rel=1e-15)


def test_an_engineering_case_loads_without_pint(seed_text, tmp_path):
    """rpm and N*m as bare numbers use the system's exact factors: no pint import (~0.6 s)."""
    path = tmp_path / "c.yaml"
    path.write_text(_declared(seed_text, "engineering", speed=(STEP, "STEP(time,0,0,1,1500)"),
                              torque=("STEP(time, 0, 0, 1, 4.5e+05)", "450"),
                              density=("7.85e-6 ", "7850 ")))
    code = ("import sys; from gearcli.case.load import load_case; c = load_case(sys.argv[1]); "
            "c.case.drive.speed.pp; c.case.load.torque.pp; print('pint' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code, str(path)], capture_output=True,
                         text=True, check=True)
    assert out.stdout.strip() == "False"
