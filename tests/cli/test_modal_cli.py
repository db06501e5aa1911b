"""`gearcli modal`: table, JSON, Campbell plot, the margin check's exit codes, bad input."""

import json

import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from tests.conftest import SEED

runner = CliRunner()
LIGHT = ["--set", "contact.max_damping=1"]  # a lightly damped mesh: the margin check applies
TORQUE = ["--set", "drive.type=torque", "--set", "drive.speed=null",
          "--set", "drive.torque=3.06e5"]


def modal(*args):
    return runner.invoke(app, ["modal", str(SEED), *args])


def test_table_seed_overdamped_mesh_passes_with_note():
    r = modal()
    assert r.exit_code == 0, r.output
    assert "mesh mode" in r.output and "281.1" in r.output
    assert "not checked" in r.output  # the verdict, not "pass": nothing to check
    check = json.loads(modal("--json").stdout)["checks"][0]
    assert check["checked"] is False and check["passed"] is None
    assert check["note"].startswith("not checked: no mode has a resonant peak")


def test_json_torque_drive_rigid_and_mesh_mode():
    r = modal("--json", *TORQUE, "--set", "drive.reference_speed=3000", *LIGHT)
    assert r.exit_code == 0, r.output
    doc = json.loads(r.output)
    rigid, mesh = doc["modes"]
    assert rigid["rigid_body"] and rigid["natural_frequency_Hz"] is None
    assert rigid["shape"]["theta2_rad"] == pytest.approx(1.0)  # as lengths: r_b2 θ2 = r_b1 θ1
    assert mesh["description"].startswith("mesh mode")
    assert doc["linearisation"]["single_pair_stiffness_N_mm"] < \
        doc["linearisation"]["mesh_stiffness_N_mm"] < \
        doc["linearisation"]["double_pair_stiffness_N_mm"]
    assert doc["checks"][0]["passed"] and doc["speed_range_deg_s"] == [0.0, 4500.0]
    f = mesh["natural_frequency_Hz"]
    gmf1 = next(c for c in doc["crossings"] if c["order"] == "1x GMF")
    assert gmf1["pinion_speed_deg_s"] == pytest.approx(f / 17 * 360)


def test_margin_violated_exit_4():
    # 1x GMF right at the mesh mode (f = 500.07 Hz: n1 = f/17 rev/s = 10590 deg/s)
    r = modal(*TORQUE, "--set", "drive.reference_speed=10590", *LIGHT)
    assert r.exit_code == 4, r.output
    assert "resonance_margin_percent" in r.output


def test_plot_written(tmp_path):
    out = tmp_path / "campbell.png"
    r = modal("--plot", str(out), "--speed-range", "0", "6000", *TORQUE,
              "--set", "drive.reference_speed=3000", *LIGHT)
    assert r.exit_code == 0, r.output
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("override, key", [
    ("contact.stiffness=-1", "contact.stiffness"),
    ("gears.gear.inertia.model=given", "gears.gear.inertia"),
    ("gears.pinion.inertia.extra=-1", "gears.pinion.inertia.extra"),
])
def test_bad_input_exit_1_names_key(override, key):
    r = modal("--set", override)
    assert r.exit_code == 1, r.output
    assert key in r.output


def test_zero_inertia_exit_1(write_case, seed_text):
    text = seed_text.replace("    teeth: 25                 # driven (body 2)",
                             "    teeth: 25\n    inertia: {model: given, value: 0}")
    r = runner.invoke(app, ["modal", str(write_case(text))])
    assert r.exit_code == 1, r.output
    assert "gears.gear.inertia.value" in r.output


def test_bad_speed_range_exit_1():
    r = modal("--speed-range", "100", "50")
    assert r.exit_code == 1, r.output
    assert "--speed-range" in r.output


# --- lateral-torsional model and the full torsional chain (issue 5) ---------------------------
def bearings(value="2e6"):
    return [a for b in ("pinion", "gear") for d in "xy"
            for a in ("--set", f"bearings.{b}.stiffness_{d}={value}")]


