"""Session 14 robustness sweep: hostile inputs that still ended as an internal error (exit 3),
a Python warning or traceback on stderr, a corrupt output stream, a results file replaced by
another kind of file, or an error that named the wrong key. Each test failed before its fix."""

from __future__ import annotations

import shutil

import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from tests.conftest import ROOT, SEED

runner = CliRunner()
SHORT = ("--set", "run.end_time=0.5")


def invoke(*args):
    return runner.invoke(app, [str(a) for a in args])


def error_line(r) -> str:
    """The error of a refused input: no traceback, no Python warning, one line (and the YAML
    line it is about, quoted as ``   3 | key: value``)."""
    text = r.stderr
    assert "Traceback" not in text and "internal error" not in text, text
    assert "Warning" not in text, text
    lines = text.splitlines()
    assert len(lines) == 1 or (len(lines) == 2 and " | " in lines[1]), text
    return lines[0]


@pytest.fixture(scope="module")
def simulated(tmp_path_factory):
    """A `gearcli simulate` results folder of the seed case, analysed (a report can be made)."""
    out = tmp_path_factory.mktemp("sim") / "seed"
    r = invoke("simulate", SEED, "-o", out, "-q", "--set", "run.end_time=2")  # monitor: > 1 rev
    assert r.exit_code in (0, 4)
    assert invoke("analyze", out, "-q").exit_code in (0, 4)
    return out


def sweep_study(tmp_path, text: str):
    """`gearcli sweep` of a study on the seed case: ``text`` is its lines after ``base:``."""
    study = tmp_path / "s.yaml"
    study.write_text(f"name: s\nbase: {SEED}\n{text}\n")
    return invoke("sweep", study, "-o", tmp_path / "out", "-q", "-j", "1")


# --- exit 3 for a user's value ----------------------------------------------------------------
@pytest.mark.parametrize("rate", ["1e-9 Hz", "1 Hz"])
def test_a_sensor_rate_too_low_for_the_run_is_a_located_error(rate):
    # 1e-9 Hz: LinAlgError from the anti-alias filter (exit 3); 1 Hz: two samples in 0.5 s
    r = invoke("simulate", SEED, "-o", "-", "-q", *SHORT, "--set",
               f"sensors={{sample_rate: {rate}}}")
    assert r.exit_code == 1
    line = error_line(r)
    assert "sensors.sample_rate" in line and "at least" in line


@pytest.mark.parametrize("fault, key", [
    ("{kind: root_crack, gear: pinion, tooth: 2, depth: 1000 mm}", "faults.0.depth"),
    ("{kind: spall, gear: pinion, tooth: 2, diameter: 100 mm, length: 3 mm, width: 0.5, "
     "depth: 0.05 mm}", "faults.0.diameter"),
    ("{kind: spall, gear: gear, tooth: 2, diameter: 1000 mm, length: 3 mm, width: 0.5, "
     "depth: 0.05 mm}", "faults.0.diameter"),
    ("{kind: spall, gear: gear, tooth: 2, roll_angle: 300 deg, length: 3 mm, width: 0.5, "
     "depth: 0.05 mm}", "faults.0.roll_angle"),
])
@pytest.mark.parametrize("command", ["geometry", "simulate"])
def test_a_fault_off_the_tooth_is_a_located_error(command, fault, key):
    """A crack through the tooth was exit 3 (ValueError of the fault model), a spall inside the
    base circle too; a spall beyond the tip ran as the healthy pair (exit 0)."""
    args = ["-o", "-"] if command == "simulate" else []
    r = invoke(command, SEED, *args, "-q", *SHORT, "--set", f"faults=[{fault}]")
    assert r.exit_code == 1
    line = error_line(r)
    assert key in line and "expected" in line


def test_a_negative_lhs_seed_is_a_located_error(tmp_path):
    r = sweep_study(tmp_path, "design: lhs\nsamples: 2\nseed: -1\n"
                    "parameters: {gears.module: {linspace: [8, 12]}}")
    assert r.exit_code == 1
    assert "seed" in error_line(r)


