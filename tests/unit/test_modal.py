"""Modal analysis of the torsional model: closed forms, the no-peak rule, the resonance map, and
a second method (free ring-down in `simulate`). The full model (motor, load shaft, lateral):
tests/unit/test_modal_full.py."""

import dataclasses
import math

import numpy as np
import pytest

from gearcli.model.modal import (
    NO_PEAK_DAMPING_RATIO,
    LinearSystem,
    crossings,
    excitation_orders,
    has_resonant_peak,
    linear_modes,
    margins,
)
from gearcli.model.structure import Structure
from tests.conftest import SEED

J1, J2, RB1, RB2, K = 2.0, 5.0, 40.0, 60.0, 1.0e5  # t*mm^2, mm, N/mm


def TorsionalSystem(J1, J2, rb1, rb2, k, c, drive, shaft_stiffness_Nmm_rad=0.0,
                    pinion_damping_Nmms_rad=0.0):
    """The 2-DOF torsional pair (+ drive shaft) as a LinearSystem (torsional model)."""
    st = Structure("torsional", drive, J1, J2, 0.0, 0.0, rb1, rb2, math.radians(20.0),
                   drive_shaft_stiffness_Nmm_rad=shaft_stiffness_Nmm_rad,
                   pinion_bearing_damping_Nmms_rad=pinion_damping_Nmms_rad)
    return LinearSystem(st, k, c)


torsional_modes = linear_modes


def two_pi(f):
    return f / (2.0 * math.pi)


def test_both_free_mesh_mode_and_rigid_mode():
    modes = torsional_modes(TorsionalSystem(J1, J2, RB1, RB2, K, 0.0, "torque")).modes
    rigid, mesh = modes
    assert rigid.rigid and rigid.natural_frequency_Hz is None and rigid.damping_ratio is None
    # θ2 in the gear's own sense: a rigid turn of the pair has r_b1 θ1 = r_b2 θ2.
    # shapes are lengths (rotations as r_b θ): the rigid turn has equal roll distances
    assert rigid.shape[1] / rigid.shape[0] == pytest.approx(1.0, rel=1e-12)
    assert mesh.natural_frequency_Hz == pytest.approx(
        two_pi(math.sqrt(K * (RB1**2 / J1 + RB2**2 / J2))), rel=1e-12)
    # M-orthogonal to the rigid mode: J1 φ1 r_b2 + J2 φ2 r_b1 = 0, i.e. as lengths
    # (r_b2 φ2) / (r_b1 φ1) = -J1 r_b2² / (J2 r_b1²).
    assert mesh.shape[1] / mesh.shape[0] == pytest.approx(-J1 * RB2**2 / (J2 * RB1**2),
                                                          rel=1e-12)
    assert mesh.description.startswith("mesh mode")
    assert max(abs(v) for v in mesh.shape) == 1.0


def test_mesh_damping_ratio_matches_closed_form():
    c = 0.5
    mesh = torsional_modes(TorsionalSystem(J1, J2, RB1, RB2, K, c, "torque")).elastic[0]
    m_e = 1.0 / (RB1**2 / J1 + RB2**2 / J2)
    zeta = c / (2.0 * math.sqrt(K * m_e))
    assert mesh.damping_ratio == pytest.approx(zeta, rel=1e-9)
    assert mesh.damped_frequency_Hz == pytest.approx(
        mesh.natural_frequency_Hz * math.sqrt(1 - zeta**2), rel=1e-9)


@pytest.mark.parametrize("c", [1.0, 500.0])  # under- and overdamped
def test_prescribed_pinion_speed_only_gear_moves(c):
    res = torsional_modes(TorsionalSystem(J1, J2, RB1, RB2, K, c, "speed",
                                          pinion_damping_Nmms_rad=7.0))
    assert res.dofs == ("theta2_rad",)
    (mode,) = res.modes
    assert mode.natural_frequency_Hz == pytest.approx(two_pi(math.sqrt(K * RB2**2 / J2)),
                                                      rel=1e-12)
    assert mode.damping_ratio == pytest.approx(c * RB2**2 / (2 * math.sqrt(K * RB2**2 * J2)),
                                               rel=1e-9)
    assert (mode.damped_frequency_Hz is None) == (mode.damping_ratio > 1.0)


