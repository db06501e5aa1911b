"""Linearised mesh mode against hand calculations for the seed case."""

import math

import numpy as np
import pytest

from gearcli.core.stepfunc import step as adams_step
from gearcli.model.mesh import mesh_mode

# Seed: F_s = 450e3 N*mm / r_b2, r_b2 = 125 cos 20 deg; discs of d = 170/250 mm, b = 100 mm.
RB1, RB2 = 85 * math.cos(math.radians(20)), 125 * math.cos(math.radians(20))
RHO = 7.85e-9
J1 = RHO * math.pi * 170**2 / 4 * 100 * 170**2 / 8
J2 = RHO * math.pi * 250**2 / 4 * 100 * 250**2 / 8
EPS = 1.56323


def test_adams_step():
    assert adams_step(-1, 0, 0, 1, 5) == 0 and adams_step(2, 0, 0, 1, 5) == 5
    assert adams_step(0.5, 0, 0, 1, 5) == pytest.approx(2.5)
    assert adams_step(0.25, 0, 0, 1, 1) == pytest.approx(0.25**2 * (3 - 0.5))


def test_seed_mesh_mode_motion_driven_pinion():
    f = 450e3 / RB2
    mm = mesh_mode(f, EPS, 1e5, 1.5, 100.0, 0.1, RB1, RB2, J1, J2, pinion_free=False)
    p = (f / (EPS * 1e5)) ** (1 / 1.5)  # hand calculation
    k_mesh = EPS * 1.5e5 * math.sqrt(p)
    m = J2 / RB2**2
    assert mm.static_force_N == pytest.approx(3831.0, rel=1e-3)
    assert mm.mesh_stiffness_N_mm == pytest.approx(k_mesh, rel=1e-12)
    assert mm.natural_frequency_Hz == pytest.approx(math.sqrt(k_mesh / m) / (2 * math.pi))
    c = EPS * 100 * (p / 0.1) ** 2 * (3 - 2 * p / 0.1)
    assert mm.damping_ratio == pytest.approx(c / (2 * math.sqrt(k_mesh * m)), rel=1e-12)
    assert mm.damping_ratio > 1.0  # the seed's c_max gives an overdamped mesh (docs/theory.md §4)


def test_free_pinion_uses_equivalent_mass():
    mm = mesh_mode(1000.0, 1.5, 2e5, 1.0, 0.0, 0.1, RB1, RB2, J1, J2, pinion_free=True)
    k = 1.5 * 2e5
    f = math.sqrt(k * (RB1**2 / J1 + RB2**2 / J2)) / (2 * math.pi)  # issue 5's closed form
    assert mm.natural_frequency_Hz == pytest.approx(f, rel=1e-12)
    assert mm.single_pair_stiffness_N_mm == 2e5 and mm.double_pair_stiffness_N_mm == 4e5


def test_tooth_mesh_mode_of_a_constant_stiffness_is_the_rectangle_wave_mean():
    """k(x) = k0 on the path: k_mean = ε_α k0, single k0, double 2 k0, c_m = 2 ζ sqrt(k m)."""
    from gearcli.model.mesh import tooth_mesh_mode

    k0, g_a, p_b = 1e6, 46.1485, 29.5213
    x = np.linspace(-5.0, g_a + 5.0, 200)
    mm = tooth_mesh_mode(3831.0, x, np.full(x.size, k0), g_a, p_b, 0.07, 80.0, 117.0, 60.0,
                         300.0, pinion_free=False)
    assert mm.mesh_stiffness_N_mm == pytest.approx(k0 * g_a / p_b, rel=1e-9)
    assert mm.single_pair_stiffness_N_mm == pytest.approx(k0, rel=1e-12)
    assert mm.double_pair_stiffness_N_mm == pytest.approx(2 * k0, rel=1e-12)
    m = 300.0 / 117.0**2
    assert mm.mesh_damping_Ns_mm == pytest.approx(2 * 0.07 * math.sqrt(k0 * g_a / p_b * m))
    assert mm.static_deflection_mm == pytest.approx(3831.0 / (k0 * g_a / p_b))


