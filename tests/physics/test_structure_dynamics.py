"""Optional bodies of the kernel (issue 5): lateral-torsional supports, motor and load inertias.

Checks against statics and limits that hold exactly, and the energy balance with every body
present (model/structure.py, core/rhs.py).
"""

import math

import numpy as np
import pytest

from gearcli.pipeline.simulate import run_simulation
from tests.conftest import ROOT
from tests.physics.simrun import run, window

DRIVETRAIN = ROOT / "cases" / "drivetrain.yaml"
NO_FRICTION = "friction.enabled=false"


def lateral(k_N_mm: float, c_Ns_mm: float = 0.0) -> list[str]:
    """Overrides: the lateral-torsional model on equal supports in x and y."""
    out = ["model=lateral-torsional"]
    for body in ("pinion", "gear"):
        for d in "xy":
            out += [f"bearings.{body}.stiffness_{d}={k_N_mm}",
                    f"bearings.{body}.damping_{d}={c_Ns_mm}"]
    return out


def wmean(res, name):
    return float(np.mean(res.columns()[name][window(res)]))


def test_energy_balance_closes_with_every_body():
    """Motor inertia + drive shaft + motor curve, lateral supports with damping, load shaft +
    load inertia, friction on: stored energy (kinetic, contact, springs) = work in - work out -
    losses. At rtol = atol = 1e-9 the residual is integration error only (measured 4.2e-9)."""
    res = run_simulation(DRIVETRAIN, ["run.end_time=0.3", "run.rtol=1e-9", "run.atol=1e-9"])
    eb = res.summary.energy_balance
    assert eb.relative_residual < 1e-6, eb
    assert eb.delta_spring_mJ > 0.0 and eb.loss_bearing_mJ > 0.0
    c = res.columns()
    for loss in ("loss_bearing_mJ", "loss_damping_mJ", "loss_friction_mJ"):
        assert np.all(np.diff(c[loss]) >= -1e-9), loss
    assert np.all(c["friction_power_mW"] <= 0.0)  # sliding speed includes the centres' motion
    for name in ("x1_mm", "bearing_force_y2_N", "omega_motor_rad_s", "load_shaft_torque_Nmm"):
        assert name in c


def test_bearing_forces_carry_the_mesh_force():
    """Statics: without friction the mean bearing forces are the mean normal force along the
    drive line of action, n_d = (sin a_w, cos a_w) on the gear, its opposite on the pinion.
    The supports' oscillation averages out over the window (0.3 % allowed for what is left of
    the transients; measured 0.02-0.03 %)."""
    res = run(NO_FRICTION, *lateral(5e5, 20.0))
    f = wmean(res, "force_total_N")
    aw = res.geometry.geometry.alpha_w_rad
    expect = {"bearing_force_x1_N": -f * math.sin(aw), "bearing_force_y1_N": -f * math.cos(aw),
              "bearing_force_x2_N": f * math.sin(aw), "bearing_force_y2_N": f * math.cos(aw)}
    for name, value in expect.items():
        assert wmean(res, name) == pytest.approx(value, rel=3e-3), name
    # the centres move apart along the line of action: x1 < 0 < x2, y1 < 0 < y2
    assert wmean(res, "x1_mm") < 0.0 < wmean(res, "x2_mm")
    assert wmean(res, "y1_mm") < 0.0 < wmean(res, "y2_mm")
    assert res.kernel.extremum("bearing_force_max_2_N") >= math.hypot(
        wmean(res, "bearing_force_x2_N"), wmean(res, "bearing_force_y2_N"))


def test_stiff_supports_reduce_to_the_torsional_model():
    """Bearings 1e9 N/mm move the centres by ~4e-6 mm under the seed's load (0.02 % of the
    DTE): the lateral-torsional results equal the torsional ones within 0.5 %."""
    tors = run(NO_FRICTION).summary
    lat = run(NO_FRICTION, *lateral(1e9, 100.0)).summary
    for key in ("force_mean_N", "force_max_N", "dte_mean_mm", "dte_peak_to_peak_mm",
                "gear_speed_mean_deg_s"):
        assert getattr(lat, key) == pytest.approx(getattr(tors, key), rel=5e-3), key


def test_load_inertia_on_a_stiff_shaft_reduces_to_the_load_on_the_gear():
    """A small load inertia (1/300 of the gear's) on a stiff load shaft (5 kHz) passes the
    load torque through: the same run as the load on the gear (0.5 %), and the shaft's mean
    torque is the load torque (0.1 %: exact at constant speed)."""
    tors = run(NO_FRICTION).summary
    res = run(NO_FRICTION, "load.shaft.stiffness=1e9", "load.shaft.damping=1e4",
              "load.inertia=1 t*mm^2")
    s = res.summary
    for key in ("force_mean_N", "force_max_N", "dte_peak_to_peak_mm", "gear_speed_mean_deg_s"):
        assert getattr(s, key) == pytest.approx(getattr(tors, key), rel=5e-3), key
    assert wmean(res, "load_shaft_torque_Nmm") == pytest.approx(4.5e5, rel=1e-3)
    assert wmean(res, "omega_load_rad_s") == pytest.approx(wmean(res, "omega2_rad_s"), rel=1e-6)


def test_motor_curve_sets_the_steady_speed_of_the_drivetrain():
    """Torque drive on the motor inertia: at steady state the motor's torque T0 (1 - w/w0)
    carries the load torque reduced to the pinion plus the power P the dampers dissipate
    (mesh damping, shafts, bearings; friction off): T0 (1 - w/w0) = T_load r_b1/r_b2 + P/w.
    Without P this would give 3000 deg/s; the measured P (~ 30 W) lowers it by 0.18 %.
    Tolerance 0.05 %: what is left of the drivetrain's slow transient in the last 0.4 s."""
    res = run_simulation(DRIVETRAIN, [NO_FRICTION])
    c = res.columns()
    late = np.flatnonzero(c["t_s"] >= 1.1)
    g = res.geometry.geometry
    t = c["t_s"][late]
    loss = c["loss_bearing_mJ"][late] + c["loss_damping_mJ"][late]
    power = (loss[-1] - loss[0]) / (t[-1] - t[0])  # [N*mm/s]
    w_motor = np.mean(c["omega_motor_rad_s"][late])
    w0 = math.radians(6000.0)
    torque = 4.5e5 * g.pinion.r_b_mm / g.gear.r_b_mm + power / w_motor
    assert power > 0.0
    assert w_motor == pytest.approx(w0 * (1.0 - torque / 6.12e5), rel=5e-4)
    assert np.mean(c["omega1_rad_s"][late]) == pytest.approx(w_motor, rel=1e-6)
    # the shafts carry the torques: the load shaft the load torque, the drive shaft the
    # motor's torque (both as means over the oscillation, 0.2 %)
    assert np.mean(c["load_shaft_torque_Nmm"][late]) == pytest.approx(4.5e5, rel=2e-3)
    assert np.mean(c["drive_shaft_torque_Nmm"][late]) == pytest.approx(
        np.mean(c["drive_torque_Nmm"][late]), rel=2e-3)