# --- Python warnings on stderr ---------------------------------------------------------------
@pytest.mark.filterwarnings("error")  # a numpy warning: an internal error, not a line to ignore
@pytest.mark.parametrize("end", [".inf", ".nan", "'1e400 mm'"])
def test_a_range_with_a_non_finite_end_is_refused(tmp_path, end):
    r = sweep_study(tmp_path, f"parameters: {{gears.module: {{linspace: [8, {end}], num: 3}}}}")
    assert r.exit_code == 1
    line = error_line(r)
    assert "parameters.gears.module.linspace" in line and "finite" in line


@pytest.mark.filterwarnings("error")
def test_a_run_stopped_at_once_warns_no_division_by_zero():
    slope = "[" + ", ".join(["5"] * 17) + "]"  # 5 mm: penetration beyond the tables at once
    r = invoke("simulate", SEED, "-o", "-", "-q", *SHORT, "--set",
               f"errors.profile_slope_deviation.pinion={slope}")
    assert r.exit_code == 4
    assert "left the contact tables" in error_line(r)


# --- outputs ---------------------------------------------------------------------------------
def test_csv_and_json_on_stdout_together_are_refused():
    r = invoke("simulate", SEED, "-o", "-", "--json", "-q", *SHORT)
    assert r.exit_code == 1
    line = error_line(r)
    assert "--json" in line and "-o -" in line
    assert r.stdout == ""


@pytest.mark.parametrize("args, name", [
    (("report", "{run}", "--force", "-o", "{run}/summary.json"), "summary.json"),
    (("report", "{run}", "--force", "--format", "md", "-o", "{run}/zoom.csv"), "zoom.csv"),
    (("monitor", "{run}", "--force", "--wav", "{run}/timeseries.csv"), "timeseries.csv"),
])
def test_a_file_option_never_replaces_another_kind_of_file(simulated, tmp_path, args, name):
    """`report -o DIR/summary.json --force` wrote the report over the run's summary.json."""
    run = tmp_path / "copy"
    shutil.copytree(simulated, run)
    before = (run / name).read_bytes()
    r = invoke(*(a.format(run=run) for a in args), "-q")
    assert r.exit_code == 1
    assert "expected a file name ending in" in error_line(r)
    assert (run / name).read_bytes() == before


# --- errors name the key the user wrote ------------------------------------------------------
@pytest.mark.parametrize("fault, key, value", [
    ("{kind: root_crack, gear: pinion, tooth: 2, depth: 1 mm, angle: -45 deg}", "faults.0.angle",
     "got '-45 deg'"),
    ("{kind: root_crack, gear: pinion, tooth: -1, depth: 1 mm}", "faults.0.tooth", "got -1"),
    ("{kind: spall, gear: pinion, tooth: 1, diameter: 170 mm, length: 1 mm, depth: 0.01 mm}",
     "faults.0.width", "missing"),
])
def test_a_fault_error_names_the_fault_key(fault, key, value):
    r = invoke("geometry", SEED, "-q", "--set", f"faults=[{fault}]")
    assert r.exit_code == 1
    line = error_line(r)
    assert f"--set faults=[{fault}]: {key}: " in line and value in line


@pytest.mark.parametrize("num", ["0", "-3", "2.5"])
def test_a_bad_range_count_names_num(tmp_path, num):
    r = sweep_study(tmp_path, f"parameters: {{gears.module: {{linspace: [8, 12], num: {num}}}}}")
    assert r.exit_code == 1
    assert "parameters.gears.module.num" in error_line(r)


def test_an_error_inside_an_overridden_section_names_the_override():
    duty = "[{torque: 1e3 N*m, speed: 0 rpm, time_share: 1}]"
    r = invoke("rate", ROOT / "cases" / "nrel5mw_sun_planet.yaml", "-q", "--set",
               f"rating.duty_cycle={duty}")
    assert r.exit_code == 1
    assert error_line(r).startswith(f"error: --set rating.duty_cycle={duty}: "
                                    "rating.duty_cycle.0.speed: got '0 rpm'")


@pytest.mark.parametrize("unit", ["''", "' '"])
def test_an_empty_unit_of_a_time_function_is_refused(unit):
    """`unit: ''` read the function's numbers in the default unit (deg/s) without a word."""
    r = invoke("geometry", SEED, "-q", "--set",
               f"drive.speed={{function: 'STEP(time, 0, 0, 1, 100)', unit: {unit}}}")
    assert r.exit_code == 1
    line = error_line(r)
    assert "drive.speed" in line and "unit" in line


