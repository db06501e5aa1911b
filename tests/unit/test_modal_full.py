"""Modal analysis of the full model (issue 5): motor inertia + drive shaft, load shaft + load
inertia, the lateral-torsional (6-DOF) option, linearised dampers, descriptions, and the
pipeline functions `simulate` uses (case_modes, modes_summary).

Closed forms are exact for their configuration unless a tolerance says otherwise; exact ones
use rel 1e-9 (floating-point round-off of a symmetric eigenproblem, ~1e-13, with margin).
Chains of rotors are written in pinion coordinates: the gear side reflected by (r_b1/r_b2)²
(rigid kinematics r_b1 θ1 = r_b2 θ2, docs/theory.md §1), the mesh as a torsional spring k r_b1².
"""

import dataclasses
import math

import numpy as np
import pytest

from gearcli.model.modal import LinearSystem, linear_modes, linearised_dampers
from gearcli.model.structure import Structure, Support, line_of_action
from tests.conftest import SEED

J1, J2, RB1, RB2 = 2.0, 5.0, 40.0, 60.0  # t*mm^2, mm
M1, M2 = 0.002, 0.003  # t
ALPHA = math.radians(20.0)


def hz(omega2):
    """f [Hz] from ω² [1/s²]."""
    return math.sqrt(omega2) / (2.0 * math.pi)


def structure(**kw) -> Structure:
    base = dict(model="torsional", drive="torque", J1_t_mm2=J1, J2_t_mm2=J2, m1_t=M1, m2_t=M2,
                r_b1_mm=RB1, r_b2_mm=RB2, alpha_w_rad=ALPHA)
    return Structure(**{**base, **kw})


def lateral(kx1, ky1, kx2, ky2, **kw) -> Structure:
    return structure(model="lateral-torsional", pinion_support=Support(kx1, ky1),
                     gear_support=Support(kx2, ky2), **kw)


def two_dof_roots(ja, jb, k_ground, k_between):
    """ω² of ground -k_ground- Ja -k_between- Jb: det(K - ω² M) = 0 with K = [[kg + kb, -kb],
    [-kb, kb]], i.e. Ja Jb ω⁴ - ((kg + kb) Jb + kb Ja) ω² + kg kb = 0 (Rao, Mechanical
    Vibrations, ch. 5, torsional two-degree-of-freedom system)."""
    b = (k_ground + k_between) * jb + k_between * ja
    disc = math.sqrt(b * b - 4.0 * ja * jb * k_ground * k_between)
    return sorted(((b - disc) / (2 * ja * jb), (b + disc) / (2 * ja * jb)))


def three_rotor_roots(ja, jb, jc, k1, k2):
    """Nonzero ω² of the free-free chain Ja -k1- Jb -k2- Jc (Rao, Mechanical Vibrations, ch. 6,
    multi-rotor torsional system; det(K - ω² M) = 0 with K tridiagonal):
    Ja Jb Jc ω⁴ - (k1 Jc (Ja + Jb) + k2 Ja (Jb + Jc)) ω² + k1 k2 (Ja + Jb + Jc) = 0."""
    a = ja * jb * jc
    b = k1 * jc * (ja + jb) + k2 * ja * (jb + jc)
    c = k1 * k2 * (ja + jb + jc)
    disc = math.sqrt(b * b - 4 * a * c)
    return sorted(((b - disc) / (2 * a), (b + disc) / (2 * a)))


