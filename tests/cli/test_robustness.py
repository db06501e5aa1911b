"""Issue 18: every bad input a clean error (exit 1 or 2, one located line), bounded work, no
silent nonsense. One test per reported class; the property-based fuzz is in test_fuzz.py."""

from __future__ import annotations

import json
import os

import pytest
from typer.testing import CliRunner

from gearcli import guards
from gearcli.cli import app
from tests.conftest import ROOT, SEED

runner = CliRunner()


def invoke(*args: str, input: str | None = None):
    return runner.invoke(app, [str(a) for a in args], input=input)


def error_line(result) -> str:
    """The first stderr line; asserts there is no traceback and at most two lines (the message
    and the offending YAML line)."""
    text = result.stderr
    assert "Traceback" not in text and "internal error" not in text, text
    assert 1 <= len(text.splitlines()) <= 2, text
    return text.splitlines()[0]


def seed_variant(tmp_path, old: str, new: str, name: str = "case.yaml"):
    text = SEED.read_text()
    assert old in text
    path = tmp_path / name
    path.write_text(text.replace(old, new, 1))
    return path


# --- hangs and memory: bounded before the work ------------------------------------------------
def test_yaml_alias_bomb_is_refused_quickly(tmp_path):
    lines = ["a: &a [x, x, x, x, x, x, x, x, x]"]
    for prev, name in zip("abcdefgh", "bcdefghi", strict=True):
        lines.append(f"{name}: &{name} [" + ", ".join([f"*{prev}"] * 9) + "]")
    path = tmp_path / "bomb.yaml"
    path.write_text("\n".join(lines) + "\n")
    assert path.stat().st_size < 500
    r = invoke("geometry", path)
    assert r.exit_code == 1
    assert "expands to more than" in error_line(r)


@pytest.mark.parametrize("depth", [5000, 60])  # far beyond (RecursionError before) and just
def test_deep_nesting_is_refused(tmp_path, depth):  # beyond the limit of 50
    path = tmp_path / "deep.yaml"
    path.write_text("a: " + "[" * depth + "]" * depth + "\n")
    r = invoke("geometry", path)
    assert r.exit_code == 1
    assert "nested too deeply" in error_line(r)


@pytest.mark.parametrize("text", ["10 ** 10 ** 10 mm", "9**9**9**9", "10 mm^99999",
                                  "2 ** 1000000 mm", "(9**9)**9 mm"])
def test_unit_powers_are_bounded(text):
    r = invoke("simulate", SEED, "-o", "-", "--set", f"gears.module={text}")
    assert r.exit_code == 1
    line = error_line(r)
    assert "gears.module" in line and "power" in line


def test_unit_powers_are_bounded_in_units_and_stiffness():
    r = invoke("simulate", SEED, "-o", "-", "--set", "contact.stiffness=9**9**9**9")
    assert r.exit_code == 1 and "contact.stiffness" in error_line(r)
    r = invoke("simulate", SEED, "-o", "-", "--set",
               'drive.speed={function: "STEP(time,0,0,1,3)", unit: "rpm**99999"}')
    assert r.exit_code == 1 and "drive.speed" in error_line(r)


def test_plain_unit_powers_still_work():
    from gearcli.case.load import load_case

    c = load_case(SEED, ["contact.stiffness=1e5 N/mm^1.5", "material.density=7.85e-6 kg/mm**3",
                         "load.viscous=1 N*mm*s/rad"]).case
    assert c.contact.stiffness == pytest.approx(1e5)


def test_huge_file_and_devices_are_refused(tmp_path):
    path = tmp_path / "big.yaml"
    path.write_text("name: x\ndescription: " + "x" * (guards.MAX_INPUT_BYTES + 10) + "\n")
    r = invoke("geometry", path)
    assert r.exit_code == 1 and "too large" in error_line(r)
    r = invoke("geometry", "/dev/zero")
    assert r.exit_code == 1 and "too large" in error_line(r)


def test_fifo_without_writer_times_out(tmp_path, monkeypatch):
    monkeypatch.setattr(guards, "READ_TIMEOUT_S", 0.2)
    fifo = tmp_path / "case.fifo"
    os.mkfifo(fifo)
    r = invoke("geometry", fifo)
    assert r.exit_code == 1 and "no data" in error_line(r)


