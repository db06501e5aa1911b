"""`gearcli modal`: table, JSON, Campbell plot, the margin check's exit codes, bad input."""

import json

import pytest
from typer.testing import CliRunner

import gearcli.cli.modal  # noqa: F401  (registers the command until cli/__init__ imports it)
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
    assert "no resonant peak" in r.output


def test_json_torque_drive_rigid_and_mesh_mode():
    r = modal("--json", *TORQUE, "--set", "drive.reference_speed=3000", *LIGHT)
    assert r.exit_code == 0, r.output
    doc = json.loads(r.output)
    rigid, mesh = doc["modes"]
    assert rigid["rigid_body"] and rigid["natural_frequency_Hz"] is None
    assert rigid["shape"]["theta2_rad"] == pytest.approx(17 / 25)
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