# --- torsional chain ----------------------------------------------------------------------------
@pytest.mark.parametrize("k_shaft", [1.0e5, 1.6e7])  # well separated / strongly coupled
def test_motor_drive_shaft_pinion_gear_three_rotor_chain(k_shaft):
    jm, k_mesh = 3.0, 1.0e4
    res = linear_modes(LinearSystem(structure(motor_inertia_t_mm2=jm,
                                              drive_shaft_stiffness_Nmm_rad=k_shaft), k_mesh))
    assert res.dofs == ("theta_m_rad", "theta1_rad", "theta2_rad")
    rigid, low, high = res.modes
    expected = three_rotor_roots(jm, J1, J2 * (RB1 / RB2) ** 2, k_shaft, k_mesh * RB1**2)
    assert [low.natural_frequency_Hz, high.natural_frequency_Hz] == pytest.approx(
        [hz(w2) for w2 in expected], rel=1e-9)
    # rigid rotation of the whole train: θm = θ1, θ2 = θ1 r_b1/r_b2
    assert rigid.rigid and rigid.natural_frequency_Hz is None
    assert rigid.shape == pytest.approx((1.0, 1.0, 1.0), rel=1e-9)  # equal r_b θ
    assert rigid.description == "rigid-body rotation (the whole drive train turns together)"
    if k_shaft < 1e6:  # shaft 160x softer than the mesh (k r_b1² = 1.6e7 N*mm/rad)
        assert low.description == "torsional: drive shaft (motor against pinion)"
        assert high.description == "mesh mode (gears against each other)"
    else:
        assert "coupled" in low.description or "coupled" in high.description


def test_two_inertia_shaft_without_mesh():
    """k_mesh = 0: the motor and pinion on their shaft, ω² = k_s (1/J_m + 1/J1) exactly; the
    gear and the motor-pinion pair are two rigid bodies."""
    jm, ks = 3.0, 2.0e5
    res = linear_modes(LinearSystem(structure(motor_inertia_t_mm2=jm,
                                              drive_shaft_stiffness_Nmm_rad=ks), 0.0))
    assert [m.rigid for m in res.modes] == [True, True, False]
    assert {m.description for m in res.modes[:2]} == {
        "rigid-body rotation of the gear alone",
        "rigid-body rotation of the motor and pinion alone"}
    shaft = res.modes[2]
    assert shaft.natural_frequency_Hz == pytest.approx(hz(ks * (1 / jm + 1 / J1)), rel=1e-9)
    assert shaft.shape == pytest.approx((-J1 / jm, 1.0, 0.0), abs=1e-12)


def test_shaft_drive_pinion_on_prescribed_motor_exact():
    ks, k_mesh = 3.0e6, 2.0e3
    res = linear_modes(LinearSystem(structure(drive="shaft", drive_shaft_stiffness_Nmm_rad=ks),
                                    k_mesh))
    assert res.dofs == ("theta1_rad", "theta2_rad") and not any(m.rigid for m in res.modes)
    expected = two_dof_roots(J1, J2 * (RB1 / RB2) ** 2, ks, k_mesh * RB1**2)
    assert [m.natural_frequency_Hz for m in res.modes] == pytest.approx(
        [hz(w2) for w2 in expected], rel=1e-9)


def test_load_shaft_with_prescribed_pinion_exact_and_limit():
    """Pinion prescribed: ground -k r_b2²- J2 -k_L- J_L, exact 2-DOF roots; with a mesh far
    stiffer than the load shaft the low mode tends to the load inertia on a clamped shaft,
    √(k_L/J_L) (Rao ch. 5; limit k_ground → ∞), relative error O(k_L/(k r_b2²))."""
    jl, kl = 8.0, 1.0e5
    for k_mesh in (50.0, 1.0e5):
        res = linear_modes(LinearSystem(structure(drive="speed", load_inertia_t_mm2=jl,
                                                  load_shaft_stiffness_Nmm_rad=kl), k_mesh))
        assert res.dofs == ("theta2_rad", "theta_L_rad")
        expected = two_dof_roots(J2, jl, k_mesh * RB2**2, kl)
        assert [m.natural_frequency_Hz for m in res.modes] == pytest.approx(
            [hz(w2) for w2 in expected], rel=1e-9)
    low = res.modes[0]  # mesh 1e5 N/mm: k r_b2² = 3.6e8 = 3600 k_L
    assert low.natural_frequency_Hz == pytest.approx(hz(kl / jl), rel=2e-3)
    assert low.description == "torsional: load shaft (load inertia against gear)"
    assert res.modes[1].description == "mesh mode (gear against the fixed-speed pinion)"