def test_case_from_a_pipe_is_read_and_hashed(tmp_path):
    import hashlib
    import threading

    from gearcli.case.yamlsrc import read_source

    fifo = tmp_path / "case.fifo"
    os.mkfifo(fifo)
    raw = SEED.read_bytes()

    def write():
        with open(fifo, "wb") as fh:
            fh.write(raw)

    writer = threading.Thread(target=write)
    writer.start()
    src = read_source(fifo)
    writer.join()
    assert src.sha256 == hashlib.sha256(raw).hexdigest()
    assert src.data["name"] == "seed"


def test_long_expression_is_refused():
    expr = "+".join(["STEP(time, 0, 0, 1, 1)"] * 200)
    r = invoke("simulate", SEED, "-o", "-", "--set", f"drive.speed={expr}")
    assert r.exit_code == 1
    assert "expected at most" in error_line(r)


# --- messages stay readable ------------------------------------------------------------------
def test_long_values_are_clipped_in_messages(tmp_path):
    path = seed_variant(tmp_path, "name: seed", "name: seed\nnot_a_key: " + "x" * 200_000)
    r = invoke("geometry", path)
    assert r.exit_code == 1
    assert len(r.stderr) < 2000
    assert "not_a_key" in error_line(r)


def test_unit_without_a_number_is_refused(tmp_path):
    path = seed_variant(tmp_path, "  module: 10 ", "  module: mm ")
    r = invoke("geometry", path)
    assert r.exit_code == 1
    assert "gears.module" in error_line(r) and "unit alone" in error_line(r)


# --- exit 3 for user causes: extreme magnitudes, full disks --------------------------------
@pytest.mark.parametrize("old, new, key", [
    ("    teeth: 17 ", "    teeth: 1" + "0" * 300 + " ", "gears.pinion.teeth"),
    ("  module: 10 ", "  module: 1e300 ", "gears.module"),
    ("  face_width: 100 ", "  face_width: '1e200 km' ", "gears.face_width"),
    ("speed: STEP(time, 0, 0, 1, 3000)", "speed: 1e308", "drive.speed"),
    ("speed: STEP(time, 0, 0, 1, 3000)", "speed: STEP(time, 0, 0, 1, 1e300)", "drive.speed"),
])
def test_absurd_magnitudes_are_located_errors(tmp_path, old, new, key):
    path = seed_variant(tmp_path, old, new)
    r = invoke("geometry", path)
    assert r.exit_code == 1
    line = error_line(r)
    assert key in line and "at most" in line


def test_integer_beyond_python_digit_limit(tmp_path):
    path = seed_variant(tmp_path, "    teeth: 17 ", "    teeth: 1" + "0" * 5000 + " ")
    r = invoke("geometry", path)
    assert r.exit_code == 1
    error_line(r)


def test_tiny_module_is_no_internal_error():
    r = invoke("simulate", SEED, "-o", "-", "--set", "gears.module=1e-12",
               "--set", "run.end_time=0.2")
    assert r.exit_code in (0, 1)
    assert "internal error" not in r.stderr and "Traceback" not in r.stderr
    if r.exit_code == 0:
        assert "warning" in r.stderr