LATERAL = ["--set", "model=lateral-torsional", *bearings()]


def test_lateral_table_happy_path(tmp_path):
    out = tmp_path / "campbell.svg"
    r = runner.invoke(app, ["modal", str(SEED), *LATERAL, "--plot", str(out)],
                      env={"COLUMNS": "250"})  # no wrapping inside the table cells
    assert r.exit_code == 0, r.output
    assert "lateral-torsional model" in r.output
    assert "lateral: gear on its bearings" in r.output and "mesh mode" in r.output
    assert "x1, y1, x2, y2" in r.output and "(overdamped)" in r.output
    svg = out.read_text()
    assert "lateral-torsional model" in svg and "pinion x1" in svg


def test_lateral_json_fields():
    r = modal("--json", *LATERAL, "--set", "bearings.gear.stiffness_y=2e6 N/mm")
    assert r.exit_code == 0, r.output
    doc = json.loads(r.output)
    assert doc["model"] == "lateral-torsional"
    assert doc["dofs"] == ["theta2_rad", "x1_mm", "y1_mm", "x2_mm", "y2_mm"]
    assert doc["bodies"]["gear_mass_t"] > doc["bodies"]["pinion_mass_t"] > 0
    for m in doc["modes"]:
        assert list(m["shape"]) == doc["dofs"] and max(map(abs, m["shape"].values())) == 1.0
        assert set(m["strain_energy_share"]) == {"mesh", "pinion bearings", "gear bearings"}
        assert sum(m["strain_energy_share"].values()) == pytest.approx(1.0)
    freqs = [m["natural_frequency_Hz"] for m in doc["modes"]]
    assert freqs == sorted(freqs) and len(freqs) == 5


def test_torque_drive_with_motor_and_load_inertia_json():
    r = modal("--json", *TORQUE, "--set", "drive.reference_speed=3000",
              "--set", "drive.motor_inertia=5e5", "--set", "drive.shaft.stiffness=1e8",
              "--set", "load.inertia=2e6", "--set", "load.shaft.stiffness=2e8", *LIGHT,
              "--set", "checks.harmonics=3")  # 4 f_z would be 6.5 % from the mesh mode
    assert r.exit_code == 0, r.output
    doc = json.loads(r.output)
    assert doc["dofs"] == ["theta_m_rad", "theta1_rad", "theta2_rad", "theta_L_rad"]
    rigid = doc["modes"][0]
    assert rigid["rigid_body"] and rigid["shape"]["theta_L_rad"] == pytest.approx(1.0)
    assert any("drive shaft" in m["description"] for m in doc["modes"])
    assert any("load shaft" in m["description"] for m in doc["modes"])


@pytest.mark.parametrize("overrides, key", [
    (["--set", "model=lateral-torsional", *bearings(), "--set",
      "bearings.pinion.stiffness_x=-5e5"], "bearings.pinion.stiffness_x"),
    (["--set", "model=lateral-torsional", *bearings()[:6]], "bearings.gear.stiffness_y"),
    (["--set", "model=lateral-torsional"], "bearings.pinion.stiffness_x"),
    (["--set", "load.inertia=0", "--set", "load.shaft.stiffness=1e6"], "load.inertia"),
    ([*TORQUE, "--set", "drive.motor_inertia=-1", "--set", "drive.shaft.stiffness=1e6"],
     "drive.motor_inertia"),
    (["--set", "bearings.gear.stiffness_x=1e6"], "bearings.gear.stiffness_x"),  # torsional
])
def test_bad_full_model_input_exit_1_names_key(overrides, key):
    r = modal(*overrides)
    assert r.exit_code == 1, r.output
    first = r.stderr.strip().splitlines()[0]
    assert first.startswith("error:") and key in first
    assert "Traceback" not in r.output