def test_full_chain_rigid_mode_and_load_dofs():
    s = structure(motor_inertia_t_mm2=3.0, drive_shaft_stiffness_Nmm_rad=1e6,
                  load_inertia_t_mm2=8.0, load_shaft_stiffness_Nmm_rad=1e6)
    res = linear_modes(LinearSystem(s, 1e4))
    assert res.dofs == ("theta_m_rad", "theta1_rad", "theta2_rad", "theta_L_rad")
    rigid = res.modes[0]
    assert rigid.rigid and sum(m.rigid for m in res.modes) == 1
    assert rigid.shape == pytest.approx((1.0, 1.0, 1.0, 1.0), rel=1e-9)  # equal r_b θ
    # elastic modes are M-orthogonal to the rigid one: no net angular momentum
    system = LinearSystem(s, 1e4)
    M, _, _ = system.matrices()
    scale = system.length_scales()  # shapes are reported as lengths: back to coordinates
    for m in res.elastic:
        assert (np.array(rigid.shape) / scale) @ M @ (np.array(m.shape) / scale) \
            == pytest.approx(0.0, abs=1e-9)


# --- dampers ------------------------------------------------------------------------------------
def test_load_terms_on_the_load_body_and_motor_curve_on_the_motor():
    s = structure(motor_inertia_t_mm2=3.0, drive_shaft_stiffness_Nmm_rad=1e6,
                  motor_no_load_speed_rad_s=200.0, load_inertia_t_mm2=8.0,
                  load_shaft_stiffness_Nmm_rad=1e6, load_viscous_Nmms_rad=5.0,
                  load_quadratic_Nmms2_rad2=0.5, pinion_bearing_damping_Nmms_rad=1.0,
                  gear_bearing_damping_Nmms_rad=2.0)
    c_m, c_q = linearised_dampers(s, drive_torque_Nmm=4.0e4, pinion_speed_rad_s=60.0)
    assert c_m == pytest.approx(4.0e4 / 200.0)  # T/ω0
    assert c_q == pytest.approx(2 * 0.5 * 60.0 * RB1 / RB2)  # 2 c_q |ω2|
    _, _, C = LinearSystem(s, 1e4, 0.0, c_m, c_q).matrices()
    assert np.diag(C) == pytest.approx([c_m, 1.0, 2.0, 5.0 + c_q])


def test_one_dof_damping_ratio_collects_every_gear_damper():
    """Prescribed pinion, load on the gear: one DOF, ζ = c_total / (2 √(k_a J2)) with
    c_total = c_mesh r_b2² + c2 + c_v + 2 c_q ω2 (Rao §2.6)."""
    k, c_mesh, c2, cv, cq, w1 = 1e4, 0.3, 4.0, 6.0, 0.2, 30.0
    s = structure(drive="speed", gear_bearing_damping_Nmms_rad=c2, load_viscous_Nmms_rad=cv,
                  load_quadratic_Nmms2_rad2=cq, pinion_bearing_damping_Nmms_rad=99.0)
    _, c_q = linearised_dampers(s, 0.0, w1)
    (mode,) = linear_modes(LinearSystem(s, k, c_mesh, 0.0, c_q)).modes
    c_total = c_mesh * RB2**2 + c2 + cv + 2 * cq * w1 * RB1 / RB2
    assert mode.damping_ratio == pytest.approx(c_total / (2 * math.sqrt(k * RB2**2 * J2)),
                                               rel=1e-9)


# --- lateral-torsional --------------------------------------------------------------------------
def test_mesh_vector_signs_static_load():
    """Static check of the frame and signs (structure.py): a load torque T on the gear with the
    pinion held gives the normal force F = T/r_b2 on the gear along +n_d, so the gear centre
    moves F n_d / k2 and the pinion centre -F n_d / k1 (isotropic bearings), δ = F / k_mesh."""
    k1, k2, k_mesh, torque = 3e5, 5e5, 2e4, 1e5
    system = LinearSystem(lateral(k1, k1, k2, k2, drive="speed"), k_mesh)
    assert system.dofs() == ("theta2_rad", "x1_mm", "y1_mm", "x2_mm", "y2_mm")
    _, K, _ = system.matrices()
    q = np.linalg.solve(K, np.array([-torque, 0, 0, 0, 0]))  # the load opposes θ2
    n = np.array(line_of_action(ALPHA, "drive"))
    f = torque / RB2
    assert q[3:5] == pytest.approx(f / k2 * n, rel=1e-9)
    assert q[1:3] == pytest.approx(-f / k1 * n, rel=1e-9)
    assert system.mesh_vector() @ q == pytest.approx(f / k_mesh, rel=1e-9)