def test_a_non_finite_option_value_reads_well():
    r = invoke("modal", SEED, "-q", "--speed-range", "0", "1e400 rpm")
    assert r.exit_code == 1
    assert "expected a finite angular velocity" in error_line(r)  # was "an finite"


def test_fault_kind_errors_name_the_kind():
    r = invoke("geometry", SEED, "-q", "--set", "faults=[{kind: nope, gear: pinion, tooth: 1}]")
    assert r.exit_code == 1
    assert ("faults.0.kind: got 'nope'; expected one of 'root_crack', 'spall', 'chipped_tip', "
            "'missing_tooth'") in error_line(r)
    r = invoke("geometry", SEED, "-q", "--set", "faults=[{gear: pinion, tooth: 1}]")
    assert r.exit_code == 1
    assert "faults.0.kind: missing; expected one of root_crack, spall" in error_line(r)


def test_a_spall_without_width_is_refused_before_the_model():
    """The schema took `width` as optional (None), and the fault model failed on it: exit 3."""
    fault = "{kind: spall, gear: pinion, tooth: 1, diameter: 170 mm, length: 1 mm, depth: 0.01 mm}"
    r = invoke("simulate", SEED, "-o", "-", "-q", *SHORT, "--set", f"faults=[{fault}]")
    assert r.exit_code == 1
    assert "faults.0.width: missing" in error_line(r)


@pytest.mark.parametrize("text, fragment", [
    ("[]", "expected at least 1 entry"),
    ("5", "expected a mapping: a 'accelerometer' section"),
])
def test_pydantic_wording_is_not_shown(text, fragment):
    r = invoke("geometry", SEED, "-q", "--set", f"sensors.accelerometer.housing={text}"
               if text == "[]" else f"sensors.accelerometer={text}")
    assert r.exit_code == 1
    line = error_line(r)
    assert fragment in line and "List should" not in line and "instance of" not in line


@pytest.mark.parametrize("load, fragment", [
    ("inf", "--load 'inf': expected a finite number (N)"),  # was "load_N inf: ..."
    ("-5", "--load must be a force > 0 N, got -5 N"),
    ("5 kg", "--load '5 kg': wrong dimension"),
])
def test_mesh_load_errors_name_the_option(load, fragment):
    r = invoke("mesh", SEED, "-q", "--load", load)
    assert r.exit_code == 1
    assert fragment in error_line(r)


def test_mesh_load_takes_a_force_with_units():
    """--load '5 kN' was a usage error (exit 2): the option took a bare float only."""
    r = invoke("mesh", SEED, "--json", "--load", "5 kN")
    assert r.exit_code == 0, r.stderr
    import json

    assert json.loads(r.stdout)["force_N"] == pytest.approx(5000.0)


@pytest.mark.parametrize("value", ["nan", "inf", "-inf mm", "NaN mm", "Infinity"])
def test_nan_and_inf_as_text_are_not_called_a_unit(value):
    """'got 'nan'; expected a number with units ... (a unit alone is not a value)'."""
    r = invoke("geometry", SEED, "-q", "--set", f"gears.module={value}")
    assert r.exit_code == 1
    line = error_line(r)
    assert "gears.module" in line and "(a finite number: not NaN or infinity)" in line
    assert "unit alone" not in line


@pytest.mark.parametrize("setting, fragment", [
    ("run.atol=0", "run.atol: got 0; expected > 0 mm"),  # the unit was left out (an int bound)
    ("run.max_step=-1", "run.max_step: got -1; expected > 0 s"),
    ("faults=[{kind: spall, gear: pinion, tooth: 1, diameter: -170 mm, length: 1 mm, "
     "depth: 0.01 mm, width: 1}]", "faults.0.diameter: got '-170 mm'; expected > 0 mm"),
    ("faults=[{kind: root_crack, gear: pinion, tooth: 2, depth: 1 mm, angle: 100 deg}]",
     "faults.0.angle: got '100 deg'; expected <= 90 deg"),
    # a spall's own keys (the union's first member, the root crack's, were listed)
    ("faults=[{kind: spall, gear: pinion, tooth: 1, diameter: 170 mm, length: 1 mm, "
     "depth: 0.01 mm, widht: 1}]", "faults.0.widht: got 1; unknown key (did you mean 'width'?); "
     "expected one of: kind, gear, tooth, diameter, roll_angle, length, width, depth"),
    ("faults=[{kind: spall, gear: pinion, tooth: 1, diameter: 170 mm, length: 1 mm, "
     "depth: 0.01 mm}]", "faults.0.width: missing required key; expected share of the face "
     "width the spall covers"),
])
def test_limits_and_keys_of_optional_and_listed_fields(setting, fragment):
    r = invoke("geometry", SEED, "-q", "--set", setting)
    assert r.exit_code == 1
    assert fragment in error_line(r)


