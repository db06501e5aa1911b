"""Case-file errors (issues 27, 29): all errors of a file at once, one line each, every line
naming the key the user wrote, the value and what is allowed; one message construction."""

import re

import pytest
from typer.testing import CliRunner

from gearcli.case.load import CaseErrors, load_case_text
from gearcli.case.section import FieldError, compose, pair
from gearcli.cli import app
from gearcli.errors import CaseError

runner = CliRunner()

THREE = [("  module: 10 ", "  module: -1 "), ("    teeth: 17 ", "    teeth: 2 "),
         ("  end_time: 5 ", "  end_time: 5\n  rtol: 0.5 ")]


def _edit(text: str, edits) -> str:
    for old, new in edits:
        assert old in text, f"test set-up: {old!r} not in the seed case"
        text = text.replace(old, new, 1)
    return text


def test_three_errors_are_reported_at_once_one_line_each(seed_text, write_case):
    path = write_case(_edit(seed_text, THREE))
    res = runner.invoke(app, ["geometry", str(path)])
    assert res.exit_code == 1
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 3, res.stderr
    assert lines[0].startswith("error: ")
    expected = [("gears.module", "got -1", "> 0 mm"), ("gears.pinion.teeth", "got 2", ">= 3"),
                ("run.rtol", "got 0.5", "< 0.01")]
    for line, (key, got, allowed) in zip(lines, expected, strict=True):
        m = re.match(rf"(error: )?{re.escape(str(path))}:(\d+): {re.escape(key)}: ", line)
        assert m, line
        assert key.split(".")[-1] in _edit(seed_text, THREE).splitlines()[int(m[2]) - 1]
        assert got in line and f"expected {allowed}" in line
    assert "more error" not in res.stderr


def test_the_error_object_holds_every_error():
    text = _edit(open("cases/seed.yaml").read(), THREE)
    with pytest.raises(CaseErrors) as err:
        load_case_text(text, "c.yaml")
    assert [e.path for e in err.value.errors] == ["gears.module", "gears.pinion.teeth",
                                                  "run.rtol"]
    assert isinstance(err.value, CaseError) and err.value.path == "gears.module"  # the first


def test_a_typo_is_not_also_reported_as_a_missing_key(seed_text):
    text = _edit(seed_text, [("  face_width: 100 ", "  face_widht: 100 ")])
    with pytest.raises(CaseError) as err:
        load_case_text(text, "c.yaml")
    assert not isinstance(err.value, CaseErrors), str(err.value)
    assert "gears.face_widht: got 100; unknown key (did you mean 'face_width'?)" in str(err.value)


# (edit, key, the value as shown or None, a fragment of what is allowed)
BAD = [
    (("  module: 10 ", '  module: "10 kg" '), "gears.module", "'10 kg'", "a length"),
    (("  module: 10 ", '  module: "mm" '), "gears.module", "'mm'", "a number with units"),
    (("  law: impact ", "  law: hertz "), "contact.law", "'hertz'", "'tooth' or 'impact'"),
    (("  stiction_velocity: 0.01 ", "  stiction_velocity: 1 "), "friction.stiction_velocity",
     "1", "stiction_velocity < transition_velocity"),
    (("STEP(time, 0, 0, 1, 3000)", "STEP(time, 0, 0, 1)"), "drive.speed",
     "'STEP(time, 0, 0, 1)'", "an expression of time"),
    (("STEP(time, 0, 0, 1, 3000)", '"100 Hz"'), "drive.speed", "'100 Hz'", "rev/s, rpm"),
    (("STEP(time, 0, 0, 1, 3000)", "{functio: 3}"), "drive.speed", "{'functio': 3}",
     "a mapping with keys 'function'"),
    (("  module: 10 ", "  # module: 10 "), "gears.module", None, "module m [mm]"),
    (("gears:  ", "gearz:  "), "gearz", None, "one of: units, name"),
    (("  end_time: 5 ", "  end_time: 5\n  output_steps: 100\n  output_rate: 1000 "),
     "run.output_rate", "1000", "at most one of them"),
    (("  poisson_ratio: 0.29", "  poisson_ratio: 0.7"), "material.poisson_ratio", "0.7",
     "< 0.5"),
]


@pytest.mark.parametrize("edit, key, value, allowed", BAD, ids=[b[1] + str(i)
                                                               for i, b in enumerate(BAD)])
def test_each_error_names_key_value_and_what_is_allowed(seed_text, edit, key, value, allowed):
    with pytest.raises(CaseError) as err:
        load_case_text(_edit(seed_text, [edit]), "c.yaml")
    first = str(err.value).splitlines()[0]
    assert first.startswith("c.yaml:") and f": {key}: " in first, first
    if value is not None:
        assert f"{key}: got {value}; " in first, first
    assert "expected " in first and allowed in first.split("expected", 1)[1], first
    assert "expected:" not in first and "more error" not in first


def test_errors_of_one_validator_are_all_reported(seed_text):
    """A pitch list of the wrong length on both gears: two lines, each with its own count."""
    extra = ("errors:\n  pitch_deviation:\n    pinion: {values: [0.001]}\n"
             "    gear: {values: [0.001, 0.002]}\n")
    with pytest.raises(CaseErrors) as err:
        load_case_text(seed_text + extra, "c.yaml")
    lines = str(err.value).splitlines()
    assert len(lines) == 2
    assert lines[0].endswith("pinion.values: got [0.001]; 1 entries; expected one per tooth of "
                             "the pinion (gears.pinion.teeth: 17)")
    assert "gear.values: got [0.001, 0.002]; 2 entries; expected one per tooth of the gear " \
        "(gears.gear.teeth: 25)" in lines[1]


def test_compose_is_the_one_wording():
    assert compose("2 entries", "one per tooth") == "2 entries; expected one per tooth"
    assert compose("", "> 0 mm") == "expected > 0 mm"
    assert compose("missing") == "missing"
    assert str(FieldError(("a",), "both given", "one")) == "both given; expected one"


def test_pair_is_one_class_per_entry_named_as_before():
    from gearcli.case.schema import Errors, Modifications, PitchDeviation, Relief

    assert pair(Relief) is pair(Relief)
    assert Modifications.model_fields["tip_relief"].annotation is pair(Relief)
    assert Errors.model_fields["pitch_deviation"].annotation is pair(PitchDeviation)
    names = {pair(Relief).__name__, pair(PitchDeviation).__name__}
    assert names == {"ReliefPair", "PitchPair"}


def test_a_radian_pressure_angle_is_blamed_on_the_pressure_angle(seed_text, write_case):
    """Issue 29: `pressure_angle: 0.349` (radians meant) was blamed on gears.pinion.teeth
    with |T1A| = -49.7 mm."""
    path = write_case(_edit(seed_text, [("  pressure_angle: 20 ", "  pressure_angle: 0.349 ")]))
    res = runner.invoke(app, ["geometry", str(path)])
    assert res.exit_code == 1
    first = res.stderr.splitlines()[0]
    assert f"{path}:" in first and ": gears.pressure_angle: got 0.349; " in first, first
    assert "0.349 rad" in first and "20 deg" in first


def test_a_usual_pressure_angle_keeps_the_teeth_as_the_cause(seed_text, write_case):
    path = write_case(_edit(seed_text, [("    teeth: 17 ", "    teeth: 8 ")]))
    res = runner.invoke(app, ["geometry", str(path)])
    assert res.exit_code == 1
    assert ": gears.pinion.teeth: got 8; " in res.stderr.splitlines()[0]