def test_lateral_only_gears_on_bearings_with_soft_mesh():
    """Mesh 1 N/mm against bearings >= 4e5 N/mm: each centre vibrates on its own bearing,
    f = √(k/m)/2π. The mesh adds at most k_mesh to a bearing's stiffness: relative shift
    <= k_mesh / (2 k) ≈ 1.3e-6; tolerance 1e-5."""
    kx1, ky1, kx2, ky2 = 6e5, 8e5, 4e5, 1.5e6  # no two k/m equal
    res = linear_modes(LinearSystem(lateral(kx1, ky1, kx2, ky2, drive="speed"), 1.0))
    mesh, *lat = res.modes
    assert mesh.description == "mesh mode (gear against the fixed-speed pinion)"
    assert mesh.natural_frequency_Hz == pytest.approx(hz(1.0 * RB2**2 / J2), rel=1e-5)
    got = {m.description: m.natural_frequency_Hz for m in lat}
    assert got == pytest.approx({
        "lateral: pinion on its bearings (x)": hz(kx1 / M1),
        "lateral: pinion on its bearings (y)": hz(ky1 / M1),
        "lateral: gear on its bearings (x)": hz(kx2 / M2),
        "lateral: gear on its bearings (y)": hz(ky2 / M2)}, rel=1e-5)


def test_lateral_mesh_mode_lies_below_torsional_series_springs():
    """Equal x/y bearing stiffness: the bearings act in series with the mesh along the line of
    action (Kahraman & Singh 1991). With massless centres the lateral model's mesh mode is
    exactly √(k_eff r_b2²/J2)/2π, 1/k_eff = 1/k_mesh + 1/k1 + 1/k2; centre masses 1e-8 t
    shift it by O(m ω² / k) ~ 1e-6 (tolerance 1e-5). With real masses it lies lower still,
    well below the torsional mesh mode."""
    k1, k2, k_mesh = 2e5, 3e5, 1e5
    tors = linear_modes(LinearSystem(structure(drive="speed"), k_mesh)).modes[0]
    k_eff = 1.0 / (1 / k_mesh + 1 / k1 + 1 / k2)
    light = lateral(k1, k1, k2, k2, drive="speed", m1_t=1e-8, m2_t=1e-8)
    mesh = linear_modes(LinearSystem(light, k_mesh)).modes[0]
    assert mesh.natural_frequency_Hz == pytest.approx(hz(k_eff * RB2**2 / J2), rel=1e-5)
    real = linear_modes(LinearSystem(lateral(k1, k1, k2, k2, drive="speed"), k_mesh)).modes[0]
    assert real.natural_frequency_Hz < 0.95 * tors.natural_frequency_Hz
    # adding mass never raises an eigenvalue (Rayleigh quotient, Courant-Fischer min-max; Rao ch. 7)
    assert real.natural_frequency_Hz < mesh.natural_frequency_Hz
    assert tors.natural_frequency_Hz == pytest.approx(hz(k_mesh * RB2**2 / J2), rel=1e-12)


def test_lateral_torque_drive_rigid_rotation_has_no_translation():
    res = linear_modes(LinearSystem(lateral(3e5, 3e5, 5e5, 5e5), 1e4, 0.5))
    rigid = res.modes[0]
    assert res.dofs == ("theta1_rad", "theta2_rad", "x1_mm", "y1_mm", "x2_mm", "y2_mm")
    assert rigid.rigid and sum(m.rigid for m in res.modes) == 1
    assert rigid.shape == pytest.approx((1.0, 1.0, 0, 0, 0, 0), abs=1e-9)  # equal r_b θ
    assert rigid.description.startswith("rigid-body rotation (gears turn together")


