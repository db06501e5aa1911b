"""Linearised mesh mode: stiffness, damping, natural frequency at the operating load.

docs/theory.md §4 and §6. The Adams IMPACT law per pair, F = k p^e + STEP(p, 0, 0, d_max, c_max) ṗ
(MSC Adams Solver, IMPACT function), linearised about the static deflection p_s that carries
the static normal force F_s shared by ε_α pairs on average:

    p_s = (F_s / (ε_α k))^(1/e),   k_pair = e k p_s^(e-1),   c_pair = STEP(p_s, 0, 0, d_max, c_max)
    k_mesh = ε_α k_pair,           c_mesh = ε_α c_pair

Mesh mode (2-DOF torsional, docs/theory.md §6): with a prescribed pinion speed only the gear moves,
m = J2 / r_b2²; with both gears free, m_e = 1 / (r_b1²/J1 + r_b2²/J2) (the rigid-body mode
has zero frequency). f_n = √(k_mesh/m)/2π, ζ = c_mesh / (2 √(k_mesh m)).
Units: N, mm, s, t (k in N/mm, c in N·s/mm, m in t = N·s²/mm).
"""

from __future__ import annotations

import math
from dataclasses import dataclass


def static_reference_N(load_torque_Nmm, r_b2_mm: float, omega2_rad_s,
                       damping: tuple[float, float]):
    """The dynamic factor's static force [N]: the torque the gear's side resists at a steady
    gear speed ω2 [rad/s], T_load + (c_v + c_2) |ω2| + c_q ω2² [N*mm] (the gear's equation of
    motion at constant speed, docs/theory.md §6.3, §7.3), over r_b2 [mm]. ``damping`` =
    (c_v + c_2 [N*mm*s/rad], c_q [N*mm*s²/rad²]), case.build.gear_side_damping. Scalars or
    arrays."""
    linear, quadratic = damping
    w = abs(omega2_rad_s)
    return (load_torque_Nmm + linear * w + quadratic * w * w) / r_b2_mm


def static_normal_force_N(load_torque_Nmm: float, r_b2_mm: float) -> float:
    """Static normal tooth force F_n,static = |T_load| / r_b2 [N] of a load torque [N*mm] on
    the gear with base radius r_b2 [mm] (docs/theory.md §7; the force acts along the line of action,
    tangent to the base circle)."""
    return abs(load_torque_Nmm) / r_b2_mm


@dataclass(frozen=True)
class MeshMode:
    """Linearised mesh at the operating load (internal units)."""

    static_force_N: float  #: F_s = T_load / r_b2, the contact model's operating load
    static_deflection_mm: float  #: p_s per pair
    pair_stiffness_N_mm: float  #: k_pair = e k p_s^(e-1), one pair
    mesh_stiffness_N_mm: float  #: mean over the mesh cycle, ε_α k_pair
    single_pair_stiffness_N_mm: float  #: one pair carrying F_s
    double_pair_stiffness_N_mm: float  #: two pairs sharing F_s
    mesh_damping_Ns_mm: float  #: ε_α c_pair
    modal_mass_t: float  #: equivalent mass along the line of action [t]
    natural_frequency_Hz: float
    damping_ratio: float

    @property
    def loaded_deflection_mm(self) -> float:
        """The static deflection under load, 0 without load (``static_deflection_mm`` is then
        the power law's linearisation point, 1 % of d_max: no deflection of the teeth)."""
        return self.static_deflection_mm if self.static_force_N > 0.0 else 0.0


def mesh_mode(
    static_force_N: float,
    eps_alpha: float,
    k: float,
    exponent: float,
    c_max: float,
    d_max: float,
    r_b1_mm: float,
    r_b2_mm: float,
    J1_t_mm2: float,
    J2_t_mm2: float,
    pinion_free: bool,
) -> MeshMode:
    """Linearised mesh stiffness, damping and the mesh mode (see the module docstring).

    At zero load the exponent-law stiffness vanishes (e > 1); the pair stiffness is then
    evaluated at a deflection of 1 % of d_max so that frequencies stay finite, and the caller
    should treat the result as indicative.
    """
    e = exponent
    f = max(static_force_N, 0.0)

    def deflection(force: float, pairs: float) -> float:
        p = (force / (pairs * k)) ** (1.0 / e) if force > 0.0 else 0.0
        return max(p, 0.01 * d_max) if e > 1.0 else p

    def stiffness(p: float) -> float:
        return e * k * p ** (e - 1.0) if e != 1.0 else k

    p_s = deflection(f, eps_alpha)
    k_pair = stiffness(p_s)
    k_mesh = eps_alpha * k_pair
    # Adams STEP (one implementation); imported here: it is compiled (numba), and readers of
    # static_reference_N (the report) need no numba
    from gearcli.core.stepfunc import step as adams_step

    c_mesh = eps_alpha * adams_step(p_s, 0.0, 0.0, d_max, c_max)
    if pinion_free:
        m = 1.0 / (r_b1_mm**2 / J1_t_mm2 + r_b2_mm**2 / J2_t_mm2)
    else:
        m = J2_t_mm2 / r_b2_mm**2
    omega = math.sqrt(k_mesh / m)
    return MeshMode(
        static_force_N=f,
        static_deflection_mm=p_s,
        pair_stiffness_N_mm=k_pair,
        mesh_stiffness_N_mm=k_mesh,
        single_pair_stiffness_N_mm=stiffness(deflection(f, 1.0)),
        double_pair_stiffness_N_mm=2.0 * stiffness(deflection(f, 2.0)),
        mesh_damping_Ns_mm=c_mesh,
        modal_mass_t=m,
        natural_frequency_Hz=omega / (2.0 * math.pi),
        damping_ratio=c_mesh / (2.0 * math.sqrt(k_mesh * m)),
    )


