"""The case's :class:`gearcli.model.structure.Structure`: built once, used by simulate and modal."""

from __future__ import annotations

from gearcli.case.load import LoadedCase
from gearcli.case.schema import Case
from gearcli.model.structure import Structure, Support
from gearcli.pipeline.geometry import GeometryResult


def _support(bearing) -> Support:
    return Support(bearing.stiffness_x, bearing.stiffness_y, bearing.damping_x,
                   bearing.damping_y)


def build_structure(case: Case, geo: GeometryResult) -> Structure:
    """Bodies, shafts and supports of a validated case with checked geometry (internal units)."""
    g, dr, ld, br = geo.geometry, case.drive, case.load, case.bearings
    lateral = case.model == "lateral-torsional"
    return Structure(
        model=case.model,
        drive=dr.type,
        J1_t_mm2=geo.mass[0].inertia_t_mm2,
        J2_t_mm2=geo.mass[1].inertia_t_mm2,
        m1_t=geo.mass[0].mass_t,
        m2_t=geo.mass[1].mass_t,
        r_b1_mm=g.pinion.r_b_mm,
        r_b2_mm=g.gear.r_b_mm,
        alpha_w_rad=g.alpha_w_rad,
        drive_shaft_stiffness_Nmm_rad=dr.shaft.stiffness if dr.shaft else 0.0,
        drive_shaft_damping_Nmms_rad=dr.shaft.damping if dr.shaft else 0.0,
        motor_inertia_t_mm2=dr.motor_inertia or 0.0,
        motor_no_load_speed_rad_s=dr.motor_curve.no_load_speed if dr.motor_curve else 0.0,
        load_shaft_stiffness_Nmm_rad=ld.shaft.stiffness if ld.shaft else 0.0,
        load_shaft_damping_Nmms_rad=ld.shaft.damping if ld.shaft else 0.0,
        load_inertia_t_mm2=ld.inertia or 0.0,
        load_viscous_Nmms_rad=ld.viscous,
        load_quadratic_Nmms2_rad2=ld.quadratic,
        pinion_bearing_damping_Nmms_rad=br.pinion.damping,
        gear_bearing_damping_Nmms_rad=br.gear.damping,
        pinion_support=_support(br.pinion) if lateral else None,
        gear_support=_support(br.gear) if lateral else None,
    )


def refuse_unsupported(loaded: LoadedCase) -> None:
    """Located case error for what the model cannot describe yet (simulate and modal)."""
    if loaded.case.load.applied_to == "pinion":
        raise loaded.error(("load", "applied_to"), "a load on the pinion is not supported by "
                           "the model yet; apply it to the gear", "pinion", True)