def test_across_the_line_of_action_mode_is_undamped_and_uncoupled():
    """Isotropic bearings, no bearing damping: a centre moving perpendicular to n_d does not
    stretch the mesh, so it has √(k/m) exactly and ζ = 0 even with mesh damping."""
    res = linear_modes(LinearSystem(lateral(3e5, 3e5, 5e5, 5e5), 1e4, 50.0))
    across = [m for m in res.modes if "across the line of action" in m.description]
    assert {m.description for m in across} == {
        "lateral: pinion on its bearings (across the line of action)",
        "lateral: gear on its bearings (across the line of action)"}
    assert sorted(m.natural_frequency_Hz for m in across) == pytest.approx(
        sorted([hz(3e5 / M1), hz(5e5 / M2)]), rel=1e-9)
    assert all(m.damping_ratio == 0.0 for m in across)


def test_equal_gears_in_antiphase_along_the_line_of_action():
    """Equal centre masses m and isotropic bearings k, gear rotation nearly fixed (J2 x 1e6,
    pinion prescribed): the centres moving against each other along n_d stretch the mesh
    twice, ω² = (k + 2 k_mesh)/m (two masses on ground springs coupled by a spring, Rao ch. 5);
    the gear rotation shifts it by O(k_mesh r_b2²/(J2 ω²)) ~ 1e-7 (tolerance 1e-6)."""
    k, k_mesh = 3e5, 2e4
    s = lateral(k, k, k, k, drive="speed", m2_t=M1, J2_t_mm2=J2 * 1e6)
    res = linear_modes(LinearSystem(s, k_mesh))
    *_, anti = res.modes
    assert anti.description == ("lateral: both gears on their bearings, in antiphase "
                                "(along the line of action)")
    assert anti.natural_frequency_Hz == pytest.approx(hz((k + 2 * k_mesh) / M1), rel=1e-6)
    # in phase along n_d and both across n_d: three modes at √(k/m), shapes not unique
    triple = res.modes[1:4]
    assert [m.natural_frequency_Hz for m in triple] == pytest.approx([hz(k / M1)] * 3,
                                                                     rel=1e-9)
    assert all(m.description.endswith("[repeated frequency]") for m in triple)
    assert not anti.description.endswith("[repeated frequency]")


def test_heavily_damped_mesh_reports_damped_modes_consistently():
    """The seed's c_max (overdamped mesh) in the lateral model: non-proportional damping. Each
    underdamped mode reports its state-space root: f_d = f_n √(1 - ζ²) <= f_n, and the set of
    |λ|/2π of the complex roots is the set of reported natural frequencies."""
    from gearcli.pipeline.modal import run_modal

    res = run_modal(SEED, ["model=lateral-torsional"] + [
        f"bearings.{b}.stiffness_{d}=5e5" for b in ("pinion", "gear") for d in "xy"]).result
    under = [m for m in res.modes if m.damped_frequency_Hz is not None]
    for m in under:
        assert m.damped_frequency_Hz == pytest.approx(
            m.natural_frequency_Hz * math.sqrt(1 - m.damping_ratio**2), rel=1e-9)
    roots = sorted(abs(r) / (2 * math.pi) for r in res.eigenvalues if r.imag > 1e-6)
    assert roots == pytest.approx(sorted(m.natural_frequency_Hz for m in under), rel=1e-9)
    over = [m for m in res.modes if m.damping_ratio is not None and m.damping_ratio > 1]
    assert [m.description for m in over] == ["mesh mode (gear against the fixed-speed pinion)"]


@pytest.mark.parametrize("change, field", [
    ({"J2_t_mm2": 0.0}, "J2_t_mm2"),
    ({"m1_t": -1.0}, "m1_t"),
    ({"gear_support": Support(5e5, -1.0)}, "gear_support.stiffness_y_N_mm"),
    ({"pinion_support": None}, "pinion_support"),
    ({"load_inertia_t_mm2": 2.0}, "load_shaft_stiffness_Nmm_rad"),
])
def test_non_physical_system_rejected_naming_the_field(change, field):
    s = dataclasses.replace(lateral(3e5, 3e5, 5e5, 5e5), **change)
    with pytest.raises(ValueError, match=field.replace(".", r"\.")):
        linear_modes(LinearSystem(s, 1e4))