def with_mesh_stiffness(mode: MeshMode, k_mean_N_mm: float, k_single_N_mm: float,
                        k_double_N_mm: float) -> MeshMode:
    """``mode`` linearised with another mesh stiffness [N/mm] (the loaded contact's, docs/
    theory.md §4b): the same modal mass and damping ratio, so c_m = 2 ζ sqrt(k m), the static
    deflection F / k and f_n = sqrt(k/m)/(2π) follow it."""
    import dataclasses

    m = mode.modal_mass_t
    return dataclasses.replace(
        mode, mesh_stiffness_N_mm=k_mean_N_mm, single_pair_stiffness_N_mm=k_single_N_mm,
        double_pair_stiffness_N_mm=k_double_N_mm,
        static_deflection_mm=mode.static_force_N / k_mean_N_mm,
        mesh_damping_Ns_mm=2.0 * mode.damping_ratio * math.sqrt(k_mean_N_mm * m),
        natural_frequency_Hz=math.sqrt(k_mean_N_mm / m) / (2.0 * math.pi))


def tooth_mesh_mode(static_force_N: float, x_mm, k_N_mm, g_alpha_mm: float, p_b_mm: float,
                    damping_ratio: float, r_b1_mm: float, r_b2_mm: float, J1_t_mm2: float,
                    J2_t_mm2: float, pinion_free: bool) -> MeshMode:
    """The mesh mode of the tooth law (docs/theory.md §4b, §4c) from the pair stiffness k(x)
    [N/mm] on pinion roll positions x from A [mm] (rigid kinematics: a pair is in contact on
    0 <= x <= g_α).

    Mean mesh stiffness over a cycle k_mean = (1/p_b) ∫_0^{g_α} k(x) dx (the pairs one base
    pitch apart sum to it); single-pair zone g_α − p_b <= x <= p_b (B…D), double-pair zone the
    rest; mesh damping c_m = 2 ζ sqrt(k_mean m) (Kahraman & Singh 1990, J. Sound Vib.
    142:49-75), m as in :func:`mesh_mode`; static deflection F / k_mean.
    """
    import numpy as np

    x = np.asarray(x_mm, float)
    k = np.asarray(k_N_mm, float)
    fine = np.linspace(0.0, g_alpha_mm, 2001)
    k_fine = np.interp(fine, x, k)
    k_mean = float(np.sum((k_fine[1:] + k_fine[:-1]) * 0.5 * np.diff(fine))) / p_b_mm
    single = (fine >= g_alpha_mm - p_b_mm) & (fine <= p_b_mm)
    lead = fine <= g_alpha_mm - p_b_mm  # the double-pair zone seen from the leading pair
    # a contact ratio above 2 leaves no single-pair zone: not defined (NaN), not a warning
    k_single = float(k_fine[single].mean()) if single.any() else math.nan
    k_double = float((k_fine[lead] + np.interp(fine[lead] + p_b_mm, x, k)).mean()) \
        if lead.any() else math.nan
    if pinion_free:
        m = 1.0 / (r_b1_mm**2 / J1_t_mm2 + r_b2_mm**2 / J2_t_mm2)
    else:
        m = J2_t_mm2 / r_b2_mm**2
    c_m = 2.0 * damping_ratio * math.sqrt(k_mean * m)
    f = max(static_force_N, 0.0)
    return MeshMode(
        static_force_N=f,
        static_deflection_mm=f / k_mean,
        pair_stiffness_N_mm=float(k_fine.mean()),
        mesh_stiffness_N_mm=k_mean,
        single_pair_stiffness_N_mm=k_single,
        double_pair_stiffness_N_mm=k_double,
        mesh_damping_Ns_mm=c_m,
        modal_mass_t=m,
        natural_frequency_Hz=math.sqrt(k_mean / m) / (2.0 * math.pi),
        damping_ratio=damping_ratio,
    )
