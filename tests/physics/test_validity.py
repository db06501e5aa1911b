"""The validity guard (issue 15, docs/theory.md §10.2): a run that leaves the model's range ends
with status ``invalid``, a one-line reason and exit code 4; its numbers are not reported as
results (CLI table, analyze, sweeps)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from typer.testing import CliRunner

from gearcli.cli import app
from gearcli.pipeline.simulate import run_simulation
from gearcli.pipeline.validity import (
    ENERGY_RESIDUAL_LIMIT,
    INVALID,
    OK,
    check_validity,
    penetration_limit_mm,
)
from tests.conftest import SEED

runner = CliRunner()

# The seed pair and load with the linear ISO stiffness (`stiffness: derived`, e = 1; static
# deflection 2.3 µm) at the speed where the mesh frequency equals the mesh mode (f_n = 1393 Hz):
# its IMPACT damping is ~0 at µm penetrations (ζ = 0.0006), so the teeth hammer both flanks
# without backlash: dynamic factor 65, 186 kN on the coast flank, penetration 0.074 mm = 32 δ_s
# when measured. The "zero-backlash resonance case".
F_N = 1393.06
RESONANCE = ["contact.stiffness=derived", "contact.exponent=1",
             f"drive.speed=STEP(time, 0, 0, 0.05, {F_N / 17 * 360})",
             "load.torque=STEP(time, 0, 0, 0.05, 4.5e5)", f"run.end_time={0.05 + 300 / F_N}"]
BACKLASH = ["gears.pinion.thickness_allowance=0.2 mm"]


def test_zero_backlash_resonance_is_invalid_and_with_backlash_it_is_valid():
    res = run_simulation(SEED, RESONANCE)
    assert res.status == INVALID
    assert res.invalid_reason.startswith("tooth penetration ")
    assert "\n" not in res.invalid_reason
    pen = res.kernel.extremum("penetration_max_mm")
    assert pen > 10 * res.kernel_input.mesh.static_deflection_mm
    # with 0.2 mm less pinion tooth thickness the coast flank is out of reach: a valid run
    # (measured: dynamic factor 2.8, tooth separation 38 % of the time, no coast contact)
    ok = run_simulation(SEED, [*RESONANCE, *BACKLASH])
    assert ok.status == OK and ok.invalid_reason == ""
    assert ok.summary.coast_force_max_N == 0.0
    assert ok.kernel.extremum("penetration_max_mm") < 10 * ok.kernel_input.mesh.static_deflection_mm


def test_simulate_and_run_exit_4_keep_the_marked_run_and_analyze_refuses_it(tmp_path):
    sets = [a for s in RESONANCE for a in ("--set", s)]
    out = tmp_path / "sim"
    res = runner.invoke(app, ["simulate", str(SEED), "-o", str(out), *sets])
    assert res.exit_code == 4, res.output
    last = res.output.strip().splitlines()[-1]
    assert last.startswith("error: ") and "tooth penetration" in last and "marked invalid" in last
    assert "not valid" in res.output  # the table does not show the factor as a result
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == "invalid" and summary["invalid_reason"].startswith("tooth")
    res = runner.invoke(app, ["analyze", str(out)])
    assert res.exit_code == 4 and "outside the model's validity" in res.output
    res = runner.invoke(app, ["run", str(SEED), "-o", str(tmp_path / "run"), *sets])
    assert res.exit_code == 4 and "no analysis or report" in res.output
    assert json.loads((tmp_path / "run" / "summary.json").read_text())["status"] == "invalid"
    assert not list((tmp_path / "run").glob("report.*"))


def test_sweep_marks_invalid_points_and_leaves_their_metrics_empty(tmp_path):
    study = tmp_path / "study.yaml"
    study.write_text(f"base: {SEED}\nset:\n"
                     + "".join(f"  {k}: {v}\n" for k, v in (s.split("=", 1) for s in RESONANCE))
                     + "parameters:\n  gears.pinion.thickness_allowance: [0 mm, 0.2 mm]\n")
    out = tmp_path / "out"
    res = runner.invoke(app, ["sweep", str(study), "-o", str(out), "--jobs", "1"])
    assert res.exit_code == 0, res.output
    assert "1 invalid (outside the model's validity)" in res.output
    import pandas as pd

    df = pd.read_csv(out / "summary.csv")
    bad, good = df.iloc[0], df.iloc[1]
    assert bad["status"] == "invalid" and bad["error"].startswith("tooth penetration")
    assert np.isnan(bad["dynamic_factor"])
    assert good["status"] == "ok" and good["dynamic_factor"] > 1.0


# --- the rules one by one (pure function) ---------------------------------------------------
def _check(**kw):
    args = dict(penetration_max_mm=0.01, static_deflection_mm=0.005, module_mm=5.0,
                gear_speed_rad_s=np.full(10, 50.0), pinion_speed_rad_s=None, window_s=0.1,
                teeth=(20, 40),
                energy_relative_residual=1e-8)
    args.update(kw)
    return check_validity(**args)


def test_penetration_limit_is_ten_static_deflections_at_most_five_percent_of_the_thickness():
    assert penetration_limit_mm(0.005, 5.0) == pytest.approx(0.05)
    assert penetration_limit_mm(0.1, 5.0) == pytest.approx(0.05 * np.pi * 5.0 / 2)
    assert penetration_limit_mm(0.0, 2.0) == pytest.approx(0.05 * np.pi)  # no load
    assert _check(penetration_max_mm=0.0499).status == OK
    assert _check(penetration_max_mm=0.0501).status == INVALID
    assert _check(penetration_max_mm=float("nan")).status == INVALID


def test_speed_reversal_and_energy_residual_are_invalid():
    back = np.array([50.0, 20.0, -0.5, 30.0])  # mean 24.9: -0.5 is 2 % of it
    assert _check(gear_speed_rad_s=np.array([50.0, 20.0, -0.2, 30.0])).status == OK  # 0.8 %
    v = _check(gear_speed_rad_s=back)
    assert v.status == INVALID and v.reason.startswith("the gear reverses")
    assert "speed -28.65 deg/s against its mean of 1425 deg/s" in v.reason  # signs as they are
    # backwards throughout (a load larger than a torque drive): judged against the sign of
    # its own mean this passed, and the run reported a dynamic factor
    v = _check(gear_speed_rad_s=np.full(10, -50.0))  # 0.1 s: 31.8 pitches of a 40-tooth gear
    assert v.status == INVALID and v.reason.startswith("the gear runs backwards in the steady "
                                                       "window (mean speed -2865 deg/s, 31.8")
    # a gear creeping back by its deflection (ring-down at rest, -0.0126 deg/s measured): no
    creep = np.full(10, -2.2e-4)
    assert "runs backwards" not in _check(gear_speed_rad_s=creep).reason
    assert _check(gear_speed_rad_s=-back).status == INVALID  # a reverse-running gear likewise
    # a ring-down at rest dithers about zero: judged by its dither, not as running backwards
    dither = np.array([1e-6, -1.1e-6, 1.2e-6, -1e-6])
    assert "runs backwards" not in _check(gear_speed_rad_s=dither).reason
    v = _check(pinion_speed_rad_s=back)
    assert v.status == INVALID and "pinion" in v.reason
    assert _check(energy_relative_residual=0.5 * ENERGY_RESIDUAL_LIMIT).status == OK
    v = _check(energy_relative_residual=2 * ENERGY_RESIDUAL_LIMIT)
    assert v.status == INVALID and v.reason.startswith("energy balance residual")