# --- pipeline: the same modes for simulate's summary --------------------------------------------
LATERAL = ["model=lateral-torsional", "bearings.pinion.stiffness_x=2e6",
           "bearings.pinion.stiffness_y=2e6", "bearings.gear.stiffness_x=2e6",
           "bearings.gear.stiffness_y=2e6 N/mm"]


def test_case_modes_and_summary_match_run_modal():
    from gearcli.case.load import load_case
    from gearcli.pipeline.geometry import run_geometry
    from gearcli.pipeline.mesh_input import case_mesh
    from gearcli.pipeline.modal import case_modes, modes_summary, run_modal

    loaded = load_case(SEED, LATERAL)
    geo = run_geometry(loaded)
    result = case_modes(loaded.case, geo, case_mesh(loaded.case, geo), geo.pinion_speed_rad_s)
    assert result.modes == run_modal(loaded).result.modes
    assert result.model == "lateral-torsional"
    summary = modes_summary(result)
    assert [set(m.to_dict()) for m in summary] == [
        {"mode", "natural_frequency_Hz", "damping_ratio", "description", "rigid_body"}
    ] * len(result.modes)
    assert [m.mode for m in summary] == list(range(1, len(summary) + 1))
    assert summary[0].natural_frequency_Hz == pytest.approx(result.modes[0]
                                                               .natural_frequency_Hz)


def test_seed_lateral_mesh_mode_below_torsional():
    """The seed with a light mesh damping: the bearings (2e6 N/mm) lower the mesh mode."""
    from gearcli.pipeline.modal import run_modal

    light = ["contact.max_damping=1"]
    tors = run_modal(SEED, light).result.modes[0]
    lat = run_modal(SEED, light + LATERAL).result
    mesh = min(lat.elastic, key=lambda m: m.natural_frequency_Hz)
    assert "mesh" in mesh.description
    assert mesh.natural_frequency_Hz < tors.natural_frequency_Hz


@pytest.mark.parametrize("zeta", [0.05, 3.0])
def test_free_pair_with_an_overdamped_mesh_keeps_its_mesh_mode(zeta):
    """Torque drive, both gears free: the state matrix has the defective double zero root of
    the rigid rotation, which round-off splits into a complex pair ~1e-8 of the largest root.
    With an overdamped mesh (no genuine complex pair left) that pair was taken for the mesh
    mode (the seed with a torque drive: "mode 2: 8.4e-06 Hz, ζ 7.7e-09"). Exact: one
    relative coordinate on the line of action, m_e = 1/(r_b1²/J1 + r_b2²/J2), ω² = k/m_e,
    ζ = c/(2√(k m_e)) (Rao, Mechanical Vibrations, §2.6), for ζ < 1 and ζ > 1 alike."""
    k = 1e4  # N/mm
    m_e = 1.0 / (RB1**2 / J1 + RB2**2 / J2)  # t
    c = 2.0 * zeta * math.sqrt(k * m_e)
    res = linear_modes(LinearSystem(structure(), k, c))
    assert [m.rigid for m in res.modes] == [True, False]
    mesh = res.modes[1]
    assert mesh.natural_frequency_Hz == pytest.approx(hz(k / m_e), rel=1e-9)
    assert mesh.damping_ratio == pytest.approx(zeta, rel=1e-9)
    # the round-off pair is no slow decay either (it set a 4.9 s steady window): the slowest
    # decay is the mesh mode's, ζω below ζ = 1, the slower real root ω(ζ - √(ζ² - 1)) above
    omega = math.sqrt(k / m_e)
    slowest = zeta * omega if zeta < 1 else omega * (zeta - math.sqrt(zeta**2 - 1))
    assert res.slowest_decay_rate_1_s() == pytest.approx(slowest, rel=1e-6)