def test_linearisation_follows_the_tip_relief():
    """The tooth law's mesh mode is linearised on the loaded contact (pipeline/kernel_input.
    linearised_mesh): tip relief lowers its stiffness (fewer pairs share the load near the
    tips), it equals `gearcli mesh`'s mean to 0.5 % (1 x 100 against 2 x 200 positions), and
    f_n = sqrt(k/m)/2π with the same modal mass; the geometric sum over the path ignores the
    relief (docs/theory.md §4b)."""
    import gearcli
    from gearcli.pipeline.geometry import run_geometry
    from gearcli.pipeline.kernel_input import linearised_mesh
    from gearcli.pipeline.mesh_input import case_mesh

    relief = {"modifications.tip_relief.pinion": {"amount": "15 um", "length": "3 mm"},
              "modifications.tip_relief.gear": {"amount": "15 um", "length": "3 mm"}}
    modes = {}
    for name, overrides in (("plain", {}), ("relief", relief)):
        loaded = gearcli.load_case("cases/iso_pair.yaml", set=overrides)
        geo = run_geometry(loaded)
        modes[name] = (linearised_mesh(loaded.case, geo), case_mesh(loaded.case, geo))
        k_ltca = gearcli.mesh(loaded).summary.stiffness.mesh_mean_N_mm
        lin = modes[name][0]
        assert lin.mesh_stiffness_N_mm == pytest.approx(k_ltca, rel=5e-3)
        assert lin.natural_frequency_Hz == pytest.approx(
            math.sqrt(lin.mesh_stiffness_N_mm / lin.modal_mass_t) / (2 * math.pi), rel=1e-12)
    assert modes["relief"][0].mesh_stiffness_N_mm < 0.9 * modes["plain"][0].mesh_stiffness_N_mm
    assert modes["relief"][1].mesh_stiffness_N_mm == modes["plain"][1].mesh_stiffness_N_mm


def test_static_force_includes_the_speed_dependent_resisting_torques():
    """F_static = (T_load + (c_v + c_2) ω2 + c_q ω2²)/r_b2 at the window's gear speed (docs/
    theory.md §7.3): without the load's viscous and quadratic terms the dynamic factor of a
    viscous load counted their share as dynamic (iso_pair: 1.52 instead of 1.32, at 1500 rpm).
    Hand value: ω2 = 1340 rpm · 21/43 = 68.53 rad/s (the case's speed since issue 31);
    300e3 + 500·68.53 + 1·68.53² + 200·68.53 N·mm. The
    contact model's load (linearisation, validity) stays T_load/r_b2."""
    from gearcli.pipeline.simulate import run_simulation
    from tests.conftest import ROOT

    res = run_simulation(ROOT / "cases" / "iso_pair.yaml", [
        "load.viscous=0.5 N*m*s/rad", "load.quadratic=0.001 N*m*s^2/rad^2",
        "bearings.gear.damping=0.2 N*m*s/rad", "run.end_time=0.35"], zoom=False)
    # 0.35 s at 1340 rpm: the steady window spans as many gear turns as 0.3 s at 1500 rpm did
    # (the window's mean vibration speed is the residual, 4e-7 here, 1.3e-6 with 0.3 s)
    r_b2 = res.geometry.geometry.gear.r_b_mm
    w2 = 1340 * 2 * math.pi / 60 * 21 / 43  # speed drive: the window's mean is this
    torque = 300e3 + 500 * w2 + 1.0 * w2**2 + 200 * w2
    assert res.summary.force_static_N == pytest.approx(torque / r_b2, rel=1e-6)
    assert res.kernel_input.mesh.static_force_N == pytest.approx(300e3 / r_b2, rel=1e-12)
    assert res.summary.dynamic_factor == pytest.approx(
        res.summary.force_max_N / (torque / r_b2), rel=1e-6)