def test_full_disk_on_stdout_is_exit_1():
    import subprocess
    import sys

    with open("/dev/full", "w") as full:
        p = subprocess.run([sys.executable, "-m", "gearcli", "schema"], stdout=full,
                           stderr=subprocess.PIPE, text=True, timeout=60, cwd=ROOT,
                           env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert p.returncode == 1
    assert p.stderr.strip().startswith("error:") and "No space left" in p.stderr
    assert "Traceback" not in p.stderr


# --- run size: refused before anything is allocated; short runs refused or flagged -------------
@pytest.mark.parametrize("setting, key", [("run.end_time=20000", "run.end_time"),
                                          ("run.output_steps=1000000000000", "run.output_steps"),
                                          ("run.output_rate=1e9", "run.output_rate")])
def test_output_size_is_checked_before_allocation(setting, key):
    r = invoke("simulate", SEED, "-o", "-", "--set", setting)
    assert r.exit_code == 1
    line = error_line(r)
    assert key in line and "output samples" in line and "in memory" in line


def test_output_rows_agree_with_the_sampling():
    from gearcli.case.load import load_case
    from gearcli.pipeline.case_checks import output_rows
    from gearcli.pipeline.geometry import run_geometry
    from gearcli.pipeline.kernel_input import output_times

    for extra in ([], ["run.output_steps=123"], ["run.output_rate=777"], ["drive.speed=0"],
                  ["run.end_time=1e-4"]):
        loaded = load_case(SEED, extra)
        geo = run_geometry(loaded)
        from gearcli.model.frequencies import mesh_frequencies

        g = geo.geometry
        speed = geo.pinion_speed_rad_s
        f_z = mesh_frequencies(g.pinion.teeth, speed, g.ratio)[0] if speed else None
        t, _ = output_times(loaded.case, f_z)
        assert output_rows(loaded.case, f_z)[0] == t.size, extra


def test_run_shorter_than_a_mesh_cycle_is_refused(tmp_path):
    r = invoke("simulate", SEED, "-o", tmp_path / "out", "--set", "run.end_time=1e-9")
    assert r.exit_code == 1
    assert "run.end_time" in error_line(r) and "mesh cycle" in error_line(r)
    assert not (tmp_path / "out").exists()


def test_run_shorter_than_the_window_needs_is_flagged():
    r = invoke("simulate", SEED, "-o", "-", "--set", "run.end_time=0.05")
    assert r.exit_code == 0
    assert "short run" in r.stderr


def test_max_step_needing_more_steps_than_the_solver_takes_is_refused():
    r = invoke("simulate", SEED, "-o", "-", "--set", "run.end_time=0.2",
               "--set", "run.max_step=1e-9")
    assert r.exit_code == 1
    line = error_line(r)
    assert "run.max_step" in line and "steps" in line


# --- command-line options with absurd values -------------------------------------------------
@pytest.mark.parametrize("args, code", [
    (["mesh", SEED, "--load", "inf"], 1),
    (["mesh", SEED, "--load", "1e300"], 1),
    (["mesh", SEED, "--set", "load.torque=1e11"], 1),
    (["modal", SEED, "--speed-range", "0", "inf"], 1),
    (["sweep", SEED, "-o", "x", "-j", "100000"], 2),
])
def test_absurd_option_values_are_clean_errors(args, code):
    r = invoke(*args)
    assert r.exit_code == code, r.stderr
    assert "internal error" not in r.stderr and "Traceback" not in r.stderr



@pytest.mark.parametrize("case, override, key, cure", [
    # a --set profile shift that makes the gear's tip cut the pinion's root fillet: the error
    # names the key that was changed (it named the unchanged teeth before), and no direction
    ("iso_pair.yaml", "gears.pinion.profile_shift=1.5", "gears.pinion.profile_shift: got 1.5",
     "change the pinion's profile shift or teeth, or shorten the gear tip"),
    # too few teeth: involute interference beyond T1, whose classic cures are named
    ("iso_pair.yaml", "gears.pinion.teeth=8", "gears.pinion.teeth: got 8",
     "more teeth or a larger profile shift on the pinion, or a shorter gear tip"),
])
def test_interference_names_the_changed_lever(case, override, key, cure):
    r = invoke("geometry", ROOT / "cases" / case, "--set", override)
    assert r.exit_code == 1
    line = error_line(r)
    assert line.startswith(f"error: --set {override}: {key};"), line
    assert cure in line


def test_interference_from_a_file_names_the_teeth(tmp_path):
    # which value of a file the user edited is unknown: the teeth are named even when the file
    # sets a profile shift (it named the shift before), and so is a --set of the mate's teeth
    text = (ROOT / "cases" / "iso_pair.yaml").read_text()
    assert "    teeth: 21\n" in text
    case = tmp_path / "ip9.yaml"
    case.write_text(text.replace("    teeth: 21\n", "    teeth: 9\n", 1))
    line = error_line(invoke("geometry", case))
    assert f"{case}:" in line and "gears.pinion.teeth: got 9;" in line, line


def test_bore_outside_the_root_circle_is_refused(tmp_path):
    r = invoke("mesh", ROOT / "cases" / "iso_pair.yaml", "--set",
               "gears.gear.bore_diameter=250 mm")
    assert r.exit_code == 1
    line = error_line(r)
    assert "gears.gear.bore_diameter: got '250 mm'" in line and "expected < d_f" in line, line


@pytest.mark.parametrize("speed", ["0", "-0 rpm"])
def test_a_run_at_rest_simulates_but_has_no_mesh_frequency_to_analyse(tmp_path, speed):
    # a pinion held at rest (a ring-down) is a valid simulation; analyze divided by its zero
    # mesh frequency (exit 3), and so did run
    case, sets = ROOT / "cases" / "iso_pair.yaml", ("--set", f"drive.speed={speed}", "--set",
                                                   "run.end_time=0.2")
    r = invoke("simulate", case, "-o", tmp_path / "o", "--quiet", *sets)
    assert r.exit_code == 0, r.output
    for args in (("analyze", tmp_path / "o"), ("run", case, "-o", tmp_path / "r", *sets)):
        r = invoke(*args)
        assert r.exit_code == 1, (args, r.output)
        line = error_line(r)
        assert "the pinion turns less than one tooth pitch" in line, line
    assert not (tmp_path / "r").exists()


def test_a_load_too_large_for_the_teeth_names_the_load(tmp_path):
    r = invoke("simulate", ROOT / "cases" / "iso_pair.yaml", "-o", tmp_path / "o", "--set",
               "load.torque=3e4 N*m")
    assert r.exit_code == 1
    line = error_line(r)
    assert line.startswith("error: load.torque: the static deflection at this load is too "
                           "large for the teeth"), line


@pytest.mark.parametrize("override, fragment", [
    # a penalty contact that soft carried the load on damping alone: f_n 1e-6 Hz, zeta 4e8,
    # and the run passed the validity guard (its penetration stayed below 5 % of the tooth)
    ("contact.stiffness=1e-20", "contact.stiffness: got '1e-20'; the static deflection at the "
                                "case's load is 3.9"),
    ("contact.stiffness=1e2", "contact.stiffness: got '1e2'; the static deflection at the "
                              "case's load is 8.4"),
])
def test_a_contact_too_soft_for_the_load_is_refused(tmp_path, override, fragment):
    r = invoke("run", SEED, "-o", tmp_path / "o", "--set", override)
    assert r.exit_code == 1, r.output
    line = error_line(r)
    assert fragment in line and "beyond the contact model's range of 0.7854 mm" in line, line
    assert not (tmp_path / "o").exists()
    # without load there is no static deflection to refuse (the linearisation point at 1 % of
    # d_max, here 0.79 mm, was taken for one)
    r = invoke("simulate", SEED, "-o", tmp_path / "z", "--quiet", "--set", "load.torque=0",
               "--set", "contact.penetration_depth=79", "--set", "run.end_time=0.2")
    assert "static deflection" not in r.output, r.output


def test_a_load_that_ends_negative_is_refused_and_a_reversal_on_the_way_runs(tmp_path):
    # a negative load drives the gear: the pair ran on its coast flanks, the summary said
    # dynamic factor 0, and the report crashed drawing a colour scale without range (exit 3)
    r = invoke("run", SEED, "-o", tmp_path / "o", "--set", "load.torque=-3e5")
    assert r.exit_code == 1, r.output
    line = error_line(r)
    assert "load.torque: got '-3e5'; the load torque ends at -300000 N*mm" in line, line
    assert not (tmp_path / "o").exists()
    r = invoke("simulate", SEED, "-o", tmp_path / "s", "--quiet", "--set", "run.end_time=0.2",
               "--set", "load.torque=STEP(time, 0, -1e5, 0.1, 2e5)")
    assert r.exit_code == 0, r.output
    # negative only after the run ends: judged where the run ends, not after the last ramp
    r = invoke("simulate", SEED, "-o", tmp_path / "a", "--quiet", "--set", "run.end_time=0.2",
               "--set", "load.torque=STEP(time, 0, 0, 0.1, 4.5e5) - STEP(time, 1, 0, 2, 9e5)")
    assert r.exit_code == 0, r.output


def test_a_run_without_load_is_judged_by_the_tooth_thickness_and_reported(tmp_path):
    # without load the IMPACT law's linearisation point (1 % of d_max) stood in for the static
    # deflection, so the seed's rattle (17 µm) was "10 x the static deflection" and invalid;
    # the tooth law's run was valid and its report divided by the zero static force (exit 3)
    from gearcli.pipeline.simulate import run_simulation

    res = run_simulation(SEED, ["load.torque=0", "run.end_time=0.5"], zoom=False)
    assert res.status == "ok", res.invalid_reason
    assert res.summary.dynamic_factor is None  # no static force: no dynamic factor
    r = invoke("run", ROOT / "cases" / "iso_pair.yaml", "-o", tmp_path / "o", "--set",
               "load.torque=0", "--set", "run.end_time=0.2")
    assert r.exit_code in (0, 4), r.output
    assert "internal error" not in r.output and (tmp_path / "o" / "report.html").is_file()


def test_a_pair_without_single_pair_zone_writes_valid_json(tmp_path):
    # contact ratio 2.6: no single-pair zone, whose stiffness is then null, never NaN
    sets = ["gears.pressure_angle=16", "gears.rack.addendum=1.35", "gears.rack.dedendum=1.6",
            "gears.rack.root_radius=0.2", "gears.pinion.teeth=40", "gears.gear.teeth=80",
            "gears.pinion.profile_shift=0", "gears.gear.profile_shift=0"]
    args = [a for s in sets for a in ("--set", s)]
    r = invoke("mesh", ROOT / "cases" / "iso_pair.yaml", "--json", *args)
    assert r.exit_code == 0, r.output

    def no_nan(token):
        raise AssertionError(f"{token} in JSON")

    doc = json.loads(r.stdout, parse_constant=no_nan)
    assert doc["stiffness"]["single_pair_zone_N_mm"] is None
    assert doc["stiffness"]["double_pair_zone_N_mm"] > 0
    assert "RuntimeWarning" not in r.stderr


@pytest.mark.parametrize("override, fragment", [
    ("material.density=1e-30", "expected a density of at least 1e-10 kg/mm^3"),
    ("gears.pinion.material.density=1e-30", "expected a density of at least"),
    ("material.youngs_modulus=1 Pa", "expected a Young's modulus of at least 1 MPa"),
])
def test_no_gear_material_is_that_light_or_soft(override, fragment):
    # such values ran to status "ok" at 1e28 rpm with a 5e15 Hz mesh mode
    r = invoke("geometry", ROOT / "cases" / "iso_pair.yaml", "--set", override)
    assert r.exit_code == 1
    line = error_line(r)
    assert f"--set {override}:" in line and fragment in line, line


def test_dev_null_as_the_case_is_empty_at_once():
    # a character device reads empty at its end: that is EOF, not "no data yet" (it polled
    # for 30 s); the wall time is not asserted, the message is the empty file's
    r = invoke("geometry", "/dev/null")
    assert r.exit_code == 1
    assert "file is empty" in error_line(r)


def test_a_ramp_that_outlasts_the_run_is_warned(tmp_path):
    # the speed reaches 1500 rpm at 100 s, a 0.2 s run sees 0.015 rpm: no steady state
    r = invoke("simulate", ROOT / "cases" / "iso_pair.yaml", "-o", tmp_path / "o", "--quiet",
               "--set", "run.end_time=0.2", "--set",
               "drive.speed={function: 'STEP(time, 0, 0, 100, 1500)', unit: rpm}")
    assert r.exit_code == 0, r.output
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert any(w.startswith("no steady state: the drive/load functions reach their final "
                            "values at 100 s, after the run ends (0.2 s)")
               for w in summary["warnings"]), summary["warnings"]


@pytest.mark.parametrize("option, values", [("--window", ["200", "ms"]),
                                            ("--speed-range", ["0", "'rpm'"])])
def test_a_unit_alone_is_not_an_option_value(tmp_path, option, values):
    # "ms" was read as 1 ms and "'rpm'" leaked pint's AssertionError
    args = (("analyze", tmp_path) if option == "--window"
            else ("modal", ROOT / "cases" / "iso_pair.yaml"))
    r = invoke(*args, option, *values)
    assert r.exit_code == 1
    assert "no number in front: a unit alone is not a value" in error_line(r)


def test_an_edited_window_in_summary_json_is_refused(tmp_path):
    out = tmp_path / "o"
    r = invoke("simulate", SEED, "-o", out, "--quiet", "--set", "run.end_time=0.3")
    assert r.exit_code == 0, r.output
    doc = json.loads((out / "summary.json").read_text())
    doc["scalars"]["window_s"] = [5, 1]  # it ended in exit 3 (zero-size array)
    (out / "summary.json").write_text(json.dumps(doc))
    for command in ("analyze", "stress", "report"):
        r = invoke(command, out)
        assert r.exit_code == 1, (command, r.output)
        assert "scalars.window_s missing or not a window T0 < T1" in error_line(r)


@pytest.mark.parametrize("relief, key, fragment", [
    ("{amount: 15 um, start_diameter: 1 mm}", "start_diameter",
     "1 mm is off the pinion's active flank; expected between its active profile start d_Nf"),
    ("{amount: 15 um, length: 1000 mm}", "length",
     "a relief 1000 mm long does not start on the path of contact, which is g_alpha = 23.17"),
    # 3 mm on both flanks of a 2.8 mm tip (the validity sweep's try ran and ended invalid,
    # "left the contact tables", naming neither the relief nor its amount)
    ("{amount: 3 mm, length: 20 mm}", "amount",
     "a tip relief of 3 mm leaves no tip: the reliefs of both flanks meet at C_a = s_a cos α_a"),
])
def test_a_relief_off_the_active_flank_is_refused(relief, key, fragment):
    # both passed silently (iso_pair's path of contact is 23.17 mm long)
    r = invoke("geometry", ROOT / "cases" / "iso_pair.yaml", "--set",
               f"modifications.tip_relief.pinion={relief}")
    assert r.exit_code == 1
    line = error_line(r)
    assert f"modifications.tip_relief.pinion.{key}:" in line and fragment in line, line


def test_a_tip_relief_just_short_of_the_tip_runs_the_geometry():
    """The bound is the tip's: s_a cos α_a / 2 = 1.166 mm on iso_pair's pinion (s_a 2.802 mm,
    cos α_a = d_b/d_a); 1.1 mm leaves a tip, so geometry accepts it (a bad design, not an
    impossible one)."""
    r = invoke("geometry", ROOT / "cases" / "iso_pair.yaml", "--set",
               "modifications.tip_relief.pinion={amount: 1.1 mm, length: 5 mm}")
    assert r.exit_code == 0, r.output


def test_rtol_below_double_precision_is_refused_with_a_readable_bound():
    r = invoke("geometry", SEED, "--set", "run.rtol=1e-20")
    assert r.exit_code == 1
    assert error_line(r).endswith("run.rtol: got '1e-20'; expected >= 2.3e-14")


def test_iso_method_b_block_follows_the_si_units(tmp_path):
    r = invoke("--units", "si", "mesh", ROOT / "cases" / "iso_pair.yaml")
    assert r.exit_code == 0, r.output
    assert "N/(mm·µm)" not in r.stdout and "kg/mm" not in r.stdout
    assert "N/m²" in r.stdout and "kg/m " in r.stdout


@pytest.mark.parametrize("override, fragment", [
    ("gears.pinion.bore_diameter=200", "the bore must lie inside the root circle"),
    ("errors.runout.pinion.eccentricity=10", "expected < 1.25 mm"),  # module 5: a quarter
])
def test_geometry_refuses_bores_and_runout_the_pair_cannot_have(override, fragment):
    # geometry passed a 200 mm bore in a 96 mm root circle; a 10 mm runout ended in a generic
    # solver failure
    r = invoke("geometry", ROOT / "cases" / "iso_pair.yaml", "--set", override)
    assert r.exit_code == 1
    line = error_line(r)
    assert f"{override.partition('=')[0]}: got 10" in line or "bore" in line
    assert fragment in line, line


def test_a_raised_output_rate_is_said(tmp_path):
    # 1 Hz over 0.2 s is under the 10-sample floor: 50 Hz was written without a word
    r = invoke("simulate", ROOT / "cases" / "iso_pair.yaml", "-o", tmp_path / "o", "--set",
               "run.end_time=0.2", "--set", "run.output_rate=1")
    assert r.exit_code == 0, r.output
    assert ("warning: output rate 1 Hz gives fewer than 10 samples in the run: written at "
            "50 Hz instead") in r.stderr


def test_a_stress_window_shorter_than_a_mesh_cycle_is_refused(tmp_path):
    out = tmp_path / "o"
    assert invoke("simulate", SEED, "-o", out, "--quiet", "--set",
                  "run.end_time=1.2").exit_code == 0  # steady after the 1 s ramp
    r = invoke("stress", out, "--window", "0", "0.0005")  # f_z = 141.7 Hz: 7.06 ms a cycle
    assert r.exit_code == 1
    assert "is shorter than one mesh cycle (1/f_z = 0.00706 s)" in error_line(r)


@pytest.mark.parametrize("command", ["mesh", "modal"])
@pytest.mark.parametrize("name", ["figure.txt", "figure"])
def test_mesh_and_modal_plots_need_a_figure_format(tmp_path, command, name):
    # .txt ended in matplotlib's ValueError (exit 3); no suffix wrote a PNG without one
    r = invoke(command, SEED, "--plot", tmp_path / name)
    assert r.exit_code == 1
    assert "expected a file name ending in .png, .svg or .pdf" in error_line(r)
    assert not (tmp_path / name).exists()


@pytest.mark.parametrize("seed, expected", [("-3", "expected >= 0"),
                                            ("99999999999", "expected <= 4294967295")])
def test_pitch_deviation_seed_is_bounded(tmp_path, seed, expected):
    # a negative seed reached numpy's random generator (exit 3)
    r = invoke("simulate", SEED, "-o", tmp_path / "o", "--set",
               "errors.pitch_deviation.pinion.iso1328_grade=11", "--set",
               f"errors.pitch_deviation.pinion.seed={seed}")
    assert r.exit_code == 1
    assert f"errors.pitch_deviation.pinion.seed: got {seed}; {expected}" in error_line(r)


@pytest.mark.parametrize("override, fragment", [
    # the pointed tip named profile_shift, the shift sum the whole gears section (file line)
    ("gears.pinion.thickness_allowance=7", "--set gears.pinion.thickness_allowance=7: "
                                           "gears.pinion.thickness_allowance: got 7; pinion: tip "
                                           "thickness"),
    ("gears.gear.profile_shift=-0.9", "--set gears.gear.profile_shift=-0.9: "
                                      "gears.gear.profile_shift: got -0.9; profile shift sum"),
    # a misspelt 'derived' and a bad time: examples of the field's own dimension
    ("contact.stiffness=Derived", "e.g. '10 N/mm^1.5' (no number in front: a unit alone is "
                                  "not a value); or 'derived' (ISO 6336-1)"),
    ("run.end_time=NaN", "run.end_time: got 'NaN'; expected a number with units, e.g. '10 s'"),
])
def test_geometry_and_quantity_errors_name_what_the_user_changed(tmp_path, override, fragment):
    r = invoke("simulate", SEED, "-o", tmp_path / "o", "--set", override)
    assert r.exit_code == 1
    assert fragment in error_line(r)


@pytest.mark.parametrize("speed, why", [("0", "the pinion does not turn"),
                                        ("300*time", "drive.speed has no constant final value")])
def test_modal_margin_without_a_speed_is_not_checked_and_says_why(speed, why):
    r = invoke("modal", SEED, "--json", "--set", f"drive.speed={speed}")
    assert r.exit_code == 0, r.output
    check = json.loads(r.stdout)["checks"][0]
    assert check["checked"] is False
    assert check["note"].startswith(f"not checked: no case speed ({why})")


def test_schema_kind_needs_results():
    # `schema --kind analysis` printed the case's schema with exit 0
    r = invoke("schema", "--kind", "analysis")
    assert r.exit_code == 1 and "--kind analysis: applies to --results only" in error_line(r)
    assert invoke("schema", "--study", "--results").exit_code == 1
    assert json.loads(invoke("schema", "--results").stdout)["title"] == "gearcli summary.json"


def test_round_off_coast_contact_is_no_impact_warning():
    # zero backlash left the coast flanks touching at 1.7e-8 N: "coast force up to 0 N"
    from gearcli.pipeline.simulate import COAST_FORCE_FRACTION, run_simulation

    res = run_simulation(ROOT / "cases" / "iso_pair.yaml", ["run.end_time=0.3"], zoom=False)
    warned = any(w.startswith("coast-flank impacts") for w in res.warnings)
    assert warned == (res.summary.coast_force_max_N
                      > COAST_FORCE_FRACTION * res.kernel_input.mesh.static_force_N)
    # near resonance without backlash the coast flanks are hit: 11.8 kN at 4440 rpm (f_z 0.95
    # f_n = 1630 Hz; 11 kN at 4900 rpm when the mesh mode was at 1792 Hz, before the tooth
    # law took Weber's contact term and the bores left the disc inertias, issue 31)
    hit = run_simulation(ROOT / "cases" / "iso_pair.yaml", [
        "run.end_time=0.4", 'drive.speed={function: "STEP(time,0,0,0.2,4440)", unit: rpm}'],
        zoom=False)
    assert any(w.startswith("coast-flank impacts: coast force up to 1.18") for w in hit.warnings)
