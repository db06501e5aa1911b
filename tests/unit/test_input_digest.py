"""The input digest of a run (issue 29): iso_pair's against hand formulas, and the
"did you mean" warnings of a bare torque / a slow speed."""

import json
import math

import pytest
from typer.testing import CliRunner

from gearcli import api
from gearcli.cli import app
from gearcli.pipeline.digest import slip_warnings
from gearcli.pipeline.outputs import summary_document
from tests.conftest import SEED

ISO_PAIR = SEED.parent / "iso_pair.yaml"
SHORT = ["run.end_time=0.4"]  # past the 0.2 s ramps: the digest uses the final values anyway


def test_iso_pair_digest_against_hand_formulas():
    """iso_pair: z 21/43, m 5 mm, α 20°, b 50 mm, 1340 rpm (1500 before issue 31 moved the
    case off 3 f_z = f_n), 300 N·m on the gear, E 206 GPa, ν 0.3 (cases/iso_pair.yaml)."""
    res = api.simulate(ISO_PAIR, SHORT)
    d = summary_document(res).input_digest
    geo = res.geometry.geometry
    w1 = 1340 * 2 * math.pi / 60  # [rad/s]
    d1, d2, b = 21 * 5.0, 43 * 5.0, 50.0  # [mm]
    f_t = 300e3 / (d2 / 2)  # T2/r2 [N]
    v = w1 * d1 / 2 / 1000  # [m/s]
    # all relative 1e-9: the same closed forms, only the order of operations differs
    assert d.pitch_line_velocity_m_s == pytest.approx(v, rel=1e-9)  # 7.367 m/s
    assert d.line_load_N_mm == pytest.approx(f_t / b, rel=1e-9)  # 55.81 N/mm
    assert d.power_kW == pytest.approx(300 * w1 * 21 / 43 / 1000, rel=1e-9)  # T2 ω2 = 20.6 kW
    assert d.gear_mesh_frequency_Hz == pytest.approx(21 * 1340 / 60, rel=1e-9)  # 469 Hz
    assert d.resonance_ratio == pytest.approx(469 / res.summary.mesh_natural_frequency_Hz,
                                              rel=1e-9)
    # ISO 6336-2 eq. 4 with Z_ε, spur: Z_E = √(E/(2π(1-ν²))) for equal materials
    a, aw = math.radians(20), geo.alpha_w_rad
    z_h = math.sqrt(2 * math.cos(aw) / (math.cos(a) ** 2 * math.sin(aw)))
    z_e = math.sqrt(206e3 / (2 * math.pi * (1 - 0.3 ** 2)))
    z_eps = math.sqrt((4 - geo.eps_alpha) / 3)
    u = 43 / 21
    sigma = z_eps * z_h * z_e * math.sqrt(f_t * (u + 1) / (d1 * b * u))
    assert d.sigma_H0_MPa == pytest.approx(sigma, rel=1e-9)
    assert d.warnings == ()
    assert json.loads(json.dumps(summary_document(res).to_dict()))["input_digest"][
        "line_load_N_mm"] == pytest.approx(f_t / b, rel=1e-9)


def test_bare_torque_on_seed_warns_did_you_mean_Nm():
    """The seed with `torque: 450` (N·mm, meant 450 N·m): F_t/b = 0.036 N/mm on module 10."""
    r = CliRunner().invoke(app, ["simulate", str(SEED), "-o", "-", "--set", "load.torque=450",
                                 "--set", "run.end_time=1.2"])
    assert "did you mean N·m? bare torques read as N·mm" in r.stderr


def test_a_tiny_torque_written_with_its_unit_is_no_slip():
    """`torque: 0.45 N*m` on the seed is as tiny (0.036 N/mm) but says what it means: the
    warning calls it implausible, without "did you mean N·m?" (the user wrote N·m) or "reads
    as N·mm" (it does not)."""
    r = CliRunner().invoke(app, ["simulate", str(SEED), "-o", "-", "--set",
                                 "load.torque=0.45 N*m", "--set", "run.end_time=1.2"])
    assert "load.torque: F_t/b = 0.036 N/mm" in r.stderr, r.stderr
    assert "implausibly small for the pair, as written" in r.stderr
    assert "did you mean" not in r.stderr and "N·mm" not in r.stderr