LONG = "a" * 300  # a file name above NAME_MAX (255 bytes)


@pytest.mark.parametrize("args", [
    ("geometry", f"{LONG}.yaml"),
    ("geometry", SEED, "--plot", f"{LONG}.png"),
    ("simulate", SEED, *SHORT, "-o", LONG),
    ("new", f"{LONG}.yaml"),
    ("mesh", SEED, "-o", LONG),
])
def test_a_file_name_too_long_is_a_user_error(tmp_path, monkeypatch, args):
    """ENAMETOOLONG was an internal error (exit 3) in every command."""
    monkeypatch.chdir(tmp_path)
    r = invoke(*args, "-q") if args[0] != "new" else invoke(*args)
    assert r.exit_code == 1
    line = error_line(r)
    assert "File name too long" in line and f"{LONG[:20]}" in line


def test_a_bad_value_in_a_studys_set_names_the_set_line(tmp_path):
    """It quoted the base file's line of the value it replaced ("50 |   end_time: 5" beside
    "got '-1 s'")."""
    r = sweep_study(tmp_path, "set:\n  run.end_time: -1 s\nparameters: {gears.module: [9, 10]}")
    assert r.exit_code == 1
    line = error_line(r)
    assert line.startswith(f"error: {tmp_path / 's.yaml'}:4: the base case is invalid: "
                           "--set run.end_time=-1 s: run.end_time: got '-1 s'")
    assert "end_time: 5" not in r.stderr


def test_a_study_check_no_value_passes_is_refused(tmp_path):
    """min > max failed every point after the whole study had run (exit 4)."""
    r = sweep_study(tmp_path, "parameters: {gears.module: [9, 10]}\n"
                    "checks: [{metric: dynamic_factor, min: 5, max: 1}]")
    assert r.exit_code == 1
    assert "checks.0: min 5 > max 1" in error_line(r)


def test_a_report_elsewhere_keeps_the_figures_of_the_earlier_report(simulated, tmp_path):
    """`report DIR -o other.md` rewrote DIR/figures, which DIR/report.md links, without
    --force."""
    run = tmp_path / "copy"
    shutil.copytree(simulated, run)
    assert invoke("report", run, "-q", "--format", "md").exit_code in (0, 4)
    before = {p.name: p.stat().st_mtime_ns for p in (run / "figures").iterdir()}
    r = invoke("report", run, "-q", "--format", "md", "-o", tmp_path / "other.md")
    assert r.exit_code == 1
    assert "figures" in error_line(r) and "--force" in error_line(r)
    assert {p.name: p.stat().st_mtime_ns for p in (run / "figures").iterdir()} == before
    r = invoke("report", run, "-q", "--format", "md", "-o", tmp_path / "other.md", "--force")
    assert r.exit_code in (0, 4) and (tmp_path / "other.md").is_file()


@pytest.mark.parametrize("name, fragment", [
    ("missing", "missing: not found; expected a results folder"),  # was "the report
    ("case.yaml", "case.yaml: not a folder; expected a results folder"),  # missing/report.html"
])
def test_report_on_no_folder_says_so(tmp_path, monkeypatch, name, fragment):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "case.yaml").write_text("x: 1\n")
    r = invoke("report", name, "-q")
    assert r.exit_code == 1
    assert error_line(r) == f"error: {fragment} from gearcli simulate"


def test_a_case_file_given_to_sweep_says_it_wants_a_study(tmp_path):
    r = invoke("sweep", SEED, "-o", tmp_path / "out", "-q")
    assert r.exit_code == 1
    assert "gears: unknown key" in error_line(r) and "gearcli new --template study" in r.stderr