def test_two_inertia_shaft_with_stiff_mesh():
    ks = 1.0e6  # N*mm/rad; mesh 1e4 x stiffer than the shaft as seen by the pinion
    res = torsional_modes(TorsionalSystem(J1, J2, RB1, RB2, 1e4 * ks / RB1**2, 0.0, "shaft",
                                          shaft_stiffness_Nmm_rad=ks))
    shaft, mesh = res.modes
    j_eq = J1 + J2 * (RB1 / RB2) ** 2
    assert shaft.natural_frequency_Hz == pytest.approx(two_pi(math.sqrt(ks / j_eq)), rel=1e-3)
    assert shaft.description.startswith("torsional: drive shaft")
    assert shaft.shape[1] / shaft.shape[0] == pytest.approx(1.0, rel=1e-3)  # equal r_b θ
    assert mesh.description.startswith("mesh mode")


def test_zero_inertia_rejected():
    with pytest.raises(ValueError, match="J2_t_mm2 must be > 0"):
        torsional_modes(TorsionalSystem(J1, 0.0, RB1, RB2, K, 0.0, "torque"))


def test_no_peak_rule_is_shared_with_analyze():
    import gearcli.pipeline.analyze as analyze

    assert analyze.has_resonant_peak is has_resonant_peak
    assert has_resonant_peak(0.70) and not has_resonant_peak(NO_PEAK_DAMPING_RATIO)


def test_crossings_and_margins():
    mesh = torsional_modes(TorsionalSystem(J1, J2, RB1, RB2, K, 0.5, "torque")).elastic[0]
    f = mesh.natural_frequency_Hz
    orders = excitation_orders(17, 25, 3)
    assert [o.name for o in orders] == ["1x GMF", "2x GMF", "3x GMF", "1x pinion", "1x gear"]
    cross = {c.order: c.pinion_speed_rev_s for c in crossings([mesh], orders)}
    assert cross["2x GMF"] == pytest.approx(f / 34.0)
    assert cross["1x gear"] == pytest.approx(f * 25 / 17)
    near = margins([mesh], orders, f / 34.0 * 1.05)[0]  # 2x GMF 5 % above the mode
    assert near.order == "2x GMF" and near.margin_percent == pytest.approx(5.0)
    assert near.has_peak


# --- second method: free ring-down in the time-domain solver ----------------------------------
# Linear contact (e = 1), friction off, small contact damping, gears at rest in the single-pair
# zone (θ1 = 0 puts a pair at the pitch point), the load applied at t = 0: the DTE rings down
# about the static deflection in the mesh mode of the single-pair stiffness k.
RING = ["friction.enabled=false", "contact.exponent=1", "contact.stiffness=5e4",
        "contact.max_damping=0.5", "load.torque=4.5e4", "run.end_time=0.04",
        "run.output_rate=2e5"]
DRIVES = {"speed": ["drive.speed=0"],
          # balanced drive torque T_load r_b1/r_b2: the rigid-body mode is not excited
          "torque": ["drive.type=torque", "drive.speed=null", "drive.torque=3.06e4"]}


def ring_down_frequency_Hz(t, x):
    x = x - np.mean(x[x.size // 2:])
    up = np.nonzero((x[:-1] < 0.0) & (x[1:] >= 0.0))[0]
    tc = t[up] - x[up] * (t[up + 1] - t[up]) / (x[up + 1] - x[up])
    return (tc.size - 1) / (tc[-1] - tc[0])


@pytest.mark.parametrize("drive", sorted(DRIVES))
def test_ring_down_in_simulate_matches_modal(drive):
    from gearcli.pipeline.modal import run_modal
    from gearcli.pipeline.simulate import run_simulation

    overrides = RING + DRIVES[drive]
    sim = run_simulation(SEED, overrides)
    pairs = sim.kernel.column("pairs_in_contact")[1:]
    assert np.all(pairs == 1)  # the contact never opens and no second pair engages
    f_sim = ring_down_frequency_Hz(sim.kernel.column("t_s"), sim.kernel.column("delta_mm"))
    system = run_modal(SEED, overrides).system
    single = dataclasses.replace(system, mesh_stiffness_N_mm=5e4)  # one pair, e = 1
    mode = linear_modes(single).elastic[0]
    assert f_sim == pytest.approx(mode.damped_frequency_Hz, rel=0.02)
