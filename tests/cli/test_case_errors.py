"""Every bad-input case: exit code 1, one message line naming file, line and key path."""

import re

import pytest
from typer.testing import CliRunner

from gearcli.cli import app

runner = CliRunner()

# (id, (pattern, replacement) applied to the seed text, expected key path, expected line text,
#  a fragment of the message)
CASES = [
    (
        "unknown_key",
        ("  face_width: 100 ", "  face_widht: 100 "),
        "gears.face_widht",
        "face_widht",
        "did you mean 'face_width'",
    ),
    (
        "missing_required",
        ("  module: 10 ", "  # module: 10 "),
        "gears.module",
        "gears:",
        "missing required key",
    ),
    (
        "wrong_type",
        ("    teeth: 17 ", "    teeth: seventeen "),
        "gears.pinion.teeth",
        "teeth",
        "integer",
    ),
    (
        "non_finite",
        ("  face_width: 100 ", "  face_width: .inf "),
        "gears.face_width",
        "face_width",
        "finite",
    ),
    ("zero_teeth", ("    teeth: 17 ", "    teeth: 0 "), "gears.pinion.teeth", "teeth: 0", ">= 3"),
    (
        "negative_teeth",
        ("    teeth: 25 ", "    teeth: -25 "),
        "gears.gear.teeth",
        "teeth: -25",
        ">= 3",
    ),
    (
        "non_integer_teeth",
        ("    teeth: 17 ", "    teeth: 17.5 "),
        "gears.pinion.teeth",
        "17.5",
        "integer",
    ),
    ("module_zero", ("  module: 10 ", "  module: 0 "), "gears.module", "module: 0", "> 0 mm"),
    (
        "module_negative",
        ("  module: 10 ", "  module: -10 "),
        "gears.module",
        "module: -10",
        "> 0 mm",
    ),
    (
        "pressure_angle_high",
        ("  pressure_angle: 20 ", "  pressure_angle: 50 "),
        "gears.pressure_angle",
        "pressure_angle: 50",
        "< 45 deg",
    ),
    (
        "pressure_angle_zero",
        ("  pressure_angle: 20 ", "  pressure_angle: 0 "),
        "gears.pressure_angle",
        "pressure_angle: 0",
        "> 0 deg",
    ),
    (
        "wrong_dimension",
        ("STEP(time, 0, 0, 1, 4.5e+05)", '"450 N"'),
        "load.torque",
        "450 N",
        "not a torque",
    ),
    (
        "unparseable_unit",
        ("  module: 10 ", '  module: "10 furlongz" '),
        "gears.module",
        "furlongz",
        "cannot parse units",
    ),
    (
        "malformed_step",
        ("STEP(time, 0, 0, 1, 3000)", "STEP(time, 0, 0, 1)"),
        "drive.speed",
        "STEP(time, 0, 0, 1)",
        "malformed expression",
    ),
    (
        "step_bad_name",
        ("STEP(time, 0, 0, 1, 3000)", "STEPP(time, 0, 0, 1, 3000)"),
        "drive.speed",
        "STEPP",
        "malformed expression",
    ),
    (
        "load_on_motion_pinion",
        ("  applied_to: gear ", "  applied_to: pinion "),
        "load.applied_to",
        "applied_to: pinion",
        "never reaches the mesh",
    ),
    (
        "centre_distance_too_small",
        ("    teeth: 25 ", "    teeth: 25\n  centre_distance: 205 "),
        "gears.centre_distance",
        "centre_distance: 205",
        "centre distance",
    ),
    (
        "contact_ratio_below_one",
        ("    teeth: 25 ", "    teeth: 25\n  centre_distance: 222 "),
        "gears.centre_distance",
        "centre_distance: 222",
        "contact ratio",
    ),
    (
        "interference",
        ("    teeth: 17 ", "    teeth: 8 "),
        "gears.pinion.teeth",
        "teeth: 8",
        "interference",
    ),
]


@pytest.mark.parametrize("cid, edit, path, line_text, fragment", CASES, ids=[c[0] for c in CASES])
def test_bad_case(cid, edit, path, line_text, fragment, seed_text, write_case):
    pattern, repl = edit
    assert pattern in seed_text, f"test set-up: {pattern!r} not in the seed case"
    text = seed_text.replace(pattern, repl, 1)
    case = write_case(text)
    result = runner.invoke(app, ["geometry", str(case)])
    assert result.exit_code == 1, result.output
    first = result.stderr.splitlines()[0]
    m = re.match(rf"error: {re.escape(str(case))}:(\d+): {re.escape(path)}: ", first)
    assert m, first
    line_no = int(m.group(1))
    assert line_text in text.splitlines()[line_no - 1], (first, text.splitlines()[line_no - 1])
    assert fragment in first
    assert "Traceback" not in result.output


@pytest.mark.parametrize(
    "content, fragment",
    [
        (None, "file not found"),
        ("", "file is empty"),
        ("gears: [1, 2\n", "invalid YAML"),
        ("- 1\n- 2\n", "expected a mapping"),
        ("just a string\n", "expected a mapping"),
        ("gears: {}\ngears: {}\n", "duplicate key"),
    ],
)
def test_bad_file(content, fragment, tmp_path):
    p = tmp_path / "c.yaml"
    if content is not None:
        p.write_text(content)
    result = runner.invoke(app, ["geometry", str(p)])
    assert result.exit_code == 1
    assert result.stderr.startswith(f"error: {p}")
    assert fragment in result.stderr.splitlines()[0]


def test_directory_instead_of_file(tmp_path):
    result = runner.invoke(app, ["geometry", str(tmp_path)])
    assert result.exit_code == 1
    assert "is a directory" in result.stderr


def test_missing_section_required_by_a_set_option_names_the_option(seed_text, write_case):
    """A key that nothing in the file locates (the seed has no `bearings` section) is reported
    without a misleading source line, with the --set options the file was checked with."""
    path = write_case(seed_text)
    res = runner.invoke(app, ["simulate", str(path), "-o", "-", "--set",
                              "model=lateral-torsional"])
    assert res.exit_code == 1
    lines = res.output.strip().splitlines()
    keys = [f"bearings.{gear}.stiffness_{axis}" for gear in ("pinion", "gear") for axis in "xy"]
    assert len(lines) == len(keys), res.output  # every missing key, one line each
    for i, (line, key) in enumerate(zip(lines, keys, strict=True)):
        assert line.startswith(("error: " if i == 0 else "")
                               + f"{path} with --set model=lateral-torsional: {key}: missing;")
