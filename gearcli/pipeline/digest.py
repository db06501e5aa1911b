"""The input digest of a run: what the case asks for at its final speed and load,
in the magnitudes a person checks at a glance, with a "did you mean" for implausible ones.

At the pinion speed ω1 (drive.speed's final value or drive.reference_speed) and the load torque
at the end of its ramps (the contact model's F_n = T_load/r_b2, docs/theory.md §7.3):

- F_t = F_n cos α on the reference circle [N], b = the narrower face width [mm];
- pitch-line velocity v = ω1 d1/2 on the reference circle [m/s] (ISO 6336-1, v);
- power P = F_t v [kW] (= T1 ω1);
- nominal contact stress σ_H0 = Z_ε Z_H Z_E √(F_t (u + 1)/(d1 b u)) [MPa]
  (ISO 6336-2:2019 eq. 4, spur; gearcli/model/rating.py);
- mesh frequency f_z = z1 ω1/(2π) [Hz], resonance ratio N = f_z/f_n against the run's mesh
  natural frequency f_n (the same ratio `gearcli mesh` sweeps).
"""

from __future__ import annotations

import math

from gearcli.results.run import InputDigest

#: F_t/b below this [N/mm] on a pair of module >= SLIP_MODULE_MM reads as a torque given in
#: N·mm that was meant in N·m (1000x): ISO 6336-1 line loads run from ~100 N/mm upwards.
SLIP_LINE_LOAD_N_MM = 1.0
SLIP_MODULE_MM = 5.0
#: A pitch-line velocity below this [m/s] reads as a speed in deg/s (or rad/s) meant in rpm.
SLIP_VELOCITY_M_S = 0.05


def input_digest(res) -> InputDigest:
    """The digest of a simulation run (pipeline.simulation.SimulationResult)."""
    from gearcli.model.rating import (
        contact_ratio_factor,
        elasticity_factor,
        nominal_contact_stress,
        zone_factor,
    )
    from gearcli.pipeline.mesh_input import static_force_N

    case, g = res.loaded.case, res.geometry.geometry
    # the key ω1 comes from: a torque drive has no drive.speed
    speed_key = ("drive", "reference_speed" if case.drive.type == "torque" else "speed")
    g1, g2 = g.pinion, g.gear
    omega1 = abs(res.geometry.pinion_speed_rad_s or 0.0)  # [rad/s]
    f_t = static_force_N(case, res.geometry) * math.cos(g.pressure_angle_rad)  # [N]
    b = min(g1.face_width_mm, g2.face_width_mm)
    v_m_s = omega1 * g1.d_mm / 2.0 / 1000.0
    u = g2.teeth / g1.teeth
    mats = [case.material_of("pinion"), case.material_of("gear")]
    z_e = elasticity_factor(mats[0].youngs_modulus, mats[0].poisson_ratio,
                            mats[1].youngs_modulus, mats[1].poisson_ratio)
    sigma = (contact_ratio_factor(g.eps_alpha)
             * nominal_contact_stress(max(f_t, 0.0), g1.d_mm, b, u,
                                      zone_factor(g.pressure_angle_rad, g.alpha_w_rad), z_e))
    f_z = g1.teeth * omega1 / (2.0 * math.pi)
    f_n = res.summary.mesh_natural_frequency_Hz
    ratio = f_z / f_n if f_n and math.isfinite(f_n) and f_n > 0 else math.nan
    return InputDigest(power_kW=f_t * v_m_s / 1000.0, pitch_line_velocity_m_s=v_m_s,
                       line_load_N_mm=f_t / b, sigma_H0_MPa=sigma, gear_mesh_frequency_Hz=f_z,
                       resonance_ratio=ratio,
                       warnings=tuple(slip_warnings(
                           f_t / b, v_m_s, g.module_mm, case.units,
                           (res.loaded.written_bare(("load", "torque")),
                            res.loaded.written_bare(speed_key)), ".".join(speed_key))))


def slip_warnings(line_load_N_mm: float, velocity_m_s: float, module_mm: float,
                  system: str | None = None, bare: tuple[bool, bool] = (True, True),
                  speed_key: str = "drive.speed") -> list[str]:
    """"Did you mean" warnings for a line load or a speed of an implausible magnitude, in the
    terms of the case's unit ``system`` (its ``units:`` key; None: "adams"): where bare torques
    are N·mm (adams) a tiny line load reads as N·m meant, where they are N·m already
    (engineering, si) it is only implausible; likewise a slow speed where bare speeds are not
    rpm (adams: deg/s, si: rad/s) or are (engineering). ``bare``: whether the torque and the
    speed were written without a unit (LoadedCase.written_bare); a value written with its unit
    is only implausible, never "did you mean". ``speed_key``: the key of the speed
    (drive.reference_speed for a torque drive)."""
    from gearcli import units

    torque_unit = units.in_system(units.TORQUE, system).default
    speed_unit = units.in_system(units.ANGULAR_VELOCITY, system).default
    torque_bare, speed_bare = bare
    out = []
    if 0.0 < line_load_N_mm < SLIP_LINE_LOAD_N_MM and module_mm >= SLIP_MODULE_MM:
        if not torque_bare:
            hint = "implausibly small for the pair, as written"
        elif torque_unit == "N*mm":
            hint = "did you mean N·m? bare torques read as N·mm (write the unit, e.g. '450 N*m')"
        else:
            hint = (f"implausibly small for the pair (bare torques are {torque_unit} in this "
                    "case; write the unit, e.g. '450 N*m')")
        out.append(f"load.torque: F_t/b = {line_load_N_mm:.3g} N/mm on a module "
                   f"{module_mm:g} mm pair: {hint}")
    if 0.0 < velocity_m_s < SLIP_VELOCITY_M_S:
        if not speed_bare:
            hint = "implausibly slow, as written"
        elif speed_unit == "rpm":
            hint = (f"implausibly slow (bare speeds are {speed_unit} in this case; write the "
                    "unit, e.g. '1500 rpm')")
        else:
            hint = (f"did you mean rpm? bare speeds read as {speed_unit} (write the unit, e.g. "
                    "'1500 rpm')")
        out.append(f"{speed_key}: a pitch-line velocity of {velocity_m_s:.3g} m/s: {hint}")
    return out
