"""Issue 32 input slips through the CLI: exit 1 before any solving, one message line naming
file, line, key and value, and what to write instead."""

import re

import pytest
from typer.testing import CliRunner

from gearcli.cli import app

runner = CliRunner()

# (id, (pattern, replacement) in the seed text, key path, the message after "got VALUE; ")
SLIPS = [
    ("output_rate_rpm", ("  end_time: 5 ", "  output_rate: 60000 rpm\n  end_time: 5 "),
     "run.output_rate", "got '60000 rpm'; a frequency, not a speed: write '1000 Hz' (60000/min)"),
    ("exponent_true", ("  exponent: 1.5", "  exponent: true"),
     "contact.exponent", "got True; a YAML boolean, not a number; expected a number"),
    ("teeth_true", ("    teeth: 17 ", "    teeth: true "),
     "gears.pinion.teeth", "got True; expected a valid integer"),
    ("module_false", ("  module: 10 ", "  module: false "),
     "gears.module", "got False; a YAML boolean, not a number; expected a length"),
]


@pytest.mark.parametrize("cid, edit, path, message", SLIPS, ids=[s[0] for s in SLIPS])
def test_slip_is_refused_in_one_line(cid, edit, path, message, seed_text, write_case, tmp_path):
    pattern, repl = edit
    assert pattern in seed_text, f"test set-up: {pattern!r} not in the seed case"
    case = write_case(seed_text.replace(pattern, repl, 1))
    out = tmp_path / "run"
    result = runner.invoke(app, ["simulate", str(case), "-o", str(out)])
    assert result.exit_code == 1, result.output
    lines = result.stderr.splitlines()
    assert re.match(rf"error: {re.escape(str(case))}:\d+: {re.escape(path)}: "
                    rf"{re.escape(message)}", lines[0]), lines[0]
    assert "Traceback" not in result.output
    assert not out.exists()  # refused before any work


@pytest.mark.parametrize("rate", ["1000 Hz", "1000 1/s", "60000 1/min"])
def test_output_rate_in_hz_per_second_or_per_minute_is_accepted(rate, seed_text, write_case):
    case = write_case(seed_text.replace("  end_time: 5 ", f"  output_rate: {rate}\n  end_time: 5 "))
    result = runner.invoke(app, ["geometry", str(case)])
    assert result.exit_code == 0, result.output


def test_shaft_speed_in_rpm_is_accepted(seed_text, write_case):
    case = write_case(seed_text.replace("STEP(time, 0, 0, 1, 3000)", "3000 rpm"))
    result = runner.invoke(app, ["geometry", str(case)])
    assert result.exit_code == 0, result.output