def test_slip_warnings_thresholds():
    assert slip_warnings(0.5, 5.0, 5.0)[0].startswith("load.torque")
    assert slip_warnings(0.5, 5.0, 4.0) == []  # a small module may carry little load
    assert slip_warnings(50.0, 5.0, 10.0) == []
    assert "did you mean rpm?" in slip_warnings(50.0, 0.01, 10.0)[0]
    assert slip_warnings(50.0, 0.1, 10.0) == []


def test_slip_warnings_speak_the_case_unit_system():
    """A bare torque is N·mm only in "adams" (the default): in an engineering or SI case it is
    N·m already, and "did you mean N·m? the torque reads as N·mm" was false there. A bare speed
    is rpm in "engineering" (no "did you mean rpm?"), rad/s in "si"."""
    for system in ("engineering", "si"):
        (torque,) = slip_warnings(0.5, 5.0, 5.0, system)
        assert "did you mean" not in torque and "bare torques are N*m" in torque
    assert "bare torques read as N·mm" in slip_warnings(0.5, 5.0, 5.0, "adams")[0]
    # written with units: implausible, never "did you mean" (in any system)
    for system in ("adams", "engineering", "si"):
        (torque, speed) = slip_warnings(0.5, 0.01, 5.0, system, (False, False))
        assert "did you mean" not in torque + speed and "as written" in torque
        assert "implausibly slow, as written" in speed
    (speed,) = slip_warnings(50.0, 0.01, 10.0, "engineering")
    assert "did you mean" not in speed and "bare speeds are rpm" in speed
    assert "did you mean rpm? bare speeds read as rad/s" in slip_warnings(50.0, 0.01, 10.0, "si")[0]
    assert "bare speeds read as deg/s" in slip_warnings(50.0, 0.01, 10.0, None)[0]


def test_tiny_torque_in_the_engineering_starter_is_not_called_N_mm(tmp_path):
    """`gearcli new` writes an engineering case: its 0.5 (N·m) load warns, without claiming
    that the torque reads as N·mm."""
    runner = CliRunner()
    case = tmp_path / "pair.yaml"
    assert runner.invoke(app, ["new", str(case)]).exit_code == 0
    r = runner.invoke(app, ["simulate", str(case), "-o", "-", "--set", "run.end_time=0.3",
                            "--set", "load.torque=STEP(time, 0, 0, 0.2, 0.5)"])
    assert "load.torque: F_t/b = 0.0851 N/mm" in r.stderr, r.stderr
    assert "reads as N·mm" not in r.stderr and "bare torques are N*m" in r.stderr


@pytest.mark.parametrize(("value", "bare"), [
    ("450", True), ("'450'", True), ("STEP(time, 0, 0, 0.2, 450)", True),
    ("{function: 'STEP(time, 0, 0, 0.2, 450)'}", True), ("450 N*m", False),
    ("{function: 'STEP(time, 0, 0, 0.2, 450)', unit: N*m}", False),
    ("{function: 450, unit: N*m}", False),
    ("{function: '450 N*m'}", False),  # a constant with its unit, in a mapping without unit
])
def test_written_bare_tells_a_bare_value_from_one_with_units(value, bare):
    from gearcli.case.load import load_case

    loaded = load_case(SEED, [f"load.torque={value}"])
    assert loaded.written_bare(("load", "torque")) is bare
    assert loaded.written_bare(("run", "max_step")) is False  # not written: its default


def test_a_torque_drives_bare_reference_speed_is_named_and_read_as_bare():
    """A torque drive's speed is drive.reference_speed (there is no drive.speed): written bare
    (30, deg/s in the adams units of cases/drivetrain.yaml) it is a slip like a bare
    drive.speed, not "implausibly slow, as written", and the warning names its key."""
    drivetrain = SEED.parent / "drivetrain.yaml"
    r = CliRunner().invoke(app, ["simulate", str(drivetrain), "-o", "-", "--set",
                                 "drive.reference_speed=30", "--set", "run.end_time=0.8"])
    (line,) = [w for w in r.stderr.splitlines() if "pitch-line velocity" in w]
    assert line.startswith("warning: drive.reference_speed:"), line
    assert "did you mean rpm? bare speeds read as deg/s" in line and "as written" not in line
    r = CliRunner().invoke(app, ["simulate", str(drivetrain), "-o", "-", "--set",
                                 "drive.reference_speed=30 deg/s", "--set", "run.end_time=0.8"])
    (line,) = [w for w in r.stderr.splitlines() if "pitch-line velocity" in w]
    assert "implausibly slow, as written" in line and "did you mean" not in line, line
